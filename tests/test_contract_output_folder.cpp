// The output-folder and signal contract (docs/contract.md): a run owns its
// folder (a second run into it is refused, naming the holder), never writes
// or deletes through a symbolic link, never overwrites a file no sphclip
// run made, removes all of an earlier run's outputs, and treats SIGHUP,
// SIGQUIT and SIGPIPE like SIGINT: it stops between steps and finalises.

#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"
#include "support/text.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <catch2/catch.hpp>
#include <chrono>
#include <csignal>
#include <fcntl.h>
#include <filesystem>
#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sph::test::read_text;
using sph::test::run_sphclip;
using sph::test::shell_quote;
using sph::test::TempFolder;
using sph::test::write_text;

using sph::test::contains;

// A small 2D tank: 36 particles, quick frames.
const std::string small_scene = R"({
    "domain": {"min": [0, 0], "max": [0.1, 0.1]},
    "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.03, 0.03]}]},
    "render": {"size": [64, 64]},
    "duration": 0.05, "fps": 40
})";

// sphclip started in the background with stdout and stderr to `log` (or
// stdout to the write end `stdout_fd` of a pipe); the pid.
pid_t start_sphclip(const std::vector<std::string>& args, const fs::path& log, int stdout_fd = -1) {
    const pid_t pid = fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int log_fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        dup2(stdout_fd >= 0 ? stdout_fd : log_fd, STDOUT_FILENO);
        dup2(log_fd, STDERR_FILENO);
        setenv("OMP_WAIT_POLICY", "passive", 1);
        std::vector<char*> argv{const_cast<char*>(SPHCLIP_EXE)};
        for (const auto& a : args)
            argv.push_back(const_cast<char*>(a.c_str()));
        argv.push_back(nullptr);
        execv(SPHCLIP_EXE, argv.data());
        _exit(127);
    }
    return pid;
}

int wait_exit(pid_t pid) {
    int status = 0;
    waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// Waits until `path` exists and holds `text` (at most 30 s).
bool wait_for(const fs::path& path, const std::string& text) {
    for (int k = 0; k < 300; ++k) {
        if (fs::exists(path) && contains(read_text(path), text))
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
    return false;
}

bool playable_mp4(const fs::path& path) {
    AVFormatContext* video = nullptr;
    if (avformat_open_input(&video, path.c_str(), nullptr, nullptr) != 0)
        return false;
    const bool ok = avformat_find_stream_info(video, nullptr) >= 0 && video->nb_streams == 1 &&
                    video->streams[0]->nb_frames >= 1;
    avformat_close_input(&video);
    return ok;
}

} // namespace

TEST_CASE("output folder: a second run into a running run's folder is refused, naming its pid",
          "[contract][output_folder]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    const fs::path out = tmp / "shared";
    // Run A: long enough to be running when B starts.
    const pid_t a = start_sphclip({"run", (tmp / "scene.json").string(), "--out", out.string(),
                                   "--duration", "100", "--export", "csv", "--threads", "1"},
                                  tmp / "a.log");
    REQUIRE(wait_for(out / "run.json", "\"running\""));
    const auto b = run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--out", out.string(),
                                     "--duration", "0.05", "--threads", "1"});
    INFO(b.output);
    CHECK(b.exit_code == 2);
    CHECK(contains(b.output, out.string()));
    CHECK(contains(b.output, fmt::format("another sphclip run (pid {})", a)));
    // A is untouched by B, and ends cleanly when asked.
    kill(a, SIGINT);
    CHECK(wait_exit(a) == 130);
    const json run = json::parse(read_text(out / "run.json"));
    CHECK(run.at("status") == "interrupted");
    CHECK(run.at("command").get<std::string>().find("--duration 100") != std::string::npos);
    // After A, the folder is free again.
    CHECK(run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--out", out.string(), "--no-mp4",
                            "--threads", "1", "--quiet"})
              .exit_code == 0);
}

