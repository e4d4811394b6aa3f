// The overlay (src/render/overlay.*, text.*): colour-bar ticks at round
// values with one precision, the caption's placeholders, and text from a
// real font, with the bitmap font standing in when there is none.
#include "render/gl_context.hpp"
#include "render/overlay.hpp"
#include "render/text.hpp"

#include <catch2/catch.hpp>
#include <filesystem>

using namespace sph;

TEST_CASE("colour-bar ticks are round, 1-2-5 steps, with one precision", "[render]") {
    // The old bar's 0.5537 / 1.107 / 1.661 / 2.215 for a range of 2.215.
    const Ticks speed = round_ticks(0, 2.215);
    CHECK(speed.labels == std::vector<std::string>{"0.0", "0.5", "1.0", "1.5", "2.0"});
    const Ticks density = round_ticks(955, 1045);
    CHECK(density.labels == std::vector<std::string>{"960", "980", "1000", "1020", "1040"});
    const Ticks pressure = round_ticks(0, 1121.3);
    CHECK(pressure.labels == std::vector<std::string>{"0", "200", "400", "600", "800", "1000"});
    const Ticks small = round_ticks(0, 0.05);
    CHECK(small.labels == std::vector<std::string>{"0.00", "0.01", "0.02", "0.03", "0.04", "0.05"});
    // Large values in powers of ten, one mantissa precision.
    const Ticks large = round_ticks(0, 3e6);
    CHECK(large.labels.front() == "0e+00");
    CHECK(large.labels.back() == "3e+06");
    for (const Ticks* t : {&speed, &density, &pressure, &small, &large}) {
        CHECK(t->values.size() >= 2);
        CHECK(t->values.size() <= 6);
        CHECK(t->values.size() == t->labels.size());
    }
    // Negative ranges, and no "-0".
    CHECK(round_ticks(-1, 1).labels ==
          std::vector<std::string>{"-1.0", "-0.5", "0.0", "0.5", "1.0"});
}

TEST_CASE("the caption's placeholders are replaced, anything else kept", "[render]") {
    Snapshot frame;
    frame.time = 0.25;
    frame.frame = 7;
    frame.steps = 123;
    CHECK(format_caption("t = {time} s    frame {frame}", frame) == "t = 0.250 s    frame 7");
    CHECK(format_caption("{steps} steps, {other}", frame) == "123 steps, {other}");
    CHECK(format_caption("", frame).empty());
}

TEST_CASE("the overlay's text comes from a real font, or from the bitmap font with a warning",
          "[render]") {
    const auto context = make_gl_context("auto");
    std::string warning;
    const std::string font = find_font("", warning);
    // fonts-dejavu-core is one of sphclip's dependencies (.ci/setup).
    REQUIRE(std::filesystem::exists(font));
    CHECK(warning.empty());
    const TextFace face(font, 20, warning);
    CHECK(face.from_font());
    CHECK(warning.empty());
    // DejaVu Sans at 20 px: capitals 14-15 px tall, proportional widths.
    CHECK(face.cap_height() == Approx(14.5).margin(1));
    CHECK(face.width("WWW") > 2 * face.width("iii"));
    std::vector<TextVertex> quads;
    face.append("a b", 10, 30, quads);
    CHECK(quads.size() == 12); // two glyphs, the space has none

    // A font that cannot be read: a warning naming it, and the default.
    const std::string bad = "/nonexistent/font.ttf";
    CHECK(find_font(bad, warning) == font);
    CHECK(warning.find(bad) != std::string::npos);
    // No font at all: the bitmap font, never a failure.
    const TextFace bitmap("", 20, warning);
    CHECK_FALSE(bitmap.from_font());
    CHECK(bitmap.width("abc") > 0);
    const TextFace unreadable(bad, 20, warning);
    CHECK_FALSE(unreadable.from_font());
    CHECK(warning.find(bad) != std::string::npos);
}
