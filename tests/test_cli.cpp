// End to end through the real program (src/cli/): outputs of a run, exit
// codes, messages, and that bad input leaves nothing behind.

#include "output/png_io.hpp"
#include "scene/scene.hpp"
#include "sph/stage_times.hpp"
#include "support/run_sphclip.hpp"
#include "support/temp_folder.hpp"
#include "support/text.hpp"

extern "C" {
#include <libavformat/avformat.h>
}

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using sph::test::read_text;
using sph::test::TempFolder;
using sph::test::write_text;

std::vector<std::string> split(const std::string& text, char separator) {
    std::vector<std::string> parts;
    std::string part;
    std::istringstream in(text);
    while (std::getline(in, part, separator))
        parts.push_back(part);
    return parts;
}

using sph::test::contains;
using sph::test::shell_quote;
using Result = sph::test::ProgramResult;

// Runs sphclip with `args` in the folder `cwd` (support/run_sphclip.hpp).
Result sphclip(const TempFolder& tmp, const std::vector<std::string>& args,
               const fs::path& cwd = fs::current_path()) {
    return sph::test::run_sphclip(tmp, args, cwd);
}

// `sphclip run SCENE --out OUT` writing data outputs only, with `extra` flags.
Result run_scene(const TempFolder& tmp, const fs::path& scene, const fs::path& out,
                 const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{"run",      scene.string(), "--out",  out.string(),
                                  "--no-png", "--no-mp4",     "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    return sphclip(tmp, args);
}

struct Csv {
    std::string header;
    std::vector<std::vector<std::string>> rows;

    std::size_t column(const std::string& name) const {
        const auto names = split(header, ',');
        const auto it = std::find(names.begin(), names.end(), name);
        REQUIRE(it != names.end());
        return std::size_t(it - names.begin());
    }
    double number(std::size_t row, const std::string& name) const {
        return std::stod(rows.at(row).at(column(name)));
    }
};

Csv read_csv(const fs::path& path) {
    const auto lines = split(read_text(path), '\n');
    Csv csv;
    if (lines.empty())
        return csv;
    csv.header = lines[0];
    for (std::size_t i = 1; i < lines.size(); ++i)
        csv.rows.push_back(split(lines[i], ','));
    return csv;
}

// stats.csv without its last column, the wall-clock seconds.
std::string stats_without_wall_time(const fs::path& path) {
    std::string out;
    for (const auto& line : split(read_text(path), '\n'))
        out += line.substr(0, line.rfind(',')) + "\n";
    return out;
}

// 6 x 6 = 36 particles, 3 frames (t = 0, 0.025, 0.05).
const std::string tiny_2d = R"({
    // a small block in the corner of a small box
    "domain": {"min": [0, 0], "max": [0.1, 0.1]},
    "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.03, 0.03]}]},
    "duration": 0.05,
    "fps": 40
})";
constexpr std::size_t tiny_2d_particles = 36;

// 6 x 6 x 6 = 216 particles, 3 frames.
const std::string tiny_3d = R"({
    "dimension": 3,
    "domain": {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]},
    "fluid": {"spacing": 0.01, "blocks": [{"min": [0, 0, 0], "max": [0.06, 0.06, 0.06]}]},
    "duration": 0.05,
    "fps": 40
})";
constexpr std::size_t tiny_3d_particles = 216;

const std::string stats_header =
    "frame,time,steps,dt,particles,density_avg,density_max,density_error_avg_pct,"
    "density_error_max_pct,kinetic_energy,max_speed,dt_min,dt_max,pressure_iterations,"
    "divergence_iterations,retries,obstacle_pushes,state_hash,wall_s";

fs::path write_scene(const TempFolder& tmp, const std::string& text,
                     const std::string& name = "scene.json") {
    write_text(tmp / name, text);
    return tmp / name;
}

