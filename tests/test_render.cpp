// The renderer: both headless backends make a GL 4.5 context and draw the
// same picture (STYLE.md point 13), frames match the golden images under
// tests/golden/, impostors look like the seed's meshes, and images are the
// right way up. Set SPHCLIP_UPDATE_GOLDEN=1 to rewrite the golden images
// (then look at them before committing).
#include "output/image_compare.hpp"
#include "output/png_io.hpp"
#include "render/colour_maps.hpp"
#include "render/frame_renderer.hpp"
#include "render/gl_context.hpp"
#include "render/sphere_geometry.hpp"
#include "scene/scene_setup.hpp"
#include "support/golden_frames.hpp"
#include "support/temp_folder.hpp"

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sys/wait.h>
#include <unistd.h>

using namespace sph;
using sph::test::check_against_golden;
using sph::test::render_scene;
namespace fs = std::filesystem;

namespace {

// The spheres style's tiny scene: impostors, or the seed's meshes.
Scene tiny_scene(int dimension, const std::string& spheres = "impostor",
                 const std::vector<Override>& more = {}) {
    std::vector<Override> o{{"render.spheres", spheres}};
    o.insert(o.end(), more.begin(), more.end());
    return test::tiny_scene(dimension, o);
}

} // namespace

TEST_CASE("both headless backends give an OpenGL 4.5 core context", "[render]") {
    for (const char* backend : {"egl", "osmesa"}) {
        INFO(backend);
        const auto context = make_gl_context(backend);
        CHECK(context->info().backend == backend);
        CHECK_FALSE(context->info().renderer.empty());
        CHECK(context->info().version.find("4.") != std::string::npos);
    }
    // auto tries EGL first, and EGL works here.
    CHECK(make_gl_context("auto")->info().backend == "egl");
}

TEST_CASE("EGL and OSMesa draw the same frame", "[render]") {
    for (int dimension : {2, 3}) {
        const Scene scene = tiny_scene(dimension);
        const Image egl = render_scene(scene, "egl");
        const Image osmesa = render_scene(scene, "osmesa");
        const CompareResult result = compare_images(egl, osmesa, CompareOptions{});
        INFO("dimension " << dimension << ": mean difference " << result.mean_difference);
        CHECK(result.match);
    }
}

TEST_CASE("frames match the golden images, with either backend", "[render]") {
    for (const char* backend : {"egl", "osmesa"}) {
        INFO(backend);
        check_against_golden(render_scene(tiny_scene(2), backend), "tiny_2d");
        check_against_golden(render_scene(tiny_scene(3), backend), "tiny_3d");
        check_against_golden(render_scene(tiny_scene(3, "impostor",
                                                     {{"render.shadows", "true"},
                                                      {"render.ambient_occlusion", "true"}}),
                                          backend),
                             "tiny_3d_lit");
        // Each of light and depth's switches off, on the dark palette.
        check_against_golden(render_scene(tiny_scene(3, "impostor",
                                                     {{"render.shadows", "false"},
                                                      {"render.ambient_occlusion", "false"},
                                                      {"render.floor", "false"},
                                                      {"render.tank", "false"},
                                                      {"render.background", "dark"}}),
                                          backend),
                             "tiny_3d_plain");
        check_against_golden(
            render_scene(tiny_scene(2, "impostor", {{"render.background", "dark"}}), backend),
            "tiny_2d_dark");
        // The overlay's text lines: a title and a caption of the user's,
        // UTF-8 with Greek and superscripts, in the band above the scene.
        check_against_golden(
            render_scene(tiny_scene(2, "impostor",
                                    {{"render.title", "Two blocks — ρ₀ 1000 kg/m³"},
                                     {"render.caption", "t = {time} s · {steps} steps"}}),
                         backend),
            "tiny_2d_titled");
    }
}