TEST_CASE("output folder: nothing is written or deleted through a symbolic link",
          "[contract][output_folder]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    const std::vector<std::string> run{
        "run",    (tmp / "scene.json").string(), "--out", (tmp / "out").string(), "--threads", "1",
        "--quiet"};

    SECTION("a file that links elsewhere") {
        fs::create_directories(tmp / "out");
        write_text(tmp / "elsewhere.txt", "the user's file\n");
        for (const char* name : {"stats.csv", "run.json", "clip.mp4", "run.json.partial"}) {
            INFO(name);
            fs::create_symlink(tmp / "elsewhere.txt", tmp / "out" / name);
            const auto result = run_sphclip(tmp, run);
            INFO(result.output);
            CHECK(result.exit_code == 2);
            CHECK(contains(result.output, std::string(name) + " is a symbolic link"));
            CHECK(read_text(tmp / "elsewhere.txt") == "the user's file\n");
            fs::remove(tmp / "out" / name);
        }
    }
    SECTION("a frames folder that links to the user's pictures") {
        fs::create_directories(tmp / "out");
        fs::create_directories(tmp / "userpics");
        write_text(tmp / "userpics" / "frame_00042.png", "a user's picture");
        fs::create_directory_symlink(tmp / "userpics", tmp / "out" / "frames");
        const auto result = run_sphclip(tmp, run);
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "frames is a symbolic link"));
        CHECK(read_text(tmp / "userpics" / "frame_00042.png") == "a user's picture");
        CHECK(fs::directory_iterator(tmp / "userpics")->path().filename() == "frame_00042.png");
    }
    SECTION("a frame inside frames/ that links elsewhere, after an earlier run") {
        REQUIRE(run_sphclip(tmp, run).exit_code == 0);
        write_text(tmp / "target.png", "kept");
        fs::remove(tmp / "out" / "frames" / "frame_00001.png");
        fs::create_symlink(tmp / "target.png", tmp / "out" / "frames" / "frame_00001.png");
        const auto result = run_sphclip(tmp, run);
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "frames/frame_00001.png is a symbolic link"));
        CHECK(read_text(tmp / "target.png") == "kept");
    }
}

TEST_CASE("output folder: entries of the wrong type and a user's files are refused, "
          "untouched and with nothing written",
          "[contract][output_folder]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    const fs::path out = tmp / "out";
    const std::vector<std::string> run{
        "run", (tmp / "scene.json").string(), "--out", out.string(), "--threads", "1", "--quiet"};
    fs::create_directories(out);

    SECTION("run.json is a folder") {
        fs::create_directories(out / "run.json");
        const auto result = run_sphclip(tmp, run);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "run.json is a folder where a run writes a file"));
    }
    SECTION("frames is a file") {
        write_text(out / "frames", "x");
        const auto result = run_sphclip(tmp, run);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "frames is a file where a run writes a folder"));
    }
    SECTION("a pipe named stats.csv beside an earlier run's run.json") {
        REQUIRE(run_sphclip(tmp, run).exit_code == 0);
        fs::remove(out / "stats.csv");
        REQUIRE(::mkfifo((out / "stats.csv").c_str(), 0644) == 0);
        // It used to be removed as the earlier run's stats.csv.
        const auto result = run_sphclip(tmp, run);
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "stats.csv is not a regular file"));
        CHECK(fs::is_fifo(out / "stats.csv"));
        fs::remove(out / "stats.csv");
        fs::remove(out / "run.json");
    }
    SECTION("a clip.mp4 that no sphclip run made") {
        write_text(out / "clip.mp4", "the user's video");
        const auto result = run_sphclip(tmp, run);
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "no run.json of a sphclip run"));
        CHECK(read_text(out / "clip.mp4") == "the user's video");
    }
    // Nothing of a run was written: no run.json, no temporary, no stats.
    for (const char* name : {"run.json.partial", "stats.csv", "clip.mp4.partial"})
        CHECK_FALSE(fs::exists(out / name));
    CHECK_FALSE(fs::is_regular_file(out / "run.json"));
}

TEST_CASE("output folder: the filesystem's root is refused as an output folder, even through "
          "a link",
          "[contract][output_folder]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    fs::create_directory_symlink("/", tmp / "root");
    // As root the run used to write /run.json, /stats.csv and /.sphclip.lock.
    // So that a regression cannot write there, the test runs it as nobody
    // when it is root (from a copy of the program nobody can reach): / is
    // then read-only to it, and only the message tells the two refusals apart.
    std::string program = SPHCLIP_EXE, as_user;
    if (::geteuid() == 0) {
        program = (tmp / "sphclip").string();
        fs::copy_file(SPHCLIP_PROGRAM, program); // the program proper: a launcher alone finds none
        fs::permissions(tmp.path(), fs::perms::all);
        fs::permissions(tmp / "scene.json", fs::perms::owner_all | fs::perms::others_read);
        as_user = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
    }
    for (const std::string& out : {std::string("/"), (tmp / "root").string()}) {
        INFO(out);
        const std::string command =
            fmt::format("cd {} && {}{} run {} --out {} --no-png --no-mp4 --threads 1 > {} 2>&1",
                        shell_quote(tmp.path().string()), as_user, shell_quote(program),
                        shell_quote((tmp / "scene.json").string()), shell_quote(out),
                        shell_quote((tmp / "log").string()));
        const int status = std::system(command.c_str());
        const std::string log = read_text(tmp / "log");
        INFO(log);
        CHECK((WIFEXITED(status) ? WEXITSTATUS(status) : -1) == 2);
        CHECK(contains(log, "--out: " + out + " is the filesystem's root"));
    }
}