// Checks everything `run --export csv --export vtk` writes for a completed run.
void check_run_outputs(const fs::path& out, int dimension, std::size_t particles,
                       std::size_t frames, double fps) {
    // stats.csv: one row per frame, taken when the time crosses k / fps.
    const Csv stats = read_csv(out / "stats.csv");
    CHECK(stats.header == stats_header);
    REQUIRE(stats.rows.size() == frames);
    for (std::size_t k = 0; k < frames; ++k) {
        INFO("frame " << k);
        REQUIRE(stats.rows[k].size() == 19);
        CHECK(stats.number(k, "frame") == double(k));
        CHECK(stats.number(k, "particles") == double(particles));
        const double time = stats.number(k, "time");
        // Steps land on the frame times; times are written with 9 significant digits.
        CHECK(time == Approx(double(k) / fps).margin(1e-8));
        if (k > 0) {
            // dt: the mean step since the previous frame, within the range written beside it.
            const double dt = stats.number(k, "dt");
            CHECK(dt > 0);
            CHECK(stats.number(k, "dt_min") <= dt * (1 + 1e-5));
            CHECK(stats.number(k, "dt_max") >= dt * (1 - 1e-5));
            CHECK(time >= stats.number(k - 1, "time"));
            CHECK(stats.number(k, "steps") >= stats.number(k - 1, "steps"));
        }
    }
    CHECK(stats.number(0, "time") == 0);
    CHECK(stats.number(0, "steps") == 0);

    // Particle exports: a CSV and a VTK file per frame, and the time series.
    const std::string csv_header = dimension == 2 ? "x,y,vx,vy,density,pressure,id,time"
                                                  : "x,y,z,vx,vy,vz,density,pressure,id,time";
    // .sphclip.lock: the run's hold on its folder (docs/contract.md).
    std::set<fs::path> expected{out / "stats.csv", out / "run.json", out / "particles.pvd",
                                out / "particles", out / ".sphclip.lock"};
    const std::string pvd = read_text(out / "particles.pvd");
    for (std::size_t k = 0; k < frames; ++k) {
        INFO("frame " << k);
        const std::string stem = fmt::format("frame_{:05d}", k);
        const Csv frame = read_csv(out / "particles" / (stem + ".csv"));
        CHECK(frame.header == csv_header);
        CHECK(frame.rows.size() == particles);
        std::set<std::string> ids;
        for (const auto& row : frame.rows) {
            REQUIRE(row.size() == std::size_t(2 * dimension + 4));
            ids.insert(row[std::size_t(2 * dimension + 2)]);
            // Every row carries the frame's time, as stats.csv has it.
            CHECK(std::stod(row.back()) == Approx(stats.number(k, "time")).margin(1e-8));
        }
        CHECK(ids.size() == particles); // one row per particle
        const std::string vtp = read_text(out / "particles" / (stem + ".vtp"));
        CHECK(contains(vtp, fmt::format("NumberOfPoints=\"{}\"", particles)));
        CHECK(contains(vtp, "compressor=\"vtkZLibDataCompressor\""));
        CHECK(contains(vtp, "<AppendedData encoding=\"raw\">"));
        CHECK(contains(vtp, "</VTKFile>"));
        CHECK(contains(pvd, fmt::format("file=\"particles/{}.vtp\"", stem)));
        expected.insert(out / "particles" / (stem + ".csv"));
        expected.insert(out / "particles" / (stem + ".vtp"));
    }
    CHECK(std::size_t(std::count(pvd.begin(), pvd.end(), '\n')) == frames + 5);

    // Nothing else: no temporary files left from the atomic writes.
    for (const auto& entry : fs::recursive_directory_iterator(out)) {
        INFO(entry.path().string());
        CHECK(expected.count(entry.path()) == 1);
    }

    // run.json: the record of the run, with the scene as resolved.
    const json run = json::parse(read_text(out / "run.json"));
    CHECK(run.at("status") == "completed");
    CHECK(run.at("particles") == particles);
    CHECK(run.at("frames") == frames);
    CHECK(run.at("steps").get<double>() == stats.number(frames - 1, "steps"));
    CHECK(run.at("wall_s").get<double>() >= 0);
    const json& scene = run.at("scene");
    CHECK(scene.at("dimension") == dimension);
    CHECK(scene.at("fluid").at("mass").get<double>() > 0);
    CHECK(scene.at("fluid").at("smoothing_length").get<double>() > 0);
    // Adaptive steps (no solver.dt), within the scene's bounds.
    CHECK(scene.at("solver").at("dt").is_null());
    CHECK(run.at("derived").at("dt").get<double>() > 0);
    for (std::size_t k = 1; k < frames; ++k)
        CHECK(stats.number(k, "dt_max") <= scene.at("solver").at("dt_max").get<double>());
    // The resolved scene reads back as the same scene.
    CHECK(sph::to_json(sph::parse_scene(scene.dump(), "run.json", {})) == scene);
    // Where the time went: the step's stages, no render or encode (these
    // runs draw nothing), shares of the wall time.
    std::set<std::string> stages;
    double share = 0;
    for (const json& stage : run.at("stages")) {
        stages.insert(stage.at("name").get<std::string>());
        if (stage.contains("within")) {
            // A part computed inside a stage (the seed's viscosity in its
            // pressure pass): timed with that stage, no seconds of its own.
            CHECK(stage.size() == 2);
            CHECK(std::find(sph::stage_names.begin(), sph::stage_names.end(),
                            stage.at("within").get<std::string>()) != sph::stage_names.end());
            continue;
        }
        CHECK(stage.at("seconds").get<double>() > 0);
        CHECK(stage.at("ns_per_particle_step").get<double>() > 0);
        share += stage.at("share").get<double>();
    }
    CHECK(share <= 1.0 + 1e-9);
    for (const char* name : {"neighbour search", "density", "gravity", "integration"})
        CHECK(stages.count(name) == 1);
    for (const char* name : {"render", "readback", "encode"})
        CHECK(stages.count(name) == 0);
}

} // namespace

