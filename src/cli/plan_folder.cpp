#include "cli/plan_folder.hpp"

#include "cli/set_options.hpp"
#include "output/files.hpp"
#include "scene/input_error.hpp"
#include "scene/scene.hpp"

#include <cstdlib>
#include <fmt/format.h>
#include <sstream>
#include <unistd.h>

namespace sph {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* plan_format = "sphclip-plan 1";

json request_json(const ChildRunRequest& r) {
    return {{"scene", r.scene.string()},
            {"out", r.out.string()},
            {"sets", r.sets},
            {"export_csv", r.export_csv},
            {"threads", r.threads},
            {"frames", r.frames},
            {"video", r.video}};
}

std::vector<std::string> command_line(const Plan& plan, const ChildRunRequest& request) {
    auto argv = child_run_arguments(request);
    argv.insert(argv.begin(), plan.program.string());
    return argv;
}

// A plan's file, within its limit (output/files.hpp): a plan folder is the
// user's, and a file there may be anything.
std::string read_plan_file(const fs::path& file) {
    try {
        return read_input_file(file, plan_file_limit);
    } catch (const FileReadError& e) {
        throw InputError(file.string(), "", e.reason);
    }
}

// The scene with its --set applied, as `run` would resolve it.
std::optional<std::string> resolved_scene(const ChildRunRequest& request, bool strict) {
    try {
        return to_json(load_scene(request.scene, parse_sets(request.sets))).dump(2) + "\n";
    } catch (const InputError&) {
        if (strict)
            throw;
        return std::nullopt;
    }
}

} // namespace

fs::path task_folder(const Plan& plan, std::size_t index) {
    const std::size_t width = std::max<std::size_t>(
        2, fmt::format("{}", plan.runs.empty() ? 0 : plan.runs.size() - 1).size());
    return plan.folder / "plan" / fmt::format("{:0{}}", index, width);
}

void write_manifest(const Plan& plan) {
    json runs = json::array();
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
        const auto& run = plan.runs[i];
        runs.push_back({{"index", i},
                        {"name", run.name},
                        {"task", fs::relative(task_folder(plan, i), plan.folder).string()},
                        {"request", request_json(run.request)},
                        {"argv", command_line(plan, run.request)}});
    }
    const json manifest{{"format", plan_format},
                        {"kind", plan.kind},
                        {"program", plan.program.string()},
                        {"folder", plan.folder.string()},
                        {"details", plan.details},
                        {"engine", plan.engine},
                        {"runs", runs}};
    write_file_atomically(plan.folder / "plan.json", manifest.dump(1) + "\n");
}

void write_plan(const Plan& plan, bool strict) {
    // Every scene resolved first: a bad one under `strict` writes nothing.
    std::vector<std::optional<std::string>> scenes;
    for (const auto& run : plan.runs)
        scenes.push_back(resolved_scene(run.request, strict));
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
        const fs::path task = task_folder(plan, i);
        fs::create_directories(task);
        remove_run_record(plan, i);
        write_file_atomically(task / "command.json",
                              json(command_line(plan, plan.runs[i].request)).dump() + "\n");
        if (scenes[i])
            write_file_atomically(task / "scene.json", *scenes[i]);
        else
            fs::remove(task / "scene.json");
    }
    write_manifest(plan);
}

Plan read_plan(const fs::path& folder) {
    const fs::path file = folder / "plan.json";
    const std::string label = file.string();
    if (!fs::is_regular_file(file))
        throw InputError(label, "", "no plan here (study, validate and batch write one)");
    json manifest;
    try {
        manifest = json::parse(read_plan_file(file));
    } catch (const json::exception& e) {
        throw InputError(label, "", fmt::format("not JSON: {}", e.what()));
    }
    const auto field = [&](const char* key) -> const json& {
        if (!manifest.is_object() || !manifest.contains(key))
            throw InputError(label, key, "missing");
        return manifest.at(key);
    };
    if (field("format") != plan_format)
        throw InputError(label, "format", fmt::format("expected \"{}\"", plan_format));
    Plan plan;
    try {
        plan.kind = field("kind").get<std::string>();
        plan.program = field("program").get<std::string>();
        plan.folder = field("folder").get<std::string>();
        plan.details = field("details");
        plan.engine = field("engine");
        for (const auto& run : field("runs")) {
            const json& r = run.at("request");
            ChildRunRequest request{r.at("scene").get<std::string>(),
                                    r.at("out").get<std::string>(),
                                    r.at("sets").get<std::vector<std::string>>(),
                                    r.at("export_csv").get<bool>(), r.at("threads").get<int>()};
            request.frames = r.at("frames").get<bool>();
            request.video = r.at("video").get<bool>();
            plan.runs.push_back({run.at("name").get<std::string>(), request});
        }
    } catch (const json::exception& e) {
        throw InputError(label, "runs", e.what());
    }
    // A plan moved or copied elsewhere still names its own folder: the runs'
    // outputs are where it says, which must be this one.
    std::error_code ec;
    if (!fs::equivalent(plan.folder, folder, ec))
        throw InputError(label, "folder",
                         fmt::format("the plan is of {}, not of this folder (plans hold "
                                     "absolute paths; write a new one here)",
                                     plan.folder.string()));
    return plan;
}

void write_run_record(const Plan& plan, std::size_t index, const ChildRunResult& result) {
    json record{{"exit_code", result.exit_code}, {"measured_wall_s", result.measured_wall_s}};
    char host[256] = {};
    if (gethostname(host, sizeof host - 1) == 0)
        record["host"] = host;
    for (const char* name : {"SLURM_ARRAY_JOB_ID", "SLURM_ARRAY_TASK_ID", "SLURM_JOB_ID"})
        if (const char* value = std::getenv(name))
            record[name] = value;
    write_file_atomically(task_folder(plan, index) / "exit.json", record.dump(1) + "\n");
}

void remove_run_record(const Plan& plan, std::size_t index) {
    std::error_code ec;
    fs::remove(task_folder(plan, index) / "exit.json", ec);
}

ChildRunResult read_run_record(const Plan& plan, std::size_t index) {
    ChildRunResult result;
    result.log = plan.runs.at(index).request.out / "run.log";
    const fs::path file = task_folder(plan, index) / "exit.json";
    if (!fs::is_regular_file(file))
        return result;
    try {
        const json record = json::parse(read_plan_file(file));
        result.exit_code = record.at("exit_code").get<int>();
        result.measured_wall_s = record.at("measured_wall_s").get<double>();
        result.started = true;
    } catch (const json::exception& e) {
        throw InputError(file.string(), "exit_code", e.what());
    }
    return result;
}

std::vector<std::size_t> unfinished_runs(const Plan& plan) {
    std::vector<std::size_t> indices;
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
        const auto result = read_run_record(plan, i);
        if (!result.started || result.exit_code != 0)
            indices.push_back(i);
    }
    return indices;
}

} // namespace sph
