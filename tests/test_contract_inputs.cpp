// The input contract (docs: "Input limits"): sphclip reads only regular
// files, each kind within its size limit, says which file and which limit
// when it refuses one, and never writes over a file it reads.

#include "analysis/csv_table.hpp"
#include "output/files.hpp"
#include "output/png_io.hpp"
#include "render/gl_context.hpp"
#include "render/text.hpp"
#include "scene/input_error.hpp"
#include "scene/obj_mesh.hpp"
#include "scene/scene.hpp"
#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"
#include "support/text.hpp"

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <optional>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>
#include <vector>

namespace {

namespace fs = std::filesystem;

// A small 2D tank: 36 particles, quick frames.
const std::string small_tank = R"({
    "domain": {"min": [0, 0], "max": [0.1, 0.1]},
    "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.03, 0.03]}]},
    "render": {"size": [64, 64]},
    "duration": 0.05, "fps": 40
})";
using sph::test::read_text;
using sph::test::run_sphclip;
using sph::test::TempFolder;
using sph::test::write_text;

using sph::test::contains;

// The reason read_input_file gives for `path`, or "" when it reads it.
std::string refusal(const fs::path& path, const sph::InputLimit& limit) {
    try {
        sph::read_input_file(path, limit);
        return "";
    } catch (const sph::FileReadError& e) {
        return e.reason;
    }
}

// A 2x2 PNG whose header then claims `width` x `height`.
std::string png_claiming(std::uint32_t width, std::uint32_t height, const TempFolder& tmp) {
    sph::Image small(2, 2);
    std::fill(small.rgba.begin(), small.rgba.end(), std::uint8_t(255));
    sph::write_png(tmp / "small.png", small);
    std::string bytes = read_text(tmp / "small.png");
    // IHDR's width and height follow the 8-byte signature, the chunk's length and type.
    for (int k = 0; k < 4; ++k) {
        bytes[16 + k] = char((width >> (24 - 8 * k)) & 0xff);
        bytes[20 + k] = char((height >> (24 - 8 * k)) & 0xff);
    }
    return bytes;
}

} // namespace

TEST_CASE("inputs: only regular files are read, whatever the path looks like",
          "[contract][inputs]") {
    TempFolder tmp;
    const sph::InputLimit limit{"test file", 1000};
    write_text(tmp / "ok.txt", "hello");
    CHECK(sph::read_input_file(tmp / "ok.txt", limit) == "hello");
    // A symlink to a regular file is that file.
    fs::create_symlink(tmp / "ok.txt", tmp / "link.txt");
    CHECK(sph::read_input_file(tmp / "link.txt", limit) == "hello");

    // A device that never ends, directly or through a symlink, is refused
    // before one byte is read.
    CHECK(contains(refusal("/dev/zero", limit), "not a regular file"));
    fs::create_symlink("/dev/zero", tmp / "zero.txt");
    CHECK(contains(refusal(tmp / "zero.txt", limit), "not a regular file"));
    // A FIFO with no writer: refused at once, not waited on.
    REQUIRE(::mkfifo((tmp / "fifo").c_str(), 0600) == 0);
    const auto start = std::chrono::steady_clock::now();
    CHECK(contains(refusal(tmp / "fifo", limit), "not a regular file"));
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(5));
    CHECK(contains(refusal(tmp.path(), limit), "folder"));
    CHECK(contains(refusal(tmp / "missing", limit), "No such file"));

    // Past the limit: the message names the size and the kind's limit.
    write_text(tmp / "big.txt", std::string(1001, 'x'));
    const std::string big = refusal(tmp / "big.txt", limit);
    CHECK(contains(big, "the file is 1001 bytes"));
    CHECK(contains(big, "a test file is at most 1000 bytes"));
    write_text(tmp / "edge.txt", std::string(1000, 'x'));
    CHECK(sph::read_input_file(tmp / "edge.txt", limit).size() == 1000);
}

TEST_CASE("inputs: each kind has its documented limit", "[contract][inputs]") {
    CHECK(sph::scene_file_limit.bytes == 16u << 20);
    CHECK(sph::mesh_file_limit.bytes == 512u << 20);
    CHECK(sph::png_file_limit.bytes == 256u << 20);
    CHECK(sph::format_bytes(double(sph::scene_file_limit.bytes)) == "16 MiB");
    CHECK(sph::format_bytes(1.5 * (1 << 30)) == "1.5 GiB");
}