TEST_CASE("run writes stats, particle exports and run.json for a 2D scene", "[cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "out";
    const auto result =
        run_scene(tmp, write_scene(tmp, tiny_2d), out, {"--export", "csv", "--export", "vtk"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(result.output.empty()); // --quiet
    check_run_outputs(out, 2, tiny_2d_particles, 3, 40);
}

TEST_CASE("run writes stats, particle exports and run.json for a 3D scene", "[cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "out";
    const auto result =
        run_scene(tmp, write_scene(tmp, tiny_3d), out, {"--export", "csv", "--export", "vtk"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    check_run_outputs(out, 3, tiny_3d_particles, 3, 40);
}

TEST_CASE("run without --out writes to out/<scene name>/", "[cli]") {
    TempFolder tmp;
    const auto result = sphclip(
        tmp, {"run", write_scene(tmp, tiny_2d, "corner.json").string(), "--no-png", "--no-mp4"},
        tmp.path());
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(contains(result.output, "36 particles")); // the summary line without --quiet
    CHECK(read_csv(tmp / "out/corner/stats.csv").rows.size() == 3);
    CHECK(fs::exists(tmp / "out/corner/run.json"));
}

TEST_CASE("a second run in the same folder leaves no frames of the first", "[cli]") {
    TempFolder tmp;
    const fs::path scene = write_scene(tmp, tiny_2d);
    const fs::path out = tmp / "out";
    const std::vector<std::string> exports{"--export", "csv", "--export", "vtk"};
    auto longer = exports;
    longer.insert(longer.end(), {"--duration", "0.1"});
    REQUIRE(run_scene(tmp, scene, out, longer).exit_code == 0);
    REQUIRE(fs::exists(out / "particles/frame_00004.csv"));

    const auto result = run_scene(tmp, scene, out, exports);
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    check_run_outputs(out, 2, tiny_2d_particles, 3, 40);
}

TEST_CASE("bad input exits 2, names the file and field, and writes nothing", "[cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "out";
    const fs::path scene = tmp / "scene.json";
    write_text(scene, tiny_2d);

    auto expect_refused = [&](const std::vector<std::string>& args, const fs::path& out_folder,
                              const std::vector<std::string>& words) {
        const auto result = sphclip(tmp, args);
        INFO(result.output);
        CHECK(result.exit_code == 2);
        for (const auto& word : words)
            CHECK(contains(result.output, word));
        CHECK_FALSE(fs::exists(out_folder));
    };
    auto refused_run = [&](const std::vector<std::string>& extra,
                           const std::vector<std::string>& words) {
        std::vector<std::string> args{"run",        scene.string(), "--out",
                                      out.string(), "--no-png",     "--no-mp4"};
        args.insert(args.end(), extra.begin(), extra.end());
        expect_refused(args, out, words);
    };

    SECTION("a missing scene file") {
        fs::remove(scene);
        refused_run({}, {scene.string(), "cannot read the scene file"});
    }
    SECTION("invalid JSON") {
        write_text(scene, "{\n  \"fps\": 30,\n  \"duration\": ,\n}\n");
        refused_run({}, {scene.string(), "invalid JSON at line 3, column 15"});
    }
    SECTION("an unknown key") {
        write_text(scene, R"({"material": {"viscosty": 1}})");
        refused_run({},
                    {scene.string() + ": material.viscosty: unknown key", "'material.viscosity'"});
    }
    SECTION("a value of the wrong type") {
        write_text(scene, R"({"fps": "ten"})");
        refused_run({}, {scene.string() + ": fps: expected a number"});
    }
    SECTION("a value out of range") {
        write_text(scene, R"({"fluid": {"spacing": -0.01}})");
        refused_run({}, {scene.string() + ": fluid.spacing: must be greater than 0"});
    }
    SECTION("--set without '='") {
        refused_run({"--set", "fps"}, {"command line: --set: expected KEY=VALUE"});
    }
    SECTION("--set with a bad value") {
        refused_run({"--set", "fps=0"}, {"fps (from --set)"});
    }
    SECTION("--set with an unknown key") {
        refused_run({"--set", "solver.nmae=seed"}, {"solver.nmae (from --set)", "'solver.name'"});
    }
    SECTION("an unknown flag") {
        refused_run({"--bogus"}, {"--bogus"});
    }
    SECTION("--threads 0") {
        refused_run({"--threads", "0"}, {"--threads"});
    }
    SECTION("an unknown export format") {
        refused_run({"--export", "pdf"}, {"--export"});
    }
    SECTION("an output folder that cannot be created") {
        const fs::path proc = fmt::format("/proc/sphclip_test_{}", ::getpid());
        expect_refused({"run", scene.string(), "--out", proc.string(), "--no-png", "--no-mp4"},
                       proc, {"--out", proc.string()});
    }
    SECTION("an output folder under a regular file") {
        write_text(tmp / "file", "keep me");
        const fs::path under = tmp / "file" / "out";
        expect_refused({"run", scene.string(), "--out", under.string(), "--no-png", "--no-mp4"},
                       under, {"--out"});
        CHECK(read_text(tmp / "file") == "keep me");
    }
    SECTION("an output folder that is a regular file") {
        write_text(out, "keep me");
        const auto result = sphclip(tmp, {"run", scene.string(), "--out", out.string()});
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "--out"));
        CHECK(read_text(out) == "keep me");
    }
}

// Fails while nlohmann's number-overflow exception escapes the scene parser:
// the program exits 1 with a bare library message.
TEST_CASE("a number too large for a double exits 2 naming the field", "[cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "out";
    const fs::path scene = write_scene(tmp, R"({"fps": 1e999})");
    const auto result = run_scene(tmp, scene, out);
    INFO(result.output);
    CHECK(result.exit_code == 2);
    CHECK(contains(result.output, scene.string() + ": fps"));
    CHECK_FALSE(fs::exists(out));
}

TEST_CASE("the keys command lists every scene key, and --version the version", "[cli]") {
    TempFolder tmp;
    const auto keys = sphclip(tmp, {"keys"});
    INFO(keys.output);
    CHECK(keys.exit_code == 0);
    CHECK(contains(keys.output, "material.viscosity"));
    for (const auto& key : sph::scene_keys())
        CHECK(contains(keys.output, key.path + " "));

    const auto markdown = sphclip(tmp, {"keys", "--markdown"});
    CHECK(markdown.exit_code == 0);
    CHECK(markdown.output.starts_with("| key |"));
    CHECK(contains(markdown.output, "| `material.viscosity` |"));

    const auto version = sphclip(tmp, {"--version"});
    CHECK(version.exit_code == 0);
    CHECK(contains(version.output, SPHCLIP_VERSION));

    const auto nothing = sphclip(tmp, {});
    CHECK(nothing.exit_code == 2); // a subcommand is required
}

TEST_CASE("the duration and fps flags set the frames and their times", "[cli]") {
    TempFolder tmp;
    const fs::path scene = write_scene(tmp, tiny_2d);
    const fs::path out = tmp / "out";
    auto times_with = [&](const std::vector<std::string>& flags) {
        const auto result = run_scene(tmp, scene, out, flags);
        INFO(result.output);
        REQUIRE(result.exit_code == 0);
        std::vector<double> times;
        const Csv stats = read_csv(out / "stats.csv");
        for (std::size_t k = 0; k < stats.rows.size(); ++k)
            times.push_back(stats.number(k, "time"));
        return times;
    };
    CHECK(times_with({}).size() == 3);                    // 0.05 s at 40 fps
    CHECK(times_with({"--duration", "0.1"}).size() == 5); // 0.1 s at 40 fps
    CHECK(times_with({"--fps", "100"}).size() == 6);      // 0.05 s at 100 fps
    CHECK(times_with({"--duration", "0.1", "--fps", "20"}).size() == 3);
    // The flags win over --set, whatever the order.
    CHECK(times_with({"--fps", "100", "--set", "fps=20"}).size() == 6);

    // A duration between two frames ends the run at the duration: 0.06 s at
    // 40 fps is the frames at 0, 0.025 and 0.05 s, then one at 0.06.
    const auto between = times_with({"--duration", "0.06"});
    REQUIRE(between.size() == 4);
    CHECK(between[1] == Approx(0.025));
    CHECK(between[2] == Approx(0.05));
    CHECK(between[3] == Approx(0.06));
    // Shorter than one frame: the run still simulates to the duration.
    const auto short_run = times_with({"--duration", "0.01"});
    REQUIRE(short_run.size() == 2);
    CHECK(short_run[0] == 0);
    CHECK(short_run[1] == Approx(0.01));
    CHECK(json::parse(read_text(out / "run.json")).at("status") == "completed");
    // A whole number of frames gets no extra one, round-off or not.
    CHECK(times_with({"--duration", "0.075"}).size() == 4); // 3 x 1/40 s
}

TEST_CASE("one thread and two threads write the same data", "[cli]") {
    TempFolder tmp;
    // 20 x 20 particles, so that both threads have work; 71 steps.
    const fs::path scene = write_scene(tmp, R"({
        "domain": {"min": [0, 0], "max": [0.2, 0.2]},
        "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.1, 0.1]}]},
        "duration": 0.025,
        "fps": 40
    })");
    for (const char* threads : {"1", "2"}) {
        const auto result = run_scene(tmp, scene, tmp / fmt::format("out{}", threads),
                                      {"--threads", threads, "--export", "csv"});
        INFO(result.output);
        REQUIRE(result.exit_code == 0);
    }
    const fs::path one = tmp / "out1", two = tmp / "out2";
    CHECK(json::parse(read_text(two / "run.json")).at("threads") == 2);
    CHECK(read_csv(one / "stats.csv").rows.size() == 2);
    CHECK(stats_without_wall_time(one / "stats.csv") == stats_without_wall_time(two / "stats.csv"));
    for (const char* frame : {"frame_00000.csv", "frame_00001.csv"})
        CHECK(read_text(one / "particles" / frame) == read_text(two / "particles" / frame));
}

TEST_CASE("outputs choose the fields computed for them, and change no bit of the run",
          "[cli][fields]") {
    TempFolder tmp;
    // dfsph's pressure is an output only: computed for the export, not
    // without it; the simulation is the same either way.
    const fs::path scene = write_scene(tmp, R"({
        "domain": {"min": [0, 0], "max": [0.2, 0.2]},
        "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.1, 0.1]}]},
        "solver": {"name": "dfsph"},
        "duration": 0.05,
        "fps": 40
    })");
    const auto bare = run_scene(tmp, scene, tmp / "bare", {});
    const auto exported = run_scene(tmp, scene, tmp / "exported", {"--export", "csv"});
    INFO(bare.output << exported.output);
    REQUIRE(bare.exit_code == 0);
    REQUIRE(exported.exit_code == 0);
    CHECK(json::parse(read_text(tmp / "bare" / "run.json")).at("output_fields").at("pressure") ==
          false);
    CHECK(
        json::parse(read_text(tmp / "exported" / "run.json")).at("output_fields").at("pressure") ==
        true);
    CHECK(stats_without_wall_time(tmp / "bare" / "stats.csv") ==
          stats_without_wall_time(tmp / "exported" / "stats.csv"));
    // The exported pressure is the solve's: positive at the bottom of the block.
    const Csv last = read_csv(tmp / "exported" / "particles" / "frame_00002.csv");
    double highest = 0;
    for (std::size_t i = 0; i < last.rows.size(); ++i)
        highest = std::max(highest, last.number(i, "pressure"));
    CHECK(highest > 100);
}

