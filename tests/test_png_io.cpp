// PNG writing and reading (src/output/png_io.*): exact round trips, atomic
// writes, clear errors, and the writer thread.

#include "output/png_io.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using sph::test::read_text;
using sph::test::TempFolder;
using sph::test::write_text;

// Every byte different from its neighbours, so that a swapped channel, a
// flipped row or an off-by-one stride shows. `seed` makes images distinct.
sph::Image pattern(int width, int height, bool opaque, int seed = 0) {
    sph::Image image(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = std::uint8_t(x * 7 + y * 3 + seed);
            p[1] = std::uint8_t(x * 13 + y * 29 + 2 * seed);
            p[2] = std::uint8_t((x ^ y) * 5 + 3 * seed);
            p[3] = opaque ? 255 : std::uint8_t(x * 11 + y * 17 + seed);
        }
    return image;
}

// The PNG colour type from the IHDR chunk: 2 is RGB, 6 is RGBA.
int colour_type(const fs::path& png) {
    const std::string bytes = read_text(png);
    REQUIRE(bytes.size() > 25);
    return std::uint8_t(bytes[25]);
}

std::vector<fs::path> folder_contents(const fs::path& folder) {
    std::vector<fs::path> entries;
    for (const auto& entry : fs::directory_iterator(folder))
        entries.push_back(entry.path());
    return entries;
}

} // namespace

TEST_CASE("a PNG reads back exactly as written, with and without transparency", "[png]") {
    TempFolder tmp;
    const fs::path path = tmp / "image.png";
    SECTION("varied alpha: written as RGBA") {
        const sph::Image image = pattern(37, 23, false);
        sph::write_png(path, image);
        CHECK(colour_type(path) == 6);
        const sph::Image back = sph::read_png(path);
        CHECK(back.width == 37);
        CHECK(back.height == 23);
        CHECK(back.rgba == image.rgba);
    }
    SECTION("opaque: written as RGB, read back with alpha 255") {
        const sph::Image image = pattern(37, 23, true);
        sph::write_png(path, image);
        CHECK(colour_type(path) == 2);
        CHECK(sph::read_png(path).rgba == image.rgba);
    }
    SECTION("a single transparent pixel keeps the alpha channel") {
        sph::Image image = pattern(16, 16, true);
        image.pixel(15, 15)[3] = 254;
        sph::write_png(path, image);
        CHECK(colour_type(path) == 6);
        CHECK(sph::read_png(path).rgba == image.rgba);
    }
}

TEST_CASE("odd image sizes round trip, row 0 at the top", "[png]") {
    TempFolder tmp;
    for (const auto& [width, height] : {std::pair{1, 1}, {3, 5}, {5, 3}, {1281, 721}})
        for (const bool opaque : {true, false}) {
            INFO(width << "x" << height << (opaque ? " opaque" : " transparent"));
            const fs::path path = tmp / fmt::format("{}x{}.png", width, height);
            const sph::Image image = pattern(width, height, opaque);
            sph::write_png(path, image);
            const sph::Image back = sph::read_png(path);
            REQUIRE(back.width == width);
            REQUIRE(back.height == height);
            CHECK(back.rgba == image.rgba);
        }
}

TEST_CASE("write_png replaces a file whole and leaves no temporary file", "[png]") {
    TempFolder tmp;
    const fs::path path = tmp / "frame.png";
    sph::write_png(path, pattern(8, 8, true, 1));
    sph::write_png(path, pattern(9, 4, false, 2));
    CHECK(sph::read_png(path).rgba == pattern(9, 4, false, 2).rgba);
    CHECK(folder_contents(tmp.path()) == std::vector<fs::path>{path});
}

TEST_CASE("write_png names the path when it cannot write, and refuses empty images", "[png]") {
    TempFolder tmp;
    const fs::path missing = tmp / "no_such_folder" / "frame.png";
    try {
        sph::write_png(missing, pattern(4, 4, true));
        FAIL("no exception");
    } catch (const std::runtime_error& e) {
        CHECK_THAT(e.what(), Catch::Contains(missing.string()));
    }
    CHECK_THROWS_AS(sph::write_png(tmp / "empty.png", sph::Image()), std::invalid_argument);
    sph::Image short_buffer(4, 4);
    short_buffer.rgba.pop_back();
    CHECK_THROWS_AS(sph::write_png(tmp / "short.png", short_buffer), std::invalid_argument);
    CHECK(folder_contents(tmp.path()).empty());
}