TEST_CASE("inputs: a scene that is a device is refused with exit 2, naming the file",
          "[contract][inputs]") {
    TempFolder tmp;
    // A scene past its limit (a string value of a gigabyte would be): a
    // sparse file, refused by its size before it is read.
    { std::ofstream(tmp / "huge.json") << "{\"output\": {\"name\": \""; }
    fs::resize_file(tmp / "huge.json", sph::scene_file_limit.bytes + 1);
    const auto huge =
        run_sphclip(tmp, {"run", (tmp / "huge.json").string(), "--out", (tmp / "out").string()});
    CHECK(huge.exit_code == 2);
    CHECK(contains(huge.output, "huge.json: cannot read the scene file: the file is 16 MiB "
                                "(16777217 bytes); a scene file is at most 16 MiB"));
    CHECK_FALSE(fs::exists(tmp / "out"));
    fs::create_symlink("/dev/zero", tmp / "scene.json");
    for (const std::string& scene : {std::string("/dev/zero"), (tmp / "scene.json").string()}) {
        const auto result = run_sphclip(tmp, {"run", scene, "--out", (tmp / "out").string()});
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, scene + ": cannot read the scene file: not a regular file"));
        CHECK_FALSE(fs::exists(tmp / "out"));
    }
}

TEST_CASE("inputs: a PNG that is a device or claims a huge size is refused before decoding",
          "[contract][inputs]") {
    TempFolder tmp;
    try {
        sph::read_png("/dev/zero");
        FAIL("read /dev/zero as a PNG");
    } catch (const sph::ImageReadError& e) {
        CHECK(contains(e.reason, "not a regular file"));
    }
    // 100,000 x 100,000 from a file of a few dozen bytes.
    const std::string lie = png_claiming(100000, 100000, tmp);
    try {
        sph::decode_png(lie, "lie.png");
        FAIL("decoded a PNG claiming 100000x100000");
    } catch (const sph::ImageReadError& e) {
        CHECK(contains(e.reason, "the image is 100000x100000"));
        CHECK(contains(e.reason, "at most 16384 pixels a side"));
    }
    // Within a side but too many pixels in all.
    CHECK_THROWS_AS(sph::decode_png(png_claiming(16384, 16384, tmp), "many.png"),
                    sph::ImageReadError);
    // A PNG cut short anywhere (in its header, its pixels, before IEND) is
    // refused as unreadable, never read past its end.
    sph::Image whole(16, 16);
    for (std::size_t k = 0; k < whole.rgba.size(); ++k)
        whole.rgba[k] = std::uint8_t(k * 37);
    sph::write_png(tmp / "whole.png", whole);
    const std::string bytes = read_text(tmp / "whole.png");
    for (const std::size_t length : {std::size_t(8), std::size_t(20), std::size_t(33),
                                     bytes.size() / 2, bytes.size() - 12, bytes.size() - 1}) {
        INFO("cut at " << length << " of " << bytes.size());
        CHECK_THROWS_AS(sph::decode_png(bytes.substr(0, length), "cut.png"), sph::ImageReadError);
    }
    CHECK(sph::decode_png(bytes, "whole.png").rgba == whole.rgba);
    // compare says which file.
    write_text(tmp / "lie.png", lie);
    const auto result =
        run_sphclip(tmp, {"compare", (tmp / "lie.png").string(), (tmp / "lie.png").string()});
    CHECK(result.exit_code == 2);
    CHECK(contains(result.output, (tmp / "lie.png").string()));
    CHECK(contains(result.output, "100000x100000"));
}

TEST_CASE("inputs: compare refuses a --diff that is one of its inputs, by inode",
          "[contract][inputs]") {
    TempFolder tmp;
    sph::Image a(8, 8), b(8, 8);
    std::fill(a.rgba.begin(), a.rgba.end(), std::uint8_t(255));
    std::fill(b.rgba.begin(), b.rgba.end(), std::uint8_t(255));
    b.rgba[0] = 0;
    sph::write_png(tmp / "ref.png", a);
    sph::write_png(tmp / "test.png", b);
    const std::string ref_bytes = read_text(tmp / "ref.png");
    const std::string test_bytes = read_text(tmp / "test.png");
    fs::create_symlink(tmp / "test.png", tmp / "test_link.png");
    fs::create_hard_link(tmp / "ref.png", tmp / "ref_hard.png");

    const std::string ref = (tmp / "ref.png").string(), test = (tmp / "test.png").string();
    for (const auto& [diff, role] : {std::pair{test, "test image"},
                                     {ref, "reference"},
                                     {(tmp / "test_link.png").string(), "test image"},
                                     {(tmp / "ref_hard.png").string(), "reference"},
                                     {(tmp.path() / "." / "test.png").string(), "test image"}}) {
        INFO(diff);
        const auto result = run_sphclip(tmp, {"compare", ref, test, "--diff", diff});
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "--diff"));
        CHECK(contains(result.output, fmt::format("is the {}", role)));
        CHECK(read_text(tmp / "ref.png") == ref_bytes);
        CHECK(read_text(tmp / "test.png") == test_bytes);
    }
    // Any other path is written as before.
    const auto result =
        run_sphclip(tmp, {"compare", ref, test, "--diff", (tmp / "diff.png").string()});
    CHECK(result.exit_code == 1);
    CHECK(fs::exists(tmp / "diff.png"));
}

