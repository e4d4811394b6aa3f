// `--progress auto|bar|lines|none` (src/cli/progress.*): in a log, plain
// lines with increasing frame numbers and a final one; none prints none;
// --quiet keeps only what was asked for by name; a bad value is refused.
// The lines' interval is set to 0 through SPHCLIP_PROGRESS_INTERVAL_S so
// that every frame prints one, without waiting 10 s.

#include "support/run_sphclip.hpp"
#include "support/small_tank.hpp"
#include "support/temp_folder.hpp"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

using sph::test::run_sphclip;
using sph::test::TempFolder;
using sph::test::write_text;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// 36 particles, 5 frames (0 to 0.1 s at 40 fps).
const std::string small_scene = sph::test::small_tank(0.1);

// The environment variable for the run of one test (each test case is its
// own process under ctest).
struct IntervalSetting {
    explicit IntervalSetting(const char* value) { setenv("SPHCLIP_PROGRESS_INTERVAL_S", value, 1); }
    ~IntervalSetting() { unsetenv("SPHCLIP_PROGRESS_INTERVAL_S"); }
};

sph::test::ProgramResult run_small(const TempFolder& tmp, std::vector<std::string> extra) {
    write_text(tmp / "scene.json", small_scene);
    std::vector<std::string> args{"run",      (tmp / "scene.json").string(),
                                  "--out",    (tmp / "out").string(),
                                  "--no-png", "--no-mp4"};
    args.insert(args.end(), extra.begin(), extra.end());
    return run_sphclip(tmp, args);
}

struct ProgressLine {
    int frame = 0, frames = 0;
    bool final = false;
};

// The output's progress lines; a line with a frame counter ("frame 3/")
// that is not a well-formed progress line fails the test.
std::vector<ProgressLine> progress_lines(const std::string& output) {
    static const std::regex line_form("sphclip: frame ([0-9]+)/([0-9]+)  t = [0-9]+\\.[0-9]{3} s  "
                                      "[0-9]+ steps/s  (ETA [0-9]+ s|ended after [0-9.]+ s)");
    static const std::regex counter("frame [0-9]+/");
    std::vector<ProgressLine> lines;
    std::istringstream in(output);
    std::string line;
    while (std::getline(in, line)) {
        if (!std::regex_search(line, counter))
            continue;
        INFO(line);
        std::smatch match;
        REQUIRE(std::regex_match(line, match, line_form));
        lines.push_back(
            {std::stoi(match[1]), std::stoi(match[2]), match[3].str().starts_with("ended")});
    }
    return lines;
}

void check_lines(const std::string& output) {
    const auto lines = progress_lines(output);
    REQUIRE(lines.size() >= 2);
    for (std::size_t k = 0; k < lines.size(); ++k) {
        CHECK(lines[k].frames == 5);
        CHECK(lines[k].final == (k + 1 == lines.size()));
        if (k > 0)
            CHECK(lines[k].frame > lines[k - 1].frame);
    }
    CHECK(lines.back().frame == 5);
    CHECK(!contains(output, "\r"));
}

} // namespace

TEST_CASE(
    "progress: --progress lines in a log: one well-formed line per interval, then a final one",
    "[cli][progress]") {
    TempFolder tmp;
    const IntervalSetting every_frame("0");
    const auto result = run_small(tmp, {"--progress", "lines"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    check_lines(result.output);
    // With the interval at 0 every frame has its line.
    CHECK(progress_lines(result.output).size() == 5);
    CHECK(contains(result.output, "sphclip: done"));
}

TEST_CASE("progress: --progress auto (the default) prints lines when the output is not a terminal",
          "[cli][progress]") {
    TempFolder tmp;
    const IntervalSetting every_frame("0");
    const auto result = run_small(tmp, {});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    check_lines(result.output);
}

TEST_CASE("progress: --progress none prints no progress, and the rest as before",
          "[cli][progress]") {
    TempFolder tmp;
    const IntervalSetting every_frame("0");
    const auto result = run_small(tmp, {"--progress", "none"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(progress_lines(result.output).empty());
    CHECK(contains(result.output, "sphclip: done"));
}

TEST_CASE("progress: --quiet prints no progress unless --progress names bar or lines",
          "[cli][progress]") {
    TempFolder tmp;
    const IntervalSetting every_frame("0");
    const auto quiet = run_small(tmp, {"--quiet"});
    INFO(quiet.output);
    REQUIRE(quiet.exit_code == 0);
    CHECK(quiet.output.empty());

    const auto lines = run_small(tmp, {"--quiet", "--progress", "lines"});
    INFO(lines.output);
    REQUIRE(lines.exit_code == 0);
    check_lines(lines.output);
    CHECK(!contains(lines.output, "sphclip: done"));
}

TEST_CASE("progress: --progress bar draws the line in place even in a log", "[cli][progress]") {
    TempFolder tmp;
    const auto result = run_small(tmp, {"--progress", "bar", "--quiet"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(contains(result.output, "\rframe "));
    CHECK(contains(result.output, "frame 5/5"));
}

TEST_CASE("progress: a bad --progress or progress interval is refused, naming it",
          "[cli][progress]") {
    TempFolder tmp;
    const auto flag = run_small(tmp, {"--progress", "sometimes"});
    INFO(flag.output);
    CHECK(flag.exit_code == 2);
    CHECK(contains(flag.output, "--progress"));

    const IntervalSetting bad("soon");
    const auto interval = run_small(tmp, {});
    INFO(interval.output);
    CHECK(interval.exit_code == 2);
    CHECK(contains(interval.output, "SPHCLIP_PROGRESS_INTERVAL_S"));
    CHECK(!std::filesystem::exists(tmp / "out" / "stats.csv"));
}
