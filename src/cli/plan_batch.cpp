#include "cli/plan_batch.hpp"

#include "analysis/run_outputs.hpp"
#include "analysis/study_plan.hpp"
#include "cli/batch_runs.hpp"
#include "cli/child_process.hpp"
#include "cli/exit_codes.hpp"
#include "cli/set_options.hpp"
#include "output/files.hpp"
#include "scene/input_error.hpp"

#include <CLI/CLI.hpp>
#include <cctype>
#include <cmath>
#include <fmt/format.h>
#include <sstream>

namespace sph {

namespace fs = std::filesystem;

namespace {

// The scenes of --list: a line each, blank lines and # comments skipped,
// relative paths from the current folder as on the command line.
std::vector<std::string> read_list(const fs::path& list) {
    std::istringstream in;
    try {
        in.str(read_input_file(list, list_file_limit));
    } catch (const FileReadError& e) {
        throw InputError("command line", "--list",
                         fmt::format("cannot read {}: {}", list.string(), e.reason));
    }
    std::vector<std::string> scenes;
    std::string line;
    std::size_t number = 0;
    while (std::getline(in, line)) {
        ++number;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
            continue;
        const auto last = line.find_last_not_of(" \t\r");
        const std::string scene = line.substr(first, last - first + 1);
        if (!fs::is_regular_file(scene))
            throw InputError(list.string(), fmt::format("line {}", number),
                             fmt::format("no such scene file {}", scene));
        scenes.push_back(scene);
    }
    return scenes;
}

// The state hash of the last frame in stats.csv, as written (a 64-bit
// number: read as text, a double would round it).
std::string last_state_hash(const fs::path& run) {
    std::istringstream in;
    try {
        in.str(read_input_file(run / "stats.csv", table_file_limit));
    } catch (const FileReadError&) {
        return {};
    }
    std::string line, header, last;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#')
            continue;
        if (header.empty())
            header = line;
        else
            last = line;
    }
    const auto cells = [](const std::string& text) {
        std::vector<std::string> out;
        std::stringstream s(text);
        for (std::string cell; std::getline(s, cell, ',');)
            out.push_back(cell);
        return out;
    };
    const auto names = cells(header), values = cells(last);
    for (std::size_t i = 0; i < names.size() && i < values.size(); ++i)
        if (names[i] == "state_hash")
            return values[i];
    return "";
}

// A CSV cell: quoted when it holds a comma, a quote or a line break.
std::string csv_cell(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos)
        return text;
    std::string quoted = "\"";
    for (char c : text)
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

} // namespace

std::string batch_run_status(const ChildRunResult& result) {
    if (!result.started)
        return "not_run";
    switch (result.exit_code) {
    case exit_success:
        return "ok";
    case exit_unstable:
        return "unstable";
    case exit_no_gl_context:
        return "no_gl_context";
    case exit_bad_input:
        return "bad_input";
    case exit_interrupted:
        return "interrupted";
    default:
        return "failed";
    }
}