TEST_CASE("inputs: an OBJ mesh that is a device, has a bad vertex or a huge face is refused "
          "naming the line",
          "[contract][inputs]") {
    TempFolder tmp;
    const auto refusal_of = [&](const std::string& text) {
        try {
            sph::parse_obj_mesh(text, "m.obj", 1, sph::Vec<3>(0), "scene.json",
                                "effects.obstacles[0].file");
            return std::string();
        } catch (const sph::InputError& e) {
            CHECK(e.file == "scene.json");
            CHECK(e.field == "effects.obstacles[0].file");
            return e.problem;
        }
    };
    const std::string tetrahedron_faces = "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
    CHECK(refusal_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n" + tetrahedron_faces).empty());
    CHECK(contains(refusal_of("v 0 0 0\nv nan 0 0\nv 0 1 0\nv 0 0 1\n" + tetrahedron_faces),
                   "line 2: vertex coordinate \"nan\" is not a finite number"));
    CHECK(contains(refusal_of("v 0 0 0\nv 1 0 0\nv 0 1e300 0\nv 0 0 1\n" + tetrahedron_faces),
                   "line 3: vertex coordinate \"1e300\" is 1e+300 m from the origin"));
    // A face of 200,000 corners that goes round a tetrahedron's corners
    // 50,000 times is refused within about a second (tinyobjloader's ear
    // clipping took minutes on it): every ear holds 50,000 of its corners.
    std::string huge = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf";
    for (int k = 0; k < 200000; ++k)
        huge += fmt::format(" {}", 1 + k % 4);
    huge += "\n";
    CHECK(contains(refusal_of(huge), "line 5: a face of 200000 corners too irregular to split"));
    // A corner that names no vertex, by its line.
    CHECK(contains(refusal_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 x\n"),
                   "line 4: face corner \"x\" does not name a vertex"));
    // Lines that end in a lone "\r", as tinyobjloader reads them: the
    // polygon is still split here (not by its quadratic splitting).
    CHECK(contains(refusal_of("v 0 0 0\rv 1 0 0\r\nv 0 1 0\rf 1 2 3 x\r"),
                   "line 4: face corner \"x\" does not name a vertex"));
    CHECK(contains(refusal_of("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 9\n"),
                   "line 4: the face names vertex 9, but the file has 3 vertices"));

    // Through the file reader: a symlink to /dev/zero.
    fs::create_symlink("/dev/zero", tmp / "zero.obj");
    try {
        sph::read_obj_mesh(tmp / "zero.obj", 1, sph::Vec<3>(0), "scene.json", "mesh");
        FAIL("read /dev/zero as a mesh");
    } catch (const sph::InputError& e) {
        CHECK(contains(e.problem, "cannot read the mesh file: not a regular file"));
    }
}

namespace {

// A prism whose two caps are the polygon `outline` (counter-clockwise, in
// z = 0 and z = height), its sides quads.
std::string prism_obj(const std::vector<std::array<double, 2>>& outline, double height) {
    const int n = int(outline.size());
    std::string text;
    for (int z = 0; z < 2; ++z)
        for (const auto& [x, y] : outline)
            text += fmt::format("v {:.17g} {:.17g} {}\n", x, y, z * height);
    // The bottom cap seen from below (counter-clockwise from outside), the
    // top from above, with relative (negative) numbers on the top.
    text += "f";
    for (int k = n; k >= 1; --k)
        text += fmt::format(" {}", k);
    text += "\nf";
    for (int k = 0; k < n; ++k)
        text += fmt::format(" {}/1/1", k - n);
    text += "\n";
    for (int k = 0; k < n; ++k) {
        const int b = 1 + k, b2 = 1 + (k + 1) % n;
        text += fmt::format("f {} {} {} {}\n", b, b2, b2 + n, b + n);
    }
    return text;
}

double shoelace_area(const std::vector<std::array<double, 2>>& outline) {
    double twice = 0;
    for (std::size_t k = 0; k < outline.size(); ++k) {
        const auto& [x0, y0] = outline[k];
        const auto& [x1, y1] = outline[(k + 1) % outline.size()];
        twice += x0 * y1 - x1 * y0;
    }
    return twice / 2;
}

} // namespace

TEST_CASE("inputs: an OBJ face of 200,000 corners, convex or not, is split into triangles",
          "[contract][inputs]") {
    // A face of more than 256 corners used to be refused, after
    // tinyobjloader's quadratic ear clipping had taken minutes on one.
    // A circle of 10,000 corners (finer, its ears would have too little area
    // for the solid check), and a strip 100,000 m long whose long sides are
    // saw teeth: 200,000 corners, half of them reflex.
    std::vector<std::array<double, 2>> circle, saw;
    for (int k = 0; k < 10000; ++k)
        circle.push_back({std::cos(2 * M_PI * k / 10000), std::sin(2 * M_PI * k / 10000)});
    const int teeth = 100000;
    for (int k = 0; k < teeth; ++k) // the bottom, left to right, teeth down
        saw.push_back({double(k), k % 2 ? -0.5 : 0.0});
    for (int k = teeth - 1; k >= 0; --k) // the top, right to left, teeth up
        saw.push_back({double(k), k % 2 ? 1.5 : 1.0});
    // The strip's prism is as tall as it is long: a flat slab would enclose
    // too little volume for the solid check.
    for (const auto& [outline, height] : {std::pair{circle, 1.0}, std::pair{saw, double(teeth)}}) {
        const std::size_t n = outline.size();
        INFO(n << " corners");
        const auto mesh =
            sph::parse_obj_mesh(prism_obj(outline, height), "prism.obj", 1, sph::Vec<3>(0),
                                "scene.json", "effects.obstacles[0].file");
        // n - 2 triangles a cap, two a side.
        CHECK(mesh->triangles().size() == 2 * (n - 2) + 2 * n);
        CHECK(mesh->volume() == Approx(shoelace_area(outline) * height).epsilon(1e-9));
    }
    // A small concave face, a quad with a reflex corner, and a hexagon with
    // corners on a straight line: split without a degenerate triangle.
    const auto arrow = sph::split_polygon({{0, 0, 0}, {2, 1, 0}, {0, 2, 0}, {0.5, 1, 0}});
    REQUIRE(arrow.size() == 2);
    for (const auto& t : arrow)
        CHECK(std::find(t.begin(), t.end(), 3u) != t.end());
    const auto straight =
        sph::split_polygon({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {0, 1, 0}});
    REQUIRE(straight.size() == 4);
    const std::vector<sph::Vec<3>> hexagon{{0, 0, 0}, {1, 0, 0}, {2, 0, 0},
                                           {2, 1, 0}, {1, 1, 0}, {0, 1, 0}};
    double total = 0;
    for (const auto& t : straight) {
        const double area = 0.5 * glm::length(glm::cross(hexagon[t[1]] - hexagon[t[0]],
                                                         hexagon[t[2]] - hexagon[t[0]]));
        CHECK(area > 0.1);
        // Wound as the hexagon is: counter-clockwise about +z.
        CHECK(glm::cross(hexagon[t[1]] - hexagon[t[0]], hexagon[t[2]] - hexagon[t[0]]).z > 0);
        total += area;
    }
    CHECK(total == Approx(2));
}

namespace {

// The InputError parse_scene throws for `text` with `overrides`, or none.
std::optional<sph::InputError> scene_error(const std::string& text,
                                           const std::vector<sph::Override>& overrides = {}) {
    try {
        sph::parse_scene(text, "scene.json", overrides);
        return std::nullopt;
    } catch (const sph::InputError& e) {
        return e;
    }
}

} // namespace

TEST_CASE("inputs: a key given twice in one object is refused, naming it", "[contract][inputs]") {
    // nlohmann keeps the last silently: this ran 0.1 s.
    auto e = scene_error(R"({"duration": 0.05, "duration": 0.1})");
    REQUIRE(e);
    CHECK(e->file == "scene.json");
    CHECK(e->field == "duration");
    CHECK(contains(e->problem, "given twice"));
    e = scene_error(R"({"solver": {"name": "seed", "cfl": 0.3, "name": "wcsph"}})");
    REQUIRE(e);
    CHECK(e->field == "solver.name");
    e = scene_error(R"({"fluid": {"blocks": [{"min": [0, 0], "max": [0.03, 0.03]},
                                            {"min": [0, 0], "min": [0.1, 0]}]}})");
    REQUIRE(e);
    CHECK(e->field == "fluid.blocks[1].min");
    // The same key in two objects is fine.
    CHECK_FALSE(scene_error(R"({"domain": {"min": [0, 0], "max": [0.4, 0.25]},
                                "fluid": {"blocks": [{"min": [0, 0], "max": [0.05, 0.1]}]}})"));
    // In a --set value too.
    e = scene_error("{}", {{"solver", R"({"cfl": 0.3, "cfl": 0.2})"}});
    REQUIRE(e);
    CHECK(contains(e->field, "solver (from --set).cfl"));
}

