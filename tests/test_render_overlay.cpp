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

TEST_CASE("text is UTF-8: accents, Greek and symbols are drawn, any other character of the "
          "text too, and malformed bytes show as '?'",
          "[render]") {
    // Decoding: one to four bytes, and what is malformed.
    const auto characters = [](std::string_view text) {
        std::u32string out;
        for (std::size_t at = 0; at < text.size();)
            out += next_character(text, at);
        return out;
    };
    CHECK(characters("a\xc3\xa9\xcf\x81\xe2\x88\x92\xf0\x9f\x98\x80") ==
          U"a\u00e9\u03c1\u2212\U0001f600");
    CHECK(characters("\xc3") == U"\ufffd");                     // cut short
    CHECK(characters("\xc0\xaf") == U"\ufffd\ufffd");           // overlong '/'
    CHECK(characters("\xed\xa0\x80") == U"\ufffd\ufffd\ufffd"); // a surrogate
    CHECK(characters("\xff"
                     "a") == U"\ufffda");

    const auto context = make_gl_context("auto");
    std::string warning;
    const std::string font = find_font("", warning);
    // A character outside the fixed set, named in the texts: in the atlas.
    const TextFace face(font, 20, warning, {"\xe2\x88\x91"}); // U+2211 N-ARY SUMMATION
    REQUIRE(face.from_font());
    // Each character its own glyph: the quads' texture coordinates differ
    // from the '?' that stands in for a missing one.
    const auto first_quad = [&](std::string_view text) {
        std::vector<TextVertex> quads;
        face.append(text, 0, 20, quads);
        REQUIRE(quads.size() == 6);
        return std::pair{quads[0].u, quads[0].v};
    };
    const auto question = first_quad("?");
    for (const char* text : {"\xc3\xa9", "\xcf\x81", "\xc2\xb3", "\xe2\x88\x92", "\xe2\x88\x91"}) {
        INFO(text);
        CHECK(first_quad(text) != question);
    }
    // U+4E2D is in no fixed set and was not named: '?'; so is a malformed byte.
    CHECK(first_quad("\xe4\xb8\xad") == question);
    CHECK(first_quad("\xff") == question);
    // It used to skip every byte past '~': "é" drew nothing.
    std::vector<TextVertex> quads;
    face.append("d\xc3\xa9"
                "bit",
                0, 20, quads);
    CHECK(quads.size() == 5 * 6);
}
