// The full-disk contract (docs/contract.md, "A full disk"): a run whose
// writes fail for want of room stops, says what it kept and what was lost,
// keeps a playable MP4 of the frames so far when the video's index can still
// be written, leaves run.json saying "failed" with the reason even when no new
// file fits, and leaves no half-written file or ".partial" behind.
//
// The disk is filled portably and without root: the child run gets a file-size
// limit (RLIMIT_FSIZE, `ulimit -f`), so the first file to reach it fails with
// EFBIG as on a full disk. sphclip itself ignores SIGXFSZ; the test leaves the
// signal's default (kill) in the child, so a run that did not would die.

#include "support/run_limited.hpp"
#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"
#include "support/text.hpp"

extern "C" {
#include <libavformat/avformat.h>
}

#include <catch2/catch.hpp>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sph::test::contains;
using sph::test::read_text;
using sph::test::TempFolder;
using sph::test::write_text;

sph::test::LimitedRun run_with_file_size_limit(const TempFolder& tmp,
                                               const std::vector<std::string>& args,
                                               rlim_t max_bytes) {
    return sph::test::run_with_limit(tmp, args, RLIMIT_FSIZE, max_bytes);
}

// A small 2D tank, 36 particles, many quick frames; `size` the frame side.
std::string tank_scene(int size) {
    return R"({
    "domain": {"min": [0, 0], "max": [0.1, 0.1]},
    "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.03, 0.03]}]},
    "render": {"size": [)" +
           std::to_string(size) + ", " + std::to_string(size) + R"(]},
    "duration": 5, "fps": 200
})";
}

// The video's frame count, or -1 when it does not open and decode as an MP4.
long long mp4_frames(const fs::path& path) {
    AVFormatContext* video = nullptr;
    if (avformat_open_input(&video, path.c_str(), nullptr, nullptr) != 0)
        return -1;
    long long frames = -1;
    if (avformat_find_stream_info(video, nullptr) >= 0 && video->nb_streams == 1)
        frames = video->streams[0]->nb_frames;
    avformat_close_input(&video);
    return frames;
}

// Every file under `folder` whose name ends in ".partial".
std::vector<std::string> partial_files(const fs::path& folder) {
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(folder))
        if (entry.path().extension() == ".partial")
            found.push_back(entry.path().string());
    return found;
}

} // namespace

TEST_CASE("disk: when stats.csv meets a full disk, the MP4 of the frames so far is kept and "
          "run.json says failed",
          "[contract][disk]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", tank_scene(32));
    const fs::path out = tmp / "full";
    // 64 KiB: stats.csv (a row per frame) reaches it first, at about frame
    // 450; the tiny video stays far below, and the final run.json with its
    // per-frame timings would not fit as a new file.
    const auto run =
        run_with_file_size_limit(tmp,
                                 {"run", (tmp / "scene.json").string(), "--out", out.string(),
                                  "--no-png", "--threads", "1", "--quiet"},
                                 64 << 10);
    INFO(run.output);
    CHECK(run.exit_code == 1);
    // Said on stderr: why it stopped, what was kept, what was lost.
    CHECK(contains(run.output, "out of disk space"));
    CHECK(contains(run.output, (out / "stats.csv").string()));
    CHECK(contains(run.output, "File too large"));
    CHECK(contains(run.output, "clip.mp4 (the frames so far, playable)"));
    CHECK(contains(run.output, "lost: frames "));

    const json record = json::parse(read_text(out / "run.json"));
    CHECK(record.at("status") == "failed");
    CHECK(contains(record.at("error").get<std::string>(), "out of disk space"));
    CHECK(contains(record.at("error").get<std::string>(), "stats.csv"));
    CHECK(record.at("frames").get<long long>() > 0);

    // stats.csv ends with its last whole row, and the video holds those frames.
    const auto stats = sph::test::read_text_csv(out / "stats.csv");
    const std::string text = read_text(out / "stats.csv");
    REQUIRE(!text.empty());
    CHECK(text.back() == '\n');
    REQUIRE(!stats.rows.empty());
    for (const auto& row : stats.rows)
        CHECK(row.size() == stats.header.size());
    CHECK(std::stoll(stats.at(stats.rows.size() - 1, "frame")) + 1 ==
          record.at("frames").get<long long>());
    CHECK(mp4_frames(out / "clip.mp4") == record.at("frames").get<long long>());
    CHECK(partial_files(out).empty());
}

TEST_CASE("disk: when the MP4 itself meets a full disk, it is removed and said lost; the other "
          "outputs are kept",
          "[contract][disk]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", tank_scene(480));
    const fs::path out = tmp / "full";
    // 64 KiB: the 480x480 video reaches it long before stats.csv does.
    const auto run = run_with_file_size_limit(
        tmp,
        {"run", (tmp / "scene.json").string(), "--out", out.string(), "--threads", "1", "--quiet"},
        64 << 10);
    INFO(run.output);
    CHECK(run.exit_code == 1);
    CHECK(contains(run.output, "out of disk space"));
    CHECK(contains(run.output, "lost: clip.mp4"));
    const json record = json::parse(read_text(out / "run.json"));
    CHECK(record.at("status") == "failed");
    CHECK(contains(record.at("error").get<std::string>(), "clip.mp4"));
    // No video that does not play, no temporary.
    CHECK(!fs::exists(out / "clip.mp4"));
    CHECK(partial_files(out).empty());
    // The frames before the failure are whole PNGs.
    std::size_t pngs = 0;
    for (const auto& entry : fs::directory_iterator(out / "frames")) {
        CHECK(sph::test::is_png(entry.path()));
        ++pngs;
    }
    CHECK(pngs > 0);
}