TEST_CASE("inputs: command-line values that cannot be meant are refused with exit 2, naming "
          "the key",
          "[contract][inputs]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_tank);
    const auto refused = [&](const std::vector<std::string>& extra,
                             const std::vector<std::string>& words) {
        std::vector<std::string> args{"run",      (tmp / "scene.json").string(),
                                      "--out",    (tmp / "out").string(),
                                      "--no-png", "--no-mp4"};
        args.insert(args.end(), extra.begin(), extra.end());
        const auto result = run_sphclip(tmp, args);
        INFO(result.output);
        CHECK(result.exit_code == 2);
        for (const auto& word : words)
            CHECK(contains(result.output, word));
        CHECK_FALSE(fs::exists(tmp / "out"));
    };
    // stoul used to throw out_of_range: exit 1.
    refused({"--set", "fluid.blocks.99999999999999999999.velocity=[1,0]"},
            {"fluid.blocks.99999999999999999999.velocity (from --set)", "past the end"});
    // NaN used to be ignored: the scene's own duration ran.
    refused({"--duration", "nan"}, {"--duration", "not a finite number"});
    refused({"--fps", "nan"}, {"--fps", "not a finite number"});
    refused({"--fps", "inf"}, {"--fps"});
    // A key of a block past the end used to append a block of defaults.
    refused({"--set", "fluid.blocks.1.velocity=[1,0]"},
            {"fluid.blocks.1.velocity (from --set)", "'fluid.blocks' has 1 element",
             "--set fluid.blocks.1={...}"});
    // Zero: one short line, where CLI11's range printed DBL_MAX in 309 digits.
    for (const char* flag : {"--duration", "--fps"}) {
        TempFolder quiet;
        const auto result = run_sphclip(quiet, {"run", (tmp / "scene.json").string(), "--out",
                                                (tmp / "out").string(), flag, "0"});
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, std::string(flag) + ": 0 is not a finite number above 0"));
        CHECK(result.output.find("0000000000") == std::string::npos);
        CHECK(result.output.size() < 400);
    }
    // compare's --max-pixels printed the same 309 digits.
    for (const char* count : {"-1", "1.5", "nan", "99999999999999999999999"}) {
        const auto result = run_sphclip(tmp, {"compare", "a.png", "b.png", "--max-pixels", count});
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "--max-pixels"));
        CHECK(result.output.find("0000000000") == std::string::npos);
        CHECK(result.output.size() < 400);
    }
    // A key through a value that is not an object, or a list indexed by a
    // word in UTF-8 (its bytes above 127 were given to ::isdigit).
    refused({"--set", "fluid.spacing.x=1"},
            {"fluid.spacing.x (from --set)", "'fluid.spacing' is not an object"});
    refused({"--set", "fluid.blocks.\xc3\xa9=1"},
            {"'fluid.blocks' is a list; index it with a number"});
}