namespace {
// A time step far above the viscous limit (0.125 h^2 rho0 / mu, about 2e-9 s
// here): explicit viscosity amplifies the velocities every step until they
// overflow, about 50 steps in, after frame 1 (t = 0.025 s).
Result run_blowing_up(const TempFolder& tmp, const fs::path& out) {
    return run_scene(tmp, write_scene(tmp, tiny_2d), out,
                     {"--set", "solver.dt=1e-3", "--set", "material.viscosity=1e8", "--duration",
                      "1", "--export", "csv"});
}
} // namespace

TEST_CASE("a run that blows up exits 3, names the step and particle, keeps its frames", "[cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "out";
    const auto result = run_blowing_up(tmp, out);
    INFO(result.output);
    REQUIRE(result.exit_code == 3);
    CHECK(contains(result.output, "unstable at step "));
    CHECK(contains(result.output, "particle "));

    const json run = json::parse(read_text(out / "run.json"));
    CHECK(run.at("status") == "unstable");
    CHECK(contains(run.at("error").get<std::string>(), "retried 4 times"));
    const auto frames = run.at("frames").get<std::size_t>();
    CHECK(frames >= 1);
    CHECK(frames < 40); // it stopped early

    // The frames before the blow-up are kept, complete; none after it.
    const Csv stats = read_csv(out / "stats.csv");
    CHECK(stats.header == stats_header);
    REQUIRE(stats.rows.size() == frames);
    for (std::size_t k = 0; k < frames; ++k) {
        CHECK(stats.number(k, "frame") == double(k));
        CHECK(read_csv(out / "particles" / fmt::format("frame_{:05d}.csv", k)).rows.size() ==
              tiny_2d_particles);
    }
    CHECK(run.at("steps").get<double>() > stats.number(frames - 1, "steps"));
    CHECK_FALSE(fs::exists(out / "particles" / fmt::format("frame_{:05d}.csv", frames)));
}