TEST_CASE("output folder: a frames/ the run cannot write to is refused before anything is "
          "written",
          "[contract][output_folder]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    const fs::path out = tmp / "out";
    fs::create_directories(out / "frames");
    // Root writes through any permission bits: as root the run is made as
    // nobody, from a copy of the program that nobody can reach.
    std::string program = SPHCLIP_EXE;
    std::string as_user;
    if (::geteuid() == 0) {
        program = (tmp / "sphclip").string();
        fs::copy_file(SPHCLIP_PROGRAM, program); // the program proper: a launcher alone finds none
        fs::permissions(tmp.path(), fs::perms::all);
        fs::permissions(out, fs::perms::all);
        fs::permissions(tmp / "scene.json", fs::perms::owner_all | fs::perms::others_read);
        as_user = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
    }
    fs::permissions(out / "frames", fs::perms::owner_read | fs::perms::owner_exec |
                                        fs::perms::group_read | fs::perms::group_exec |
                                        fs::perms::others_read | fs::perms::others_exec);
    const std::string command = fmt::format(
        "cd {} && {}{} run {} --out {} --threads 1 > {} 2>&1", shell_quote(tmp.path().string()),
        as_user, shell_quote(program), shell_quote((tmp / "scene.json").string()),
        shell_quote(out.string()), shell_quote((tmp / "log").string()));
    const int status = std::system(command.c_str());
    const std::string log = read_text(tmp / "log");
    INFO(log);
    // It used to write run.json, stats.csv and clip.mp4, then exit 1 at the
    // first PNG.
    CHECK((WIFEXITED(status) ? WEXITSTATUS(status) : -1) == 2);
    CHECK(contains(log, "frames/ is not writable"));
    for (const char* name :
         {"run.json", "run.json.partial", "stats.csv", "clip.mp4", "clip.mp4.partial"})
        CHECK_FALSE(fs::exists(out / name));
    fs::permissions(out / "frames", fs::perms::owner_all);
}

TEST_CASE("output folder: a run whose FFmpeg cannot be loaded writes nothing; --no-mp4 needs none",
          "[contract][output_folder]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    // FFmpeg is loaded when a run starts to write video, not linked
    // (src/platform/shared_library.hpp): a libavcodec that cannot be loaded,
    // found first on the library path, stands for a server without FFmpeg.
    fs::create_directories(tmp / "lib");
    write_text(tmp / "lib" / fmt::format("libavcodec.so.{}", LIBAVCODEC_VERSION_MAJOR), "");
    const auto run = [&](const fs::path& out, const std::string& more) {
        const std::string command =
            fmt::format("cd {} && LD_LIBRARY_PATH={} {} run {} --out {} --threads 1 {} > {} 2>&1",
                        shell_quote(tmp.path().string()), shell_quote((tmp / "lib").string()),
                        shell_quote(SPHCLIP_EXE), shell_quote((tmp / "scene.json").string()),
                        shell_quote(out.string()), more, shell_quote((tmp / "log").string()));
        const int status = std::system(command.c_str());
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    };
    CHECK(run(tmp / "out", "") == 1);
    std::string log = read_text(tmp / "log");
    INFO(log);
    CHECK(contains(log, "cannot write clip.mp4: cannot load the shared library libavcodec.so."));
    CHECK(contains(log, "--no-mp4 runs need no FFmpeg"));
    CHECK_FALSE(fs::exists(tmp / "out")); // refused before the folder was made
    // The same run without the video: its frames, no FFmpeg loaded.
    CHECK(run(tmp / "frames_only", "--no-mp4 --quiet") == 0);
    log = read_text(tmp / "log");
    INFO(log);
    CHECK(fs::exists(tmp / "frames_only" / "frames" / "frame_00001.png"));
    CHECK_FALSE(fs::exists(tmp / "frames_only" / "clip.mp4"));
}

TEST_CASE("output folder: a re-run removes every output of the earlier run, and says so",
          "[contract][output_folder]") {
    TempFolder tmp;
    write_text(tmp / "scene.json", small_scene);
    const fs::path out = tmp / "out";
    std::vector<std::string> run{
        "run", (tmp / "scene.json").string(), "--out", out.string(), "--threads", "1", "--export",
        "vtk"};
    REQUIRE(run_sphclip(tmp, run).exit_code == 0);
    REQUIRE(fs::exists(out / "clip.mp4"));
    // Leftovers of a run that was killed: temporaries.
    write_text(out / "clip.mp4.partial", "stale");
    write_text(out / "frames" / "frame_00007.png.partial", "stale");
    // A user's own file beside the outputs is theirs and stays.
    write_text(out / "notes.txt", "mine");

    const auto again = run_sphclip(tmp, {"run", (tmp / "scene.json").string(), "--out",
                                         out.string(), "--threads", "1", "--no-mp4"});
    INFO(again.output);
    REQUIRE(again.exit_code == 0);
    CHECK(contains(again.output, "replacing the earlier run in " + out.string()));
    CHECK(contains(again.output, "clip.mp4"));
    CHECK_FALSE(fs::exists(out / "clip.mp4"));
    CHECK_FALSE(fs::exists(out / "clip.mp4.partial"));
    CHECK_FALSE(fs::exists(out / "frames" / "frame_00007.png.partial"));
    CHECK_FALSE(fs::exists(out / "particles.pvd"));
    CHECK_FALSE(fs::exists(out / "particles" / "frame_00000.vtp"));
    CHECK(fs::exists(out / "frames" / "frame_00002.png"));
    CHECK(read_text(out / "notes.txt") == "mine");
}