TEST_CASE("a close camera beside the tank sees the fluid, not a pane of glass", "[render]") {
    // scenes/zero_gravity_drop_3d.json frames the drop (fit = fluid) from
    // just outside the tank's front wall, inside its other walls' slabs.
    // The front wall stood between the camera and the fluid and covered the
    // whole scene as a pale pane (mean difference 4.7 against the frame
    // without the tank); only the walls behind the fluid are drawn now
    // (0.5: the side wall the camera sees from inside, at the frame's edge).
    const fs::path file = fs::path(SPHCLIP_SOURCE_DIR) / "scenes" / "zero_gravity_drop_3d.json";
    const Scene glass = load_scene(file, {{"render.size", "[240,180]"}});
    const Scene none = load_scene(file, {{"render.size", "[240,180]"}, {"render.tank", "false"}});
    const CompareResult result =
        compare_images(render_scene(none, "osmesa"), render_scene(glass, "osmesa"), {});
    INFO("mean difference " << result.mean_difference);
    CHECK(result.mean_difference < 1.5);
}

TEST_CASE("impostors look like the seed's meshes", "[render]") {
    for (int dimension : {2, 3}) {
        const Image impostor = render_scene(tiny_scene(dimension, "impostor"), "auto");
        const Image mesh = render_scene(tiny_scene(dimension, "mesh"), "auto");
        // An 80-triangle sphere is faceted: the same picture up to its edges,
        // which differ all round every sphere (a share, not a count).
        const CompareResult result = compare_images(impostor, mesh,
                                                    {.max_mean_difference = 4.0,
                                                     .pixel_threshold = 64,
                                                     .max_different_percent = 3.0,
                                                     .max_different_pixels = std::uint64_t(-1)});
        INFO("dimension " << dimension << ": mean difference " << result.mean_difference
                          << ", different " << result.different_percent << "%");
        CHECK(result.match);
    }
}

TEST_CASE("images are the right way up and particles where they belong", "[render]") {
    // One block in the top left corner of a 2D domain.
    const Scene scene = default_scene({{"render.size", "[200,200]"},
                                       {"domain.max", "[0.1,0.1]"},
                                       {"fluid.spacing", "0.004"},
                                       {"fluid.blocks", R"([{"min":[0,0.07],"max":[0.03,0.1]}])"}});
    const Image image = render_scene(scene, "auto");
    REQUIRE(image.width == 200);
    // Speed 0 is the low end of viridis, purple: count purple pixels (the
    // caption, box and background are grey) in the upper and lower halves.
    const auto low = colour_map_table("viridis", 256)[0];
    REQUIRE(low[2] > low[1] + 30);
    auto purple = [&](int y0, int y1) {
        int count = 0;
        for (int y = y0; y < y1; ++y)
            for (int x = 0; x < 120; ++x) {
                const std::uint8_t* p = image.pixel(x, y);
                count += p[2] > p[1] + 30 && p[0] > p[1];
            }
        return count;
    };
    const int upper = purple(0, 100), lower = purple(100, 200);
    INFO("purple pixels: upper " << upper << ", lower " << lower);
    CHECK(upper > 300);
    CHECK(lower == 0);
}

TEST_CASE("colour maps run from their low to their high end", "[render]") {
    for (const auto& name : colour_map_names()) {
        const auto table = colour_map_table(name, 256);
        REQUIRE(table.size() == 256);
        auto luminance = [](const Rgb8& c) {
            return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
        };
        if (name == "viridis") // sequential: brightness rises throughout
            for (int i = 1; i < 256; ++i)
                CHECK(luminance(table[i]) >= luminance(table[i - 1]) - 0.5);
        if (name == "diverging") { // blue, grey in the middle, red
            CHECK(table[0][2] > table[0][0]);
            CHECK(table[255][0] > table[255][2]);
            const auto mid = table[128];
            CHECK(std::abs(int(mid[0]) - int(mid[2])) < 20);
        }
    }
    CHECK_THROWS_AS(colour_map_table("jet"), std::invalid_argument);
}