TEST_CASE("read_png throws ImageReadError naming the path and the reason", "[png]") {
    TempFolder tmp;
    auto expect_error = [](const fs::path& path, const std::string& reason) {
        try {
            sph::read_png(path);
            FAIL("no exception for " << path);
        } catch (const sph::ImageReadError& e) {
            CHECK(e.path == path);
            CHECK_THAT(e.what(), Catch::Contains(path.string()));
            CHECK_THAT(e.what(), Catch::Contains(reason));
        }
    };
    SECTION("a missing file") {
        expect_error(tmp / "missing.png", "No such file or directory");
    }
    SECTION("a file that is not a PNG") {
        write_text(tmp / "garbage.png", "this is not an image, only text\n");
        expect_error(tmp / "garbage.png", ""); // stb's reason varies with its version
    }
    SECTION("an empty file") {
        write_text(tmp / "empty.png", "");
        expect_error(tmp / "empty.png", "");
    }
    SECTION("a PNG cut short") {
        sph::write_png(tmp / "whole.png", pattern(64, 64, false));
        const std::string whole = read_text(tmp / "whole.png");
        write_text(tmp / "cut.png", whole.substr(0, whole.size() / 2));
        expect_error(tmp / "cut.png", "");
    }
    SECTION("a folder") {
        expect_error(tmp.path(), "");
    }
}

TEST_CASE("PngWriterThread writes every image, in the order submitted", "[png]") {
    TempFolder tmp;
    constexpr int frames = 8;
    {
        sph::PngWriterThread writer(2);
        for (int k = 0; k < frames; ++k) {
            writer.submit(tmp / fmt::format("frame_{}.png", k), pattern(97, 55, true, k));
            // The same file again and again: in order, the last one submitted stays.
            writer.submit(tmp / "latest.png", pattern(31, 17, k % 2 == 0, k));
        }
        writer.finish();
        writer.finish(); // a second call does nothing
    }
    for (int k = 0; k < frames; ++k) {
        INFO("frame " << k);
        CHECK(sph::read_png(tmp / fmt::format("frame_{}.png", k)).rgba ==
              pattern(97, 55, true, k).rgba);
    }
    CHECK(sph::read_png(tmp / "latest.png").rgba == pattern(31, 17, false, frames - 1).rgba);
    for (int k = 1; k < frames; ++k)
        CHECK(fs::last_write_time(tmp / fmt::format("frame_{}.png", k - 1)) <=
              fs::last_write_time(tmp / fmt::format("frame_{}.png", k)));
    CHECK(folder_contents(tmp.path()).size() == frames + 1); // no temporary files
}

TEST_CASE("PngWriterThread's destructor writes what is queued", "[png]") {
    TempFolder tmp;
    {
        sph::PngWriterThread writer;
        writer.submit(tmp / "a.png", pattern(40, 30, true, 1));
        writer.submit(tmp / "b.png", pattern(40, 30, true, 2));
    }
    CHECK(sph::read_png(tmp / "a.png").rgba == pattern(40, 30, true, 1).rgba);
    CHECK(sph::read_png(tmp / "b.png").rgba == pattern(40, 30, true, 2).rgba);
}

TEST_CASE("PngWriterThread reports a failed write and writes nothing after it", "[png]") {
    TempFolder tmp;
    const fs::path bad = tmp / "no_such_folder" / "frame.png";
    SECTION("on finish()") {
        sph::PngWriterThread writer;
        writer.submit(tmp / "before.png", pattern(8, 8, true));
        writer.submit(bad, pattern(8, 8, true));
        try {
            writer.finish();
            FAIL("no exception");
        } catch (const std::runtime_error& e) {
            CHECK_THAT(e.what(), Catch::Contains(bad.string()));
        }
        CHECK(fs::exists(tmp / "before.png"));
    }
    SECTION("on a later submit(), and again on finish()") {
        sph::PngWriterThread writer(1);
        writer.submit(bad, pattern(8, 8, true));
        // The queue holds one image, so submit() waits for the writer, which
        // fails on its first image: within a few calls, submit() throws.
        int k = 0;
        bool thrown = false;
        for (; k < 100 && !thrown; ++k) {
            try {
                writer.submit(tmp / fmt::format("after_{}.png", k), pattern(8, 8, true));
            } catch (const std::runtime_error& e) {
                CHECK_THAT(e.what(), Catch::Contains(bad.string()));
                thrown = true;
            }
        }
        CHECK(thrown);
        CHECK_THROWS_WITH(writer.finish(), Catch::Contains(bad.string()));
        CHECK_NOTHROW(writer.finish());
        // Images queued behind the failed one were dropped.
        CHECK(folder_contents(tmp.path()).empty());
    }
}