// Fails while only the state is checked: velocities near 1e160 m/s are finite,
// but their kinetic energy is not, and the frame is written with "inf".
TEST_CASE("the frames kept before a blow-up hold finite statistics", "[cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "out";
    const auto result = run_blowing_up(tmp, out);
    REQUIRE(result.exit_code == 3);
    const Csv stats = read_csv(out / "stats.csv");
    for (std::size_t k = 0; k < stats.rows.size(); ++k) {
        INFO("frame " << k);
        CHECK(std::isfinite(stats.number(k, "kinetic_energy")));
        CHECK(std::isfinite(stats.number(k, "max_speed")));
    }
}

TEST_CASE("SIGTERM stops a run between steps and keeps its frames", "[cli]") {
    TempFolder tmp;
    const fs::path out = tmp / "out";
    // The built-in dam break for a long time: it is still running when the
    // signal arrives, a second after its first frame is written.
    const fs::path log = tmp / "sphclip.log";
    const std::string command = fmt::format(
        "OMP_WAIT_POLICY=passive {} run --out {} --duration 100 --fps 100 --quiet > {} 2>&1 & "
        "pid=$!; n=0; while [ ! -s {} ] && [ $n -lt 300 ]; do sleep 0.1; n=$((n+1)); done; "
        "sleep 1; kill -TERM $pid; wait $pid",
        shell_quote(SPHCLIP_EXE), shell_quote(out.string()), shell_quote(log.string()),
        shell_quote((out / "stats.csv").string()));
    const int status = std::system(("bash -c " + shell_quote(command)).c_str());
    REQUIRE(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 130);
    const std::string output = read_text(log);
    CHECK(contains(output, "interrupted"));
    const auto run = nlohmann::json::parse(read_text(out / "run.json"));
    CHECK(run.at("status") == "interrupted");
    const Csv stats = read_csv(out / "stats.csv");
    REQUIRE(stats.rows.size() >= 1);
    CHECK(stats.rows.size() < 10001);
    CHECK(run.at("frames").get<std::size_t>() == stats.rows.size());
}

// `sphclip compare`: images made with the library, the verdict read from the
// exit code and the metrics line.

namespace {

// 10 x 10 opaque pixels in a smooth gradient, clear of 0 and 255.
sph::Image compare_gradient() {
    sph::Image image(10, 10);
    for (int y = 0; y < 10; ++y)
        for (int x = 0; x < 10; ++x) {
            std::uint8_t* p = image.pixel(x, y);
            p[0] = std::uint8_t(20 + 20 * x);
            p[1] = std::uint8_t(20 + 20 * y);
            p[2] = 120;
            p[3] = 255;
        }
    return image;
}

// Every channel moved by at most 2, by 0.8 on average.
sph::Image with_small_noise(sph::Image image) {
    constexpr int cycle[10] = {0, 1, -1, 2, -2, 0, 1, -1, 0, 0};
    std::size_t k = 0;
    for (std::size_t i = 0; i < image.rgba.size(); i += 4)
        for (std::size_t c = 0; c < 3; ++c)
            image.rgba[i + c] = std::uint8_t(image.rgba[i + c] + cycle[k++ % 10]);
    return image;
}

fs::path write_png_file(const TempFolder& tmp, const std::string& name, const sph::Image& image) {
    sph::write_png(tmp / name, image);
    return tmp / name;
}

} // namespace