TEST_CASE("inputs: control characters in a value are shown escaped, the whole message kept",
          "[contract][inputs]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_tank);
    for (const std::string& name :
         {std::string(R"("ab\u0000cd")"), std::string(R"("ab\u001b[31mcd")")}) {
        INFO(name);
        const auto result = run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--no-png",
                                              "--no-mp4", "--set", "output.name=" + name});
        INFO(result.output);
        CHECK(result.exit_code == 2);
        // The NUL used to end the message after "ab"; the escape reached the
        // terminal raw.
        CHECK(contains(result.output, name.substr(1, name.size() - 2)));
        CHECK(contains(result.output, "holds a control character"));
        CHECK(result.output.find('\0') == std::string::npos);
        CHECK(result.output.find('\x1b') == std::string::npos);
    }
    CHECK(sph::printable(std::string("a\0b\x7f\n\tc", 7)) == "a\\u0000b\\u007f\n\tc");
}

TEST_CASE("inputs: a render.size the OpenGL context cannot draw is refused before anything is "
          "written",
          "[contract][inputs]") {
    {
        // One context per process at a time: this one is gone before sphclip runs.
        const auto context = sph::make_gl_context("osmesa");
        const sph::GlInfo& gl = context->info();
        REQUIRE(gl.max_renderbuffer_size > 0);
        CHECK(sph::frame_size_problem(*context, 64, 64, 4).empty());
        const std::string wide =
            sph::frame_size_problem(*context, gl.max_renderbuffer_size + 1, 64, 4);
        CHECK(contains(wide, fmt::format("at most {}", std::min(gl.max_renderbuffer_size,
                                                                gl.max_viewport_width))));
        CHECK_FALSE(sph::frame_size_problem(*context, 64, 64, gl.max_samples + 1).empty());
    }
    // On llvmpipe (OSMesa is always llvmpipe) a 16384^2 frame with 4 samples
    // is within the limits but cannot be completed: it used to fail at the
    // first frame with exit 1, after run.json and stats.csv were written.
    TempFolder tmp;
    write_text(tmp / "scene.json", small_tank);
    const auto result =
        run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--backend", "osmesa", "--out",
                          (tmp / "out").string(), "--set", "render.size=[16384,16384]"});
    INFO(result.output);
    CHECK(result.exit_code == 2);
    CHECK(contains(result.output, "render.size: the OpenGL renderer (osmesa"));
    CHECK(contains(result.output, "16384x16384"));
    CHECK_FALSE(fs::exists(tmp / "out"));
}

