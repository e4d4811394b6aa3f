// The README's "Your first own clip" runs as it says: scenes/first_clip_3d.json
// through the real program, a few frames, each of the scene's own size.
// A guide whose example breaks is worse than none, so the example is tested.

#include "output/png_io.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/wait.h>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sph::test::read_text;
using sph::test::TempFolder;

// The share of the frame's pixels that differ from its top-left corner, the
// background: the fluid, the domain box, the colour bar and the caption.
double share_not_background(const sph::Image& image) {
    const std::uint8_t* corner = image.pixel(0, 0);
    std::size_t different = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* p = image.pixel(x, y);
            if (p[0] != corner[0] || p[1] != corner[1] || p[2] != corner[2])
                ++different;
        }
    return double(different) / (double(image.width) * double(image.height));
}

} // namespace

TEST_CASE("first clip: scenes/first_clip_3d.json renders frames of its own size",
          "[cli][first_clip]") {
    TempFolder tmp;
    const fs::path scene = fs::path(SPHCLIP_SOURCE_DIR) / "scenes" / "first_clip_3d.json";
    const fs::path out = tmp / "out";
    // Three frames (t = 0 and 1/30 s, and the last at the duration, 0.066 s)
    // show the example runs; the whole clip
    // is for people. Idle OpenMP threads sleep: ctest runs tests side by side.
    const std::string command =
        fmt::format("OMP_WAIT_POLICY=passive '{}' run '{}' --out '{}' --duration 0.066 --no-mp4 "
                    "--quiet --threads 2 > '{}' 2>&1",
                    SPHCLIP_EXE, scene.string(), out.string(), (tmp / "log.txt").string());
    const int status = std::system(command.c_str());
    INFO(read_text(tmp / "log.txt"));
    REQUIRE(status != -1);
    REQUIRE(WIFEXITED(status));
    REQUIRE(WEXITSTATUS(status) == 0);

    // What the README promises of the scene: 3D, its own camera and colour.
    const json run = json::parse(read_text(out / "run.json"));
    REQUIRE(run.at("status") == "completed");
    const json& resolved = run.at("scene");
    CHECK(resolved.at("dimension") == 3);
    CHECK(resolved.at("render").at("colour") == "velocity");
    CHECK(resolved.at("render").at("camera").at("position").is_array());
    const int width = resolved.at("render").at("size").at(0).get<int>();
    const int height = resolved.at("render").at("size").at(1).get<int>();
    CHECK(width == 800);
    CHECK(height == 600);

    for (int k = 0; k < 3; ++k) {
        const fs::path frame_path = out / "frames" / fmt::format("frame_{:05d}.png", k);
        INFO(frame_path);
        REQUIRE(fs::exists(frame_path));
        const sph::Image frame = sph::read_png(frame_path);
        CHECK(frame.width == width);
        CHECK(frame.height == height);
        // The camera frames the fluid: a frame that is nearly all background
        // means the camera looks past it.
        CHECK(share_not_background(frame) > 0.05);
    }
    CHECK_FALSE(fs::exists(out / "frames" / "frame_00003.png"));
    CHECK(fs::exists(out / "stats.csv"));
    CHECK_FALSE(fs::exists(out / "clip.mp4"));
}