TEST_CASE("compare exits 0 for identical images and prints one line of metrics", "[cli]") {
    TempFolder tmp;
    const fs::path a = write_png_file(tmp, "a.png", compare_gradient());
    const fs::path b = write_png_file(tmp, "b.png", compare_gradient());
    const auto result = sphclip(tmp, {"compare", a.string(), b.string()});
    CHECK(result.exit_code == 0);
    CHECK(result.output == "mean_difference=0.0000 max_difference=0 different_percent=0.0000 "
                           "psnr_db=inf match=yes\n");
}

TEST_CASE("compare exits 1 when one pixel differs too much, and says why", "[cli]") {
    TempFolder tmp;
    // One pixel of 100 (1 %) off by 60 in red: mean difference 60 / 300.
    sph::Image changed = compare_gradient();
    changed.pixel(3, 7)[0] += 60;
    const fs::path ref = write_png_file(tmp, "ref.png", compare_gradient());
    const fs::path test = write_png_file(tmp, "test.png", changed);

    const auto result = sphclip(tmp, {"compare", ref.string(), test.string()});
    INFO(result.output);
    CHECK(result.exit_code == 1);
    CHECK(contains(result.output, "mean_difference=0.2000 max_difference=60 "
                                  "different_percent=1.0000 psnr_db="));
    CHECK(contains(result.output, " match=no\n"));
    CHECK(contains(result.output, "differ"));
    CHECK(contains(result.output, "--max-different"));
    CHECK_FALSE(contains(result.output, "--tolerance")); // the mean is within it

    // Allowing more differing pixels, or a larger difference per pixel, passes.
    for (const std::vector<std::string>& flags :
         {std::vector<std::string>{"--max-different", "2"}, {"--threshold", "60"}}) {
        std::vector<std::string> args{"compare", ref.string(), test.string()};
        args.insert(args.end(), flags.begin(), flags.end());
        const auto relaxed = sphclip(tmp, args);
        INFO(relaxed.output);
        CHECK(relaxed.exit_code == 0);
        CHECK(contains(relaxed.output, " match=yes\n"));
    }
}

TEST_CASE("compare's --tolerance decides on small noise everywhere", "[cli]") {
    TempFolder tmp;
    const fs::path ref = write_png_file(tmp, "ref.png", compare_gradient());
    const fs::path test = write_png_file(tmp, "test.png", with_small_noise(compare_gradient()));

    const auto loose = sphclip(tmp, {"compare", ref.string(), test.string()});
    INFO(loose.output);
    CHECK(loose.exit_code == 0);
    CHECK(contains(loose.output, "mean_difference=0.8000 max_difference=2 "
                                 "different_percent=0.0000 psnr_db="));

    const auto tight = sphclip(tmp, {"compare", ref.string(), test.string(), "--tolerance", "0.5"});
    INFO(tight.output);
    CHECK(tight.exit_code == 1);
    CHECK(contains(tight.output, "match=no"));
    CHECK(contains(tight.output, "--tolerance"));
}

TEST_CASE("compare --diff writes a difference image of the same size, match or not", "[cli]") {
    TempFolder tmp;
    sph::Image changed = compare_gradient();
    changed.pixel(3, 7)[0] += 60;
    const fs::path ref = write_png_file(tmp, "ref.png", compare_gradient());
    const fs::path test = write_png_file(tmp, "test.png", changed);

    for (const bool relaxed : {false, true}) {
        INFO((relaxed ? "matching" : "differing"));
        const fs::path diff = tmp / (relaxed ? "diff_match.png" : "diff.png");
        std::vector<std::string> args{"compare", ref.string(), test.string(), "--diff",
                                      diff.string()};
        if (relaxed)
            args.insert(args.end(), {"--max-different", "5"});
        const auto result = sphclip(tmp, args);
        INFO(result.output);
        CHECK(result.exit_code == (relaxed ? 0 : 1));
        const sph::Image image = sph::read_png(diff);
        CHECK(image.width == 10);
        CHECK(image.height == 10);
        // The changed pixel is marked red; its neighbours are grey.
        CHECK(image.pixel(3, 7)[0] > 2 * image.pixel(3, 7)[1] + 100);
        CHECK(image.pixel(4, 7)[0] == image.pixel(4, 7)[1]);
    }
}