TEST_CASE("inputs: a render.font that is a pipe, a device or not a font is refused before "
          "anything is written",
          "[contract][inputs]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_tank);
    REQUIRE(::mkfifo((tmp / "font.fifo").c_str(), 0644) == 0);
    write_text(tmp / "notes.ttf", "not a font");
    // The FIFO used to block the run for ever (open() restarts after
    // SIGTERM); /dev/zero and a text file fell back to the default with a
    // warning, though the user named a font.
    for (const auto& [font, why] : std::vector<std::pair<std::string, std::string>>{
             {(tmp / "font.fifo").string(), "not a regular file"},
             {"/dev/zero", "not a regular file"},
             {(tmp / "notes.ttf").string(), "is not a font FreeType can read"}}) {
        INFO(font);
        const auto result =
            run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--out", (tmp / "out").string(),
                              "--set", "render.font=\"" + font + "\""});
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "render.font"));
        CHECK(contains(result.output, why));
        CHECK_FALSE(fs::exists(tmp / "out"));
    }
    CHECK(sph::font_problem(sph::default_font_paths()[0]).empty());
}

TEST_CASE("inputs: a plan's files, a --list file and the tables read back are bounded too",
          "[contract][inputs]") {
    TempFolder tmp;
    // A plan.json past its limit: a sparse file, no disk used.
    fs::create_directories(tmp / "plan");
    { std::ofstream(tmp / "plan" / "plan.json").put('{'); }
    fs::resize_file(tmp / "plan" / "plan.json", sph::plan_file_limit.bytes + 1);
    auto result = run_sphclip(tmp, {"collect", (tmp / "plan").string()});
    INFO(result.output);
    CHECK(result.exit_code == 2);
    CHECK(contains(result.output, "plan.json"));
    CHECK(contains(result.output, "a plan file is at most 64 MiB"));
    // batch --list /dev/zero used to be read until memory ran out.
    result = run_sphclip(tmp, {"batch", "--list", "/dev/zero", "--out", (tmp / "b").string()});
    INFO(result.output);
    CHECK(result.exit_code == 2);
    CHECK(contains(result.output, "--list"));
    CHECK(contains(result.output, "not a regular file"));
    // A FIFO where a table is read back: refused at once, not waited on.
    REQUIRE(::mkfifo((tmp / "stats.csv").c_str(), 0644) == 0);
    CHECK_THROWS_WITH(sph::read_csv_table(tmp / "stats.csv"),
                      Catch::Contains("not a regular file"));
}