namespace {

// WCAG 2's relative luminance of an sRGB colour (components 0-1) and the
// contrast ratio of two colours, 1 (none) to 21 (black on white).
double relative_luminance(double r, double g, double b) {
    auto linear = [](double c) {
        return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
    };
    return 0.2126 * linear(r) + 0.7152 * linear(g) + 0.0722 * linear(b);
}
double contrast(const Rgb8& a, const Rgb8& b) {
    const double la = relative_luminance(a[0] / 255.0, a[1] / 255.0, a[2] / 255.0);
    const double lb = relative_luminance(b[0] / 255.0, b[1] / 255.0, b[2] / 255.0);
    return (std::max(la, lb) + 0.05) / (std::min(la, lb) + 0.05);
}

} // namespace

TEST_CASE("every colour map's dark end stays visible on the default backdrop", "[render]") {
    // Every particle below the range, so the whole fluid is drawn in the
    // map's low end (viridis' purple, turbo's navy); no caption.
    for (const auto& name : colour_map_names()) {
        for (const char* background : {"light", "dark"}) {
            INFO(name << " on " << background);
            const Image image = render_scene(tiny_scene(2, "impostor",
                                                        {{"render.colour_map", name},
                                                         {"render.range", "[5,6]"},
                                                         {"render.caption", ""},
                                                         {"render.background", background}}),
                                             "auto");
            const Rgb8 low = colour_map_table(name, 256).front();
            auto pixel = [&](int x, int y) {
                const std::uint8_t* p = image.pixel(x, y);
                return Rgb8{p[0], p[1], p[2]};
            };
            // The discs show the map's own colour (linear light, sRGB out: a
            // disc's middle gets about the bar's colour), not a darker one.
            int shown = 0;
            for (int y = 0; y < image.height; ++y)
                for (int x = 0; x < image.width; ++x) {
                    const Rgb8 c = pixel(x, y);
                    int d = 0;
                    for (int k = 0; k < 3; ++k)
                        d = std::max(d, std::abs(int(c[k]) - int(low[k])));
                    shown += d <= 24;
                }
            CHECK(shown > 200);
            // Against the backdrop at its darkest (the image's bottom row,
            // outside the scene), at least 3:1 (WCAG's least for graphics);
            // the dark backdrop, the look before, loses viridis' purple.
            const double c = contrast(low, pixel(0, image.height - 1));
            INFO("contrast " << c);
            if (std::string(background) == "light")
                CHECK(c >= 3.0);
            else if (name == "viridis")
                CHECK(c < 3.0);
        }
    }
}

TEST_CASE("icospheres are closed unit spheres", "[render]") {
    for (int subdivisions : {0, 1, 2}) {
        const SphereMesh mesh = make_icosphere(subdivisions);
        CHECK(mesh.indices.size() / 3 == std::size_t(20 * std::pow(4, subdivisions)));
        // Closed surface: V - E + F = 2, with E = 3F / 2.
        const std::size_t faces = mesh.indices.size() / 3;
        CHECK(mesh.vertices.size() + faces - 3 * faces / 2 == 2);
        for (const auto& v : mesh.vertices)
            CHECK(std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) == Approx(1).epsilon(1e-6));
    }
}

namespace {

// Runs the program through the shell; returns its exit code.
int run_program(const std::string& arguments, const fs::path& log) {
    const std::string command = "OMP_WAIT_POLICY=passive " + std::string(SPHCLIP_EXE) + " " +
                                arguments + " > '" + log.string() + "' 2>&1";
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

const char* tiny_clip = R"({
    "domain": {"min": [0, 0], "max": [0.1, 0.06]},
    "fluid": {"spacing": 0.004, "blocks": [{"min": [0, 0], "max": [0.04, 0.04]}]},
    "duration": 0.1, "fps": 20,
    "render": {"size": [161, 91]}
})";

} // namespace