TEST_CASE("signals: SIGHUP, SIGQUIT and a closed output pipe stop a run like SIGINT",
          "[contract][signals]") {
    for (const int signal : {SIGHUP, SIGQUIT, SIGPIPE}) {
        INFO("signal " << signal);
        TempFolder tmp;
        write_text(tmp / "scene.json", small_scene);
        const fs::path out = tmp / "out";
        const std::vector<std::string> args{"run",        (tmp / "scene.json").string(),
                                            "--out",      out.string(),
                                            "--duration", "100",
                                            "--threads",  "1"};
        pid_t pid = -1;
        if (signal == SIGPIPE) {
            // stdout into a pipe whose reader is gone: the first line written
            // raises SIGPIPE, as with `sphclip run ... | head -1` after head.
            int fds[2];
            REQUIRE(pipe(fds) == 0);
            close(fds[0]);
            pid = start_sphclip(args, tmp / "log", fds[1]);
            close(fds[1]);
        } else {
            pid = start_sphclip(args, tmp / "log");
            REQUIRE(wait_for(out / "stats.csv", "\n1,"));
            kill(pid, signal);
        }
        CHECK(wait_exit(pid) == 130);
        const json run = json::parse(read_text(out / "run.json"));
        CHECK(run.at("status") == "interrupted");
        CHECK(contains(run.at("error").get<std::string>(), fmt::format("signal {}", signal)));
        // The video is finalised with the frames written (a closed pipe can
        // stop the run before its first frame).
        if (run.at("frames").get<int>() > 0)
            CHECK(playable_mp4(out / "clip.mp4"));
        CHECK_FALSE(fs::exists(out / "clip.mp4.partial"));
    }
}

namespace {

// True once `pid` runs sphclip (after the exec: the forked test's own
// handlers are gone) and has a handler for `signal` (its SigCgt mask in
// /proc/PID/status): sphclip's main() has begun. Waits at most 60 s.
bool catches(pid_t pid, int signal) {
    // The program proper: the launcher (SPHCLIP_EXE) becomes it at once.
    const fs::path program = fs::canonical(SPHCLIP_PROGRAM);
    for (int k = 0; k < 60000; ++k) {
        std::error_code ec;
        const fs::path exe = fs::read_symlink(fmt::format("/proc/{}/exe", pid), ec);
        const std::string status = read_text(fmt::format("/proc/{}/status", pid));
        if (ec || exe != program) {
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
            continue;
        }
        const auto at = status.find("SigCgt:");
        if (at != std::string::npos &&
            (std::stoull(status.substr(at + 7), nullptr, 16) >> (signal - 1) & 1))
            return true;
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return false;
}

} // namespace

TEST_CASE("signals: SIGTERM at any moment of start-up ends the run with exit 130",
          "[contract][signals]") {
    // A 3D scene whose setup (scene, lattice, walls, GL context) takes a
    // while. The signal is sent as soon as main() has installed its handler
    // (seen in /proc), and then a little later: it lands in the start-up or
    // early in the run; either way the exit is 130. (Before main() starts,
    // no program can catch a signal: docs/contract.md.)
    TempFolder tmp;
    for (const int delay_ms : {0, 50, 300}) {
        INFO("SIGTERM " << delay_ms << " ms after main() began");
        const fs::path out = tmp / fmt::format("out{}", delay_ms);
        const pid_t pid =
            start_sphclip({"run", std::string(SPHCLIP_SOURCE_DIR) + "/scenes/dam_break_3d.json",
                           "--out", out.string(), "--duration", "100", "--threads", "1"},
                          tmp / "log");
        REQUIRE(catches(pid, SIGTERM));
        std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
        kill(pid, SIGTERM);
        const int code = wait_exit(pid);
        INFO(read_text(tmp / "log"));
        CHECK(code == 130);
        // Either nothing was written, or a run.json that says why it stopped.
        if (fs::exists(out / "run.json"))
            CHECK(json::parse(read_text(out / "run.json")).at("status") == "interrupted");
    }
}
