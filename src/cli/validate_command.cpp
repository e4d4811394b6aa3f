#include "cli/validate_command.hpp"

#include "analysis/run_outputs.hpp"
#include "cli/batch_runs.hpp"
#include "cli/child_process.hpp"
#include "cli/data_folders.hpp"
#include "cli/exit_codes.hpp"
#include "cli/plan_engine.hpp"
#include "cli/run_child.hpp"
#include "cli/set_options.hpp"
#include "cli/validation_cases.hpp"
#include "output/files.hpp"
#include "scene/input_error.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <fmt/format.h>

namespace sph {

namespace fs = std::filesystem;

namespace {

// summary.csv: one row per case; a figure that does not apply is empty.
// `max_speed` repeats `speed_max_m_s` under stats.csv's name for it, last so
// that the columns before it keep their places.
const char* summary_header = "case,solver,status,particles,steps,wall_s,mean_abs_dZ,max_abs_dZ,"
                             "pressure_error_rms_pct,pressure_error_max_pct,"
                             "density_error_avg_pct,speed_max_m_s,front_error_mean_pct,"
                             "front_error_max_pct,verdict,max_speed";

std::string cell(const nlohmann::json& metrics, const char* key) {
    return metrics.contains(key) && metrics[key].is_number()
               ? fmt::format("{:.6g}", metrics[key].get<double>())
               : "";
}

std::string status_of(const ChildRunResult& result) {
    if (!result.started)
        return "not_run";
    switch (result.exit_code) {
    case exit_success:
        return "completed";
    case exit_unstable:
        return "unstable";
    case exit_interrupted:
        return "interrupted";
    case exit_bad_input:
        return "bad_input";
    default:
        return "failed";
    }
}

std::vector<const ValidationCase*> select_cases(const std::vector<std::string>& names) {
    std::vector<const ValidationCase*> selected;
    for (const auto& name : names) {
        const auto* c = find_validation_case(name);
        if (!c)
            throw InputError("command line", "validate",
                             fmt::format("unknown case \"{}\"; the cases are: {}", name,
                                         validation_case_names()));
        selected.push_back(c);
    }
    if (selected.empty())
        for (const auto& c : validation_cases())
            selected.push_back(&c);
    return selected;
}

// Every scene and reference table in place before anything runs.
void check_inputs(const std::vector<const ValidationCase*>& selected, const fs::path& scenes,
                  fs::path& references) {
    for (const auto* c : selected) {
        if (!fs::exists(scenes / (c->name + ".json")))
            throw InputError("command line", "--scenes-dir",
                             fmt::format("no scene {} for the case {}",
                                         (scenes / (c->name + ".json")).string(), c->name));
        references = reference_folder(*c, references);
        if (reference_file(*c).empty())
            continue;
        if (!fs::exists(references / reference_file(*c)))
            throw InputError(
                "command line", "--reference-dir",
                fmt::format("no reference table {}", (references / reference_file(*c)).string()));
    }
}

// What went wrong in the cases, for the exit code.
struct CaseOutcomes {
    bool unstable = false, bad_input = false, failed = false;
};

// Scores a case's finished run from `run_folder` (the comparison tables and
// metrics.json into `folder`), prints its summary line, and returns its row
// of summary.csv.
std::string report_case(const ValidationCase& c, const ChildRunResult& result,
                        const fs::path& run_folder, const fs::path& folder,
                        const fs::path& references, CaseOutcomes& outcomes) {
    const RunOutputs run = read_run_outputs(run_folder);
    const std::string solver = run_solver(run);
    const double wall = run_wall_s(run, result);
    const std::string status = status_of(result);
    nlohmann::json metrics;
    std::string verdict;
    if (result.started && result.exit_code == exit_success) {
        try {
            const CaseScore score =
                score_case(c, run_folder, folder, references, true, "solver " + solver);
            metrics = score.metrics;
            verdict = score.pass ? "PASS" : "FAIL";
            write_file_atomically(folder / "metrics.json", metrics.dump(2) + "\n");
            fmt::print("{:<15} solver={:<6} {}  wall={:.1f}s  {}\n", c.name, solver, score.figures,
                       wall, verdict);
        } catch (const std::exception& e) {
            fmt::print("{:<15} solver={:<6} cannot score the run: {}\n", c.name, solver, e.what());
            outcomes.failed = true;
        }
    } else if (!result.started) {
        fmt::print("{:<15} not run\n", c.name);
    } else {
        fmt::print("{:<15} solver={:<6} {} (exit {}) after {:.1f}s\n", c.name, solver, status,
                   result.exit_code, wall);
        fmt::print("    {}\n", error_line(result.log));
        outcomes.unstable |= result.exit_code == exit_unstable;
        outcomes.bad_input |= result.exit_code == exit_bad_input;
        outcomes.failed |= result.exit_code != exit_unstable &&
                           result.exit_code != exit_bad_input &&
                           result.exit_code != exit_interrupted;
    }
    return fmt::format(
        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", c.name, solver, status, run.particles,
        run.steps, result.started ? fmt::format("{:.4g}", wall) : "", cell(metrics, "mean_abs_dZ"),
        cell(metrics, "max_abs_dZ"), cell(metrics, "pressure_error_rms_pct"),
        cell(metrics, "pressure_error_max_pct"), cell(metrics, "density_error_avg_pct"),
        cell(metrics, "speed_max_m_s"), cell(metrics, "front_error_mean_pct"),
        cell(metrics, "front_error_max_pct"), verdict, cell(metrics, "speed_max_m_s"));
}

} // namespace

CLI::App* add_validate_command(CLI::App& app, ValidateOptions& options) {
    auto* cmd = app.add_subcommand(
        "validate",
        "Run scenes with a known outcome (hydrostatic tank, dam break) and score them.");
    cmd->add_option("cases", options.cases,
                    "Cases to run (default all): " + validation_case_names());
    cmd->add_option("--out", options.out, "Output folder")->capture_default_str();
    cmd->add_option("--set", options.sets,
                    "Override a scene field in every case: --set solver.name=seed (repeatable)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false);
    cmd->add_option("--jobs", options.jobs, "Cases run at once")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    cmd->add_option("--threads", options.threads,
                    "Threads per run (default: all cores, or 1 when --jobs > 1)")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--scenes-dir", options.scenes_dir,
                    "Folder of CASE.json (default: ./scenes, else beside the program's folder)");
    cmd->add_option("--reference-dir", options.reference_dir,
                    "Folder of the reference tables (default: the repository's "
                    "data/reference, searched)");
    add_engine_options(cmd, options.engine);
    return cmd;
}

int validate_command(const ValidateOptions& options) {
    const auto selected = select_cases(options.cases);
    check_sets(options.sets);
    check_engine_options(options.engine);
    const fs::path scenes =
        options.scenes_dir.empty() ? find_scenes_folder() : fs::path(options.scenes_dir);
    fs::path references = options.reference_dir;
    check_inputs(selected, scenes, references);

    const fs::path out = options.out;
    create_out_folder(out);
    const int threads = plan_threads(options.threads, options.jobs, options.engine);
    Plan plan;
    plan.kind = "validate";
    plan.folder = fs::absolute(out).lexically_normal();
    plan.program = self_executable();
    plan.engine = engine_record(options.engine, options.jobs);
    std::vector<std::string> names;
    for (const auto* c : selected) {
        plan.runs.push_back(
            {c->name,
             {fs::absolute(scenes / (c->name + ".json")), plan.folder / c->name / "run",
              run_sets(c, options.sets), true, threads}});
        names.push_back(c->name);
    }
    plan.details = {
        {"out", out.string()},
        {"cases", names},
        {"references", references.empty() ? std::string() : fs::absolute(references).string()}};
    write_plan(plan, options.engine.engine == "slurm");
    return execute_plan(plan, options.engine, options.jobs, all_runs(plan),
                        fmt::format("validate: {} case(s) into {}/, {} at a time", selected.size(),
                                    out.string(), options.jobs));
}

std::string validate_run_status(const ChildRunResult& result) {
    return status_of(result);
}

int collect_validate(const Plan& plan) {
    const auto& d = plan.details;
    const fs::path references = d.at("references").get<std::string>();
    const std::string out = d.at("out").get<std::string>();
    const auto selected = select_cases(d.at("cases").get<std::vector<std::string>>());
    CaseOutcomes outcomes;
    bool interrupted = false;
    std::string summary = std::string(summary_header) + "\n";
    for (std::size_t i = 0; i < selected.size(); ++i) {
        const ChildRunResult result = read_run_record(plan, i);
        interrupted |= result.started && result.exit_code == exit_interrupted;
        summary += report_case(*selected[i], result, plan.runs[i].request.out,
                               plan.folder / selected[i]->name, references, outcomes);
    }
    write_file_atomically(plan.folder / "summary.csv", summary);
    fmt::print("validate: summary in {}; comparison tables and plots in {}/CASE/\n",
               (fs::path(out) / "summary.csv").string(), out);
    if (interrupted)
        return exit_interrupted;
    if (outcomes.bad_input)
        return exit_bad_input;
    if (outcomes.unstable)
        return exit_unstable;
    return outcomes.failed ? exit_failure : exit_success;
}

} // namespace sph