TEST_CASE("compare exits 2 on bad input, naming the file or the flag", "[cli]") {
    TempFolder tmp;
    const fs::path ref = write_png_file(tmp, "ref.png", compare_gradient());

    auto expect_refused = [&](const std::vector<std::string>& args,
                              const std::vector<std::string>& words) {
        std::vector<std::string> full{"compare"};
        full.insert(full.end(), args.begin(), args.end());
        const auto result = sphclip(tmp, full);
        INFO(result.output);
        CHECK(result.exit_code == 2);
        for (const auto& word : words)
            CHECK(contains(result.output, word));
        CHECK_FALSE(contains(result.output, "match=")); // no verdict
    };

    SECTION("a missing image") {
        const fs::path missing = tmp / "missing.png";
        expect_refused({ref.string(), missing.string()},
                       {missing.string(), "No such file or directory"});
        expect_refused({missing.string(), ref.string()}, {missing.string()});
    }
    SECTION("a file that is not a PNG") {
        write_text(tmp / "text.png", "not an image\n");
        expect_refused({ref.string(), (tmp / "text.png").string()},
                       {(tmp / "text.png").string(), "cannot read the PNG"});
    }
    SECTION("images of different sizes") {
        const fs::path wide = write_png_file(tmp, "wide.png", sph::Image(12, 10));
        expect_refused({ref.string(), wide.string()}, {wide.string(), "12x10", "10x10"});
    }
    SECTION("a missing argument") {
        expect_refused({ref.string()}, {"test"});
    }
    SECTION("thresholds out of range or not numbers") {
        expect_refused({ref.string(), ref.string(), "--threshold", "-1"}, {"--threshold"});
        expect_refused({ref.string(), ref.string(), "--tolerance", "nan"}, {"--tolerance"});
        expect_refused({ref.string(), ref.string(), "--tolerance", "abc"}, {"--tolerance"});
        expect_refused({ref.string(), ref.string(), "--max-different", "101"}, {"--max-different"});
    }
    SECTION("a --diff in a missing folder") {
        const fs::path diff = tmp / "no_such_folder" / "diff.png";
        expect_refused({ref.string(), ref.string(), "--diff", diff.string()},
                       {"--diff", diff.string()});
        CHECK_FALSE(fs::exists(diff.parent_path()));
    }
}

// Fails while the output folder is out/ joined with any text from the scene.
TEST_CASE("output.name picks the folder under out/ and cannot leave it", "[cli]") {
    TempFolder tmp;
    const fs::path work = tmp / "work";
    fs::create_directories(work);
    auto run_in_work = [&](const std::string& scene, const std::string& file = "scene.json") {
        write_text(work / file, scene);
        return sphclip(tmp, {"run", file, "--no-png", "--no-mp4", "--quiet"}, work);
    };
    const std::string scene_start = tiny_2d.substr(0, tiny_2d.rfind('}'));

    SECTION("a name inside out/") {
        const auto result = run_in_work(scene_start + R"(, "output": {"name": "named/run"}})");
        INFO(result.output);
        REQUIRE(result.exit_code == 0);
        CHECK(fs::exists(work / "out/named/run/stats.csv"));
        CHECK_FALSE(fs::exists(work / "out/scene"));
    }
    SECTION("a name with \"..\" exits 2 and writes nothing anywhere") {
        const auto result = run_in_work(scene_start + R"(, "output": {"name": "../escape"}})");
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "scene.json: output.name: \"../escape\""));
        CHECK_FALSE(fs::exists(work / "out"));
        CHECK_FALSE(fs::exists(work / "escape"));
        CHECK_FALSE(fs::exists(tmp / "escape"));
    }
    SECTION("an absolute name exits 2") {
        const fs::path target = tmp / "absolute";
        const auto result = run_in_work(
            fmt::format(R"({}, "output": {{"name": "{}"}}}})", scene_start, target.string()));
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "output.name"));
        CHECK_FALSE(fs::exists(target));
    }
    SECTION("a scene file named ...json, whose stem is \"..\"") {
        const auto result = run_in_work(tiny_2d, "...json");
        INFO(result.output);
        CHECK(result.exit_code == 2);
        CHECK(contains(result.output, "output.name"));
        CHECK_FALSE(fs::exists(work / "out"));
        CHECK_FALSE(fs::exists(tmp / "stats.csv"));
    }
    SECTION("--out still goes anywhere the user says") {
        write_text(work / "scene.json", scene_start + R"(, "output": {"name": "../escape"}})");
        const fs::path out = tmp / "elsewhere";
        // The scene's own name is still checked: it is part of the scene.
        CHECK(run_scene(tmp, work / "scene.json", out).exit_code == 2);
        write_text(work / "scene.json", tiny_2d);
        const auto result = run_scene(tmp, work / "scene.json", out);
        INFO(result.output);
        CHECK(result.exit_code == 0);
        CHECK(fs::exists(out / "stats.csv"));
    }
}

