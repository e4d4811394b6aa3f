// `sphclip compare` as a CI gate (docs: "Image checks in CI"): its default
// limits fail on the local regressions users reported (a colour bar whose
// labels changed, a small square added, an erased tick label) on real
// 1280x720 frames, yet pass the same frame through EGL and OSMesa and
// through a PNG round trip; the JSON report; folder mode; --update.

#include "output/png_io.hpp"
#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"
#include "support/text.hpp"

#include <catch2/catch.hpp>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sph::test::read_text;
using sph::test::run_sphclip;
using sph::test::TempFolder;

using sph::test::contains;

// The first frame of the shipped tank at rest, 1280x720, with the colour
// bar's range and the backend given: the fluid is one colour, so a change of
// range changes only the bar's labels.
fs::path tank_frame(const TempFolder& tmp, const std::string& name, double range_top,
                    const std::string& backend = "auto") {
    const fs::path out = tmp / name;
    const auto result =
        run_sphclip(tmp, {"run", std::string(SPHCLIP_SOURCE_DIR) + "/scenes/hydrostatic_2d.json",
                          "--out", out.string(), "--quiet", "--no-mp4", "--threads", "1",
                          "--duration", "0.001", "--fps", "1000", "--backend", backend, "--set",
                          "render.range=[0," + std::to_string(range_top) + "]"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    return out / "frames" / "frame_00000.png";
}

json compare_json(const TempFolder& tmp, const std::vector<std::string>& args, int& exit_code) {
    std::vector<std::string> full{"compare"};
    full.insert(full.end(), args.begin(), args.end());
    full.push_back("--json");
    const auto result = run_sphclip(tmp, full);
    exit_code = result.exit_code;
    // The JSON report is stdout; a sentence on stderr may follow it.
    const auto end = result.output.rfind("\n}");
    INFO(result.output);
    REQUIRE(end != std::string::npos);
    return json::parse(result.output.substr(0, end + 2));
}

void fill(sph::Image& image, int x0, int y0, int x1, int y1, const std::uint8_t* colour) {
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
            std::copy(colour, colour + 4, image.pixel(x, y));
}

} // namespace

TEST_CASE("compare's defaults fail on local regressions of a real frame", "[compare][cli]") {
    TempFolder tmp;
    const fs::path reference = tank_frame(tmp, "ref", 0.05);
    const sph::Image frame = sph::read_png(reference);
    REQUIRE(frame.width == 1280);
    REQUIRE(frame.height == 720);
    int exit_code = -1;

    SECTION("the colour bar's labels changed (range 0.05 -> 0.06)") {
        const fs::path relabelled = tank_frame(tmp, "relabelled", 0.06);
        const json report = compare_json(tmp, {reference.string(), relabelled.string()}, exit_code);
        CHECK(exit_code == 1);
        CHECK(report.at("match") == false);
        CHECK(report.at("metrics").at("different_pixels").get<int>() > 16);
        // Only the bar's labels, on the right of the tank.
        CHECK(report.at("metrics").at("different_box").at("x_min").get<int>() > 1000);
        // The percentage alone would pass it: that is why --max-pixels exists.
        CHECK(report.at("metrics").at("different_percent").get<double>() < 0.5);
    }
    SECTION("a 20x20 red square added") {
        sph::Image changed = frame;
        const std::uint8_t red[4] = {255, 0, 0, 255};
        fill(changed, 600, 300, 619, 319, red);
        sph::write_png(tmp / "square.png", changed);
        const json report =
            compare_json(tmp, {reference.string(), (tmp / "square.png").string()}, exit_code);
        CHECK(exit_code == 1);
        const json& metrics = report.at("metrics");
        CHECK(metrics.at("different_pixels") == 400);
        CHECK(metrics.at("largest_cluster") == 400);
        CHECK(metrics.at("different_box") ==
              json{{"x_min", 600}, {"y_min", 300}, {"x_max", 619}, {"y_max", 319}});
        CHECK(report.at("limits").at("max_pixels") == 16);
        // Allowed explicitly, it passes; one pixel fewer allowed, it fails.
        compare_json(tmp,
                     {reference.string(), (tmp / "square.png").string(), "--max-pixels", "400"},
                     exit_code);
        CHECK(exit_code == 0);
        compare_json(tmp,
                     {reference.string(), (tmp / "square.png").string(), "--max-pixels", "399"},
                     exit_code);
        CHECK(exit_code == 1);
    }
    SECTION("a tick label erased") {
        // The "0.03" label sits beside the bar a little above mid-height;
        // paint it over with the background, read from the frame's corner.
        sph::Image changed = frame;
        const std::uint8_t* background = frame.pixel(1270, 710);
        fill(changed, 1040, 312, 1095, 340, background);
        sph::write_png(tmp / "erased.png", changed);
        const auto result =
            run_sphclip(tmp, {"compare", reference.string(), (tmp / "erased.png").string()});
        INFO(result.output);
        CHECK(result.exit_code == 1);
        CHECK(contains(result.output, "match=no"));
        CHECK(contains(result.output, "above --max-pixels 16"));
        CHECK(contains(result.output, "the differing pixels lie in x 1"));
    }
}

TEST_CASE("compare's defaults pass the same frame through both backends and a PNG round trip",
          "[compare][cli]") {
    TempFolder tmp;
    const fs::path egl = tank_frame(tmp, "egl", 0.05, "egl");
    const fs::path osmesa = tank_frame(tmp, "osmesa", 0.05, "osmesa");
    int exit_code = -1;
    const json report = compare_json(tmp, {egl.string(), osmesa.string()}, exit_code);
    CHECK(exit_code == 0);
    CHECK(report.at("match") == true);
    CHECK(report.at("reasons").empty());

    // Decoded and written again: the pixels survive, the bytes need not.
    sph::write_png(tmp / "again.png", sph::read_png(egl));
    const json again = compare_json(tmp, {egl.string(), (tmp / "again.png").string()}, exit_code);
    CHECK(exit_code == 0);
    CHECK(again.at("metrics").at("different_pixels") == 0);
    CHECK(again.at("metrics").at("different_box").is_null());
    CHECK(again.at("metrics").at("psnr_db").is_null()); // identical: no finite PSNR
}

TEST_CASE("compare pairs two folders by file name and reports what is missing or extra",
          "[compare][cli]") {
    TempFolder tmp;
    sph::Image plain(16, 8), changed(16, 8);
    std::fill(plain.rgba.begin(), plain.rgba.end(), std::uint8_t(200));
    changed = plain;
    const std::uint8_t black[4] = {0, 0, 0, 255};
    fill(changed, 2, 2, 7, 6, black); // 30 pixels
    fs::create_directories(tmp / "ref" / "sub");
    fs::create_directories(tmp / "test" / "sub");
    sph::write_png(tmp / "ref" / "a.png", plain);
    sph::write_png(tmp / "ref" / "sub" / "b.png", plain);
    sph::write_png(tmp / "ref" / "c.png", plain);
    sph::write_png(tmp / "test" / "a.png", plain);
    sph::write_png(tmp / "test" / "sub" / "b.png", changed);
    sph::write_png(tmp / "test" / "d.png", plain);
    const std::string ref = (tmp / "ref").string(), test = (tmp / "test").string();

    const auto text = run_sphclip(tmp, {"compare", ref, test, "--diff", (tmp / "diffs").string()});
    INFO(text.output);
    CHECK(text.exit_code == 1);
    CHECK(contains(text.output, "sub/b.png: mean_difference="));
    CHECK(contains(text.output, "c.png: missing from " + test));
    CHECK(contains(text.output, "d.png: extra in " + test));
    CHECK(contains(text.output, "compared 2 pairs: 1 match, 1 differ; 1 missing, 1 extra"));
    CHECK_FALSE(contains(text.output, "a.png: ")); // matching pairs are not listed
    // Difference images only for the pairs that differ.
    CHECK(fs::exists(tmp / "diffs" / "sub" / "b.png"));
    CHECK_FALSE(fs::exists(tmp / "diffs" / "a.png"));

    int exit_code = -1;
    const json report = compare_json(tmp, {ref, test}, exit_code);
    CHECK(exit_code == 1);
    CHECK(report.at("missing") == json{"c.png"});
    CHECK(report.at("extra") == json{"d.png"});
    CHECK(report.at("summary").at("compared") == 2);
    CHECK(report.at("summary").at("differ") == 1);
    REQUIRE(report.at("pairs").size() == 2);
    CHECK(report.at("pairs")[1].at("name") == "sub/b.png");
    CHECK(report.at("pairs")[1].at("metrics").at("different_pixels") == 30);

    // Blessing: the changed and the new image become references; the
    // reference with no test image is kept, not deleted.
    const auto update = run_sphclip(tmp, {"compare", ref, test, "--update"});
    INFO(update.output);
    CHECK(update.exit_code == 0);
    CHECK(contains(update.output, "2 references updated"));
    CHECK(read_text(tmp / "ref" / "sub" / "b.png") == read_text(tmp / "test" / "sub" / "b.png"));
    CHECK(read_text(tmp / "ref" / "d.png") == read_text(tmp / "test" / "d.png"));
    CHECK(fs::exists(tmp / "ref" / "c.png"));
    const json after = compare_json(tmp, {ref, test}, exit_code);
    CHECK(exit_code == 1); // c.png is still missing from the test folder
    CHECK(after.at("summary").at("differ") == 0);
    CHECK(after.at("missing") == json{"c.png"});
    CHECK(after.at("extra").empty());
}

TEST_CASE("compare --update blesses a single image, and a folder against a file is bad input",
          "[compare][cli]") {
    TempFolder tmp;
    sph::Image plain(8, 8), changed(8, 8);
    std::fill(plain.rgba.begin(), plain.rgba.end(), std::uint8_t(100));
    changed = plain;
    const std::uint8_t white[4] = {255, 255, 255, 255};
    fill(changed, 0, 0, 7, 7, white);
    sph::write_png(tmp / "ref.png", plain);
    sph::write_png(tmp / "test.png", changed);
    const std::string ref = (tmp / "ref.png").string(), test = (tmp / "test.png").string();

    const auto update = run_sphclip(tmp, {"compare", ref, test, "--update"});
    INFO(update.output);
    CHECK(update.exit_code == 0);
    CHECK(contains(update.output, "match=no"));
    CHECK(contains(update.output, "updated " + ref));
    CHECK(read_text(tmp / "ref.png") == read_text(tmp / "test.png"));
    CHECK(run_sphclip(tmp, {"compare", ref, test}).exit_code == 0);

    const auto mixed = run_sphclip(tmp, {"compare", tmp.path().string(), test});
    CHECK(mixed.exit_code == 2);
    CHECK(contains(mixed.output, "is a folder and"));
}