TEST_CASE("run writes a PNG per frame and an MP4, and records the GL context", "[render][cli]") {
    sph::test::TempFolder tmp;
    sph::test::write_text(tmp / "tiny.json", tiny_clip);
    const fs::path out = tmp.path() / "out";
    REQUIRE(run_program("run '" + (tmp.path() / "tiny.json").string() + "' --quiet --out '" +
                            out.string() + "'",
                        tmp.path() / "log") == 0);
    // 0.1 s at 20 fps: frames 0..2; odd image sizes are fine.
    for (int k = 0; k < 3; ++k) {
        const fs::path png = out / "frames" / ("frame_0000" + std::to_string(k) + ".png");
        REQUIRE(fs::exists(png));
        const Image image = read_png(png);
        CHECK(image.width == 161);
        CHECK(image.height == 91);
    }
    CHECK_FALSE(fs::exists(out / "frames" / "frame_00003.png"));
    CHECK(fs::exists(out / "clip.mp4"));
    CHECK(fs::file_size(out / "clip.mp4") > 1000);
    CHECK_FALSE(fs::exists(out / "clip.mp4.partial"));
    std::ifstream in(out / "run.json");
    const std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(json.find("\"backend\": \"egl\"") != std::string::npos);
    CHECK(json.find("\"render_s\"") != std::string::npos);
    CHECK(json.find("\"readback_s\"") != std::string::npos);
    CHECK(json.find("\"encode_s\"") != std::string::npos);
    CHECK(json.find("\"simulate_s\"") != std::string::npos);
    // The stage table counts drawing and encoding too.
    for (const char* stage : {"render", "readback", "encode", "neighbour search"})
        CHECK(json.find(std::string("\"name\": \"") + stage + "\"") != std::string::npos);
}

TEST_CASE("no GL context: exit 4, nothing written; data-only runs need no GL", "[render][cli]") {
    sph::test::TempFolder tmp;
    const fs::path out = tmp.path() / "out";
    // An EGL vendor list that names nothing: libglvnd finds no EGL driver.
    const std::string no_egl = "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent ";
    const std::string run = "run --duration 0.01 --quiet --out '" + out.string() + "'";
    const int status = std::system((no_egl + SPHCLIP_EXE + " " + run + " --backend egl > '" +
                                    (tmp.path() / "log").string() + "' 2>&1")
                                       .c_str());
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 4);
    std::ifstream in(tmp.path() / "log");
    const std::string log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(log.find("EGL") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
    const int data_only = std::system(
        (no_egl + SPHCLIP_EXE + " " + run + " --backend egl --no-png --no-mp4 > /dev/null 2>&1")
            .c_str());
    CHECK(WEXITSTATUS(data_only) == 0);
    CHECK(fs::exists(out / "stats.csv"));
}

TEST_CASE("an interrupted run still finalises its video", "[render][cli]") {
    sph::test::TempFolder tmp;
    sph::test::write_text(tmp / "tiny.json", tiny_clip);
    const fs::path out = tmp.path() / "out";
    // A long clip, stopped once its second frame is on disk.
    const std::string command =
        "OMP_WAIT_POLICY=passive " + std::string(SPHCLIP_EXE) + " run '" +
        (tmp.path() / "tiny.json").string() + "' --duration 1000 --quiet --out '" + out.string() +
        "' > /dev/null 2>&1 & pid=$!; n=0; while [ ! -e '" +
        (out / "frames" / "frame_00002.png").string() +
        "' ] && [ $n -lt 600 ]; do sleep 0.05; n=$((n+1)); done; kill -TERM $pid; wait $pid";
    const int status = std::system(command.c_str());
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
    CHECK(fs::exists(out / "clip.mp4"));
    CHECK_FALSE(fs::exists(out / "clip.mp4.partial"));
    CHECK(fs::file_size(out / "clip.mp4") > 1000);
}