TEST_CASE(
    "a fast preview (--fast-preview) renders half-size frames with the fastest preset and says so",
    "[cli][render][fast_preview]") {
    TempFolder tmp;
    const fs::path out = tmp / "out";
    // An odd half (161 x 91) is rounded to even: 162 x 92.
    const std::string scene =
        tiny_2d.substr(0, tiny_2d.rfind('}')) + R"(, "render": {"size": [322, 182]}})";
    const auto result = sphclip(
        tmp, {"run", write_scene(tmp, scene).string(), "--out", out.string(), "--fast-preview"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    CHECK(
        contains(result.output, "fast preview: half-size frames (162x92), x264 preset ultrafast"));
    for (int k = 0; k < 3; ++k) {
        const sph::Image frame = sph::read_png(out / "frames" / fmt::format("frame_{:05d}.png", k));
        CHECK(frame.width == 162);
        CHECK(frame.height == 92);
    }
    const json run = json::parse(read_text(out / "run.json"));
    CHECK(run.at("fast_preview") == true);
    CHECK(run.at("scene").at("render").at("size") == json::array({162, 92}));
    CHECK(run.at("scene").at("render").at("video_preset") == "ultrafast");

    // A valid H.264 MP4 of that size, as a player opens it.
    AVFormatContext* video = nullptr;
    REQUIRE(avformat_open_input(&video, (out / "clip.mp4").c_str(), nullptr, nullptr) == 0);
    CHECK(avformat_find_stream_info(video, nullptr) >= 0);
    REQUIRE(video->nb_streams == 1);
    const AVCodecParameters& codec = *video->streams[0]->codecpar;
    CHECK(codec.codec_id == AV_CODEC_ID_H264);
    CHECK(codec.width == 162);
    CHECK(codec.height == 92);
    avformat_close_input(&video);

    // Without the flag: the scene's own size, and no claim of a preview.
    const auto full = sphclip(tmp, {"run", write_scene(tmp, scene).string(), "--out",
                                    (tmp / "full").string(), "--quiet", "--no-mp4"});
    REQUIRE(full.exit_code == 0);
    CHECK(sph::read_png(tmp / "full" / "frames" / "frame_00000.png").width == 322);
    CHECK(json::parse(read_text(tmp / "full" / "run.json")).at("fast_preview") == false);
}

TEST_CASE("run's stage table names the obstacles and paddles the scene declares, and nothing "
          "it does not",
          "[cli][stages]") {
    TempFolder tmp;
    const fs::path scene = write_scene(tmp, R"({
        "domain": {"min": [0, 0], "max": [0.2, 0.1]},
        "fluid": {"spacing": 0.005, "blocks": [{"min": [0, 0], "max": [0.05, 0.05]}]},
        "material": {"viscosity": 0},
        "solver": {"name": "dfsph"},
        "effects": {"gravity": [0, -9.81],
                    "obstacles": [{"box": {"min": [0.1, 0], "max": [0.12, 0.02]}}],
                    "paddles": [{"min": [0.17, 0], "max": [0.18, 0.1], "motion": "sine",
                                 "amplitude": [0.005, 0], "period": 0.5}]},
        "duration": 0.05,
        "fps": 40
    })");
    const fs::path out = tmp / "out";
    // Not quiet: the table is printed at the end.
    const auto result =
        sphclip(tmp, {"run", scene.string(), "--out", out.string(), "--no-png", "--no-mp4"});
    INFO(result.output);
    REQUIRE(result.exit_code == 0);
    const json run = json::parse(read_text(out / "run.json"));
    // Every row is a stage of the one table or a part the scene declares.
    std::set<std::string> parts;
    for (const json& stage : run.at("stages")) {
        const auto name = stage.at("name").get<std::string>();
        if (std::find(sph::stage_names.begin(), sph::stage_names.end(), name) ==
            sph::stage_names.end())
            parts.insert(name);
    }
    // (dfsph's default artificial viscosity is an effect of its own.)
    CHECK(parts == std::set<std::string>{"artificial_viscosity", "gravity", "obstacles", "paddles",
                                         "walls"});
    for (const char* part : {"obstacles", "paddles", "walls", "gravity"})
        CHECK(result.output.find(fmt::format("\n{} ", part)) != std::string::npos);

    // dfsph's solves: their cost per iteration, from stats.csv's iteration
    // counts (each frame's mean a step, times the frame's steps: `steps` is
    // the run's count so far) and the particles; no other row has one.
    const Csv stats = read_csv(out / "stats.csv");
    const auto column = [&](const std::string& name) {
        double sum = 0, steps_before = 0;
        for (std::size_t row = 0; row < stats.rows.size(); ++row) {
            if (stats.rows[row].size() <= 1)
                continue;
            const double steps = stats.number(row, "steps");
            sum += stats.number(row, name) * (steps - steps_before);
            steps_before = steps;
        }
        return sum;
    };
    const double steps = run.at("steps").get<double>(),
                 particles = run.at("particles").get<double>();
    int solves = 0;
    for (const json& stage : run.at("stages")) {
        const auto name = stage.at("name").get<std::string>();
        const bool solve = name == "pressure solve" || name == "divergence solve";
        CHECK(stage.contains("ns_per_particle_iteration") == solve);
        if (!solve)
            continue;
        ++solves;
        const double iterations =
            column(name == "pressure solve" ? "pressure_iterations" : "divergence_iterations");
        REQUIRE(iterations > 0);
        // (stats.csv keeps 4 digits of each frame's mean, so both to 1e-3.)
        CHECK(stage.at("iterations_per_step").get<double>() ==
              Approx(iterations / steps).epsilon(1e-3));
        CHECK(stage.at("ns_per_particle_iteration").get<double>() ==
              Approx(stage.at("seconds").get<double>() * 1e9 / (iterations * particles))
                  .epsilon(1e-3));
    }
    CHECK(solves == 2);
    CHECK(result.output.find("ns/particle-iteration)") != std::string::npos);
}