CLI::App* add_batch_command(CLI::App& app, BatchOptions& options) {
    auto* cmd = app.add_subcommand(
        "batch", "Turn many scenes into clips, one run each, with any engine (docs/cluster.md).");
    cmd->add_option("scenes", options.scenes, "Scene files (JSON)");
    cmd->add_option("--list", options.list, "A file of scene paths, one a line (# comments)");
    cmd->add_option("--out", options.out, "Output folder (runs/NN_<scene>/ in it)")
        ->capture_default_str();
    cmd->add_option("--set", options.sets, "Override a scene field in every run (repeatable)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false);
    cmd->add_option("--jobs", options.jobs, "Runs at once (--engine local)")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    cmd->add_option("--threads", options.threads,
                    "Threads per run (default: all cores, or 1 when --jobs > 1; under Slurm "
                    "--cpus-per-task)")
        ->check(CLI::Range(1, 1024));
    cmd->add_flag("--no-png", options.no_png, "No PNG frames in the runs");
    cmd->add_flag("--no-mp4", options.no_mp4, "No clip.mp4 in the runs");
    cmd->add_flag("--export-csv", options.export_csv,
                  "Particle CSV files per frame (--export csv)");
    add_engine_options(cmd, options.engine);
    return cmd;
}

int batch_command(const BatchOptions& options) {
    check_sets(options.sets);
    check_engine_options(options.engine);
    std::vector<std::string> scenes = options.scenes;
    if (!options.list.empty()) {
        const auto listed = read_list(options.list);
        scenes.insert(scenes.end(), listed.begin(), listed.end());
    }
    if (scenes.empty())
        throw InputError("command line", "batch", "no scene: give SCENE... or --list FILE");
    for (const auto& scene : scenes)
        if (!fs::is_regular_file(scene))
            throw InputError(scene, "", "no such scene file");

    const fs::path out = options.out;
    create_out_folder(out, "runs");
    Plan plan;
    plan.kind = "batch";
    plan.folder = fs::absolute(out).lexically_normal();
    plan.program = self_executable();
    plan.engine = engine_record(options.engine, options.jobs);
    const int threads = plan_threads(options.threads, options.jobs, options.engine);
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t i = 0; i < scenes.size(); ++i) {
        const fs::path scene = scenes[i];
        std::string folder = run_folder_name(i, scenes.size(), {}) + "_" + scene.stem().string();
        for (char& c : folder)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-')
                c = '_';
        ChildRunRequest request{fs::absolute(scene), plan.folder / "runs" / folder, options.sets,
                                options.export_csv, threads};
        request.frames = !options.no_png;
        request.video = !options.no_mp4;
        plan.runs.push_back({folder, request});
        rows.push_back({{"scene", scene.string()}, {"folder", folder}});
    }
    plan.details = {{"out", out.string()}, {"rows", rows}};
    write_plan(plan, options.engine.engine == "slurm");
    return execute_plan(plan, options.engine, options.jobs, all_runs(plan),
                        fmt::format("batch: {} scene(s) into {}/, {} at a time", scenes.size(),
                                    out.string(), options.jobs));
}

int collect_batch(const Plan& plan) {
    const auto& rows = plan.details.at("rows");
    std::string csv = "run,scene,status,exit_code,particles,steps,wall_s,state_hash,folder\n";
    bool interrupted = false, bad_input = false, unstable = false, failed = false;
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
        const ChildRunResult result = read_run_record(plan, i);
        const fs::path folder = plan.runs[i].request.out;
        const RunOutputs run = read_run_outputs(folder);
        const std::string status = batch_run_status(result);
        const double wall = result.started ? run_wall_s(run, result) : NAN;
        csv += fmt::format("{},{},{},{},{},{},{},{},runs/{}\n", i,
                           csv_cell(rows.at(i).at("scene").get<std::string>()), status,
                           result.started ? std::to_string(result.exit_code) : "", run.particles,
                           run.steps, std::isfinite(wall) ? fmt::format("{:.4g}", wall) : "",
                           last_state_hash(folder),
                           csv_cell(rows.at(i).at("folder").get<std::string>()));
        fmt::print("run {:>3}  {:<40} {:<13} wall={:.3g}\n", i, plan.runs[i].name, status, wall);
        interrupted |= status == "interrupted";
        bad_input |= status == "bad_input";
        unstable |= status == "unstable";
        failed |= status != "ok" && status != "interrupted" && status != "bad_input" &&
                  status != "unstable";
    }
    const std::string out = plan.details.at("out").get<std::string>();
    write_file_atomically(plan.folder / "batch.csv", csv);
    fmt::print("batch: summary in {}\n", (fs::path(out) / "batch.csv").string());
    if (interrupted)
        return exit_interrupted;
    if (bad_input)
        return exit_bad_input;
    if (unstable)
        return exit_unstable;
    return failed ? exit_failure : exit_success;
}

} // namespace sph
