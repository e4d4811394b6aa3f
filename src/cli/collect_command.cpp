#include "cli/collect_command.hpp"

#include "cli/exit_codes.hpp"
#include "cli/plan_batch.hpp"
#include "cli/run_child.hpp"
#include "cli/study_command.hpp"
#include "cli/validate_command.hpp"
#include "scene/input_error.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

namespace sph {

namespace fs = std::filesystem;

namespace {

// One line per run that did not exit 0, and how to send those again.
void report_unfinished(const Plan& plan) {
    const auto unfinished = unfinished_runs(plan);
    for (const std::size_t i : unfinished) {
        const ChildRunResult r = read_run_record(plan, i);
        if (r.started)
            fmt::print("collect: run {} ({}): exit {} ({})\n", i, plan.runs[i].name, r.exit_code,
                       batch_run_status(r));
        else
            fmt::print("collect: run {} ({}): not run (no {})\n", i, plan.runs[i].name,
                       (task_folder(plan, i) / "exit.json").string());
    }
    if (!unfinished.empty())
        fmt::print("collect: {} of {} run(s) did not complete; `sphclip collect --resubmit {}` "
                   "runs only those again\n",
                   unfinished.size(), plan.runs.size(), plan.folder.string());
}

Plan plan_in(const std::string& folder) {
    return read_plan(fs::absolute(folder).lexically_normal());
}

} // namespace

int collect_plan(const Plan& plan) {
    int code = exit_failure;
    if (plan.kind == "study")
        code = collect_study(plan);
    else if (plan.kind == "validate")
        code = collect_validate(plan);
    else if (plan.kind == "batch")
        code = collect_batch(plan);
    else
        throw InputError((plan.folder / "plan.json").string(), "kind",
                         fmt::format("\"{}\" is not study, validate or batch", plan.kind));
    report_unfinished(plan);
    return code;
}

PlanCommands add_plan_commands(CLI::App& app, PlanCommandOptions& options) {
    PlanCommands commands;
    commands.collect = app.add_subcommand(
        "collect", "Collect a plan's results from what its runs left (docs/cluster.md).");
    commands.collect->add_option("plan", options.folder, "Plan folder (the --out of the command)")
        ->required();
    commands.collect->add_flag("--resubmit", options.resubmit,
                               "Run again only the runs that did not exit 0, with the plan's "
                               "engine");
    commands.collect->add_flag("--dry-run", options.engine.dry_run,
                               "With --resubmit: write the Slurm scripts, submit nothing");
    commands.collect
        ->add_option("--jobs", options.jobs,
                     "With --resubmit under --engine local: runs at once (default: "
                     "as the plan ran)")
        ->check(CLI::Range(1, 256));

    commands.run_plan = app.add_subcommand(
        "run-plan", "Run a plan that study, validate or batch wrote (with --dry-run).");
    commands.run_plan->add_option("plan", options.folder, "Plan folder")->required();
    commands.run_plan
        ->add_option("--jobs", options.jobs,
                     "Runs at once under --engine local (default: as planned)")
        ->check(CLI::Range(1, 256));
    add_engine_options(commands.run_plan, options.engine);

    commands.plan_task = app.add_subcommand(
        "plan-task", "Run one run of a plan by its index and record its exit code (what a "
                     "Slurm array task runs).");
    commands.plan_task->add_option("plan", options.folder, "Plan folder")->required();
    commands.plan_task->add_option("index", options.index, "The run's index in plan.json")
        ->required();
    return commands;
}

int collect_command(const PlanCommandOptions& options) {
    const Plan plan = plan_in(options.folder);
    const int code = collect_plan(plan);
    if (!options.resubmit)
        return code;
    const auto unfinished = unfinished_runs(plan);
    if (unfinished.empty()) {
        fmt::print("collect: every run exited 0; nothing to resubmit\n");
        return code;
    }
    EngineOptions engine = engine_from_record(plan.engine);
    engine.dry_run = options.engine.dry_run;
    const int jobs = options.jobs ? options.jobs : jobs_from_record(plan.engine);
    return execute_plan(plan, engine, jobs, unfinished,
                        fmt::format("collect: {} run(s) of {} again, {} at a time",
                                    unfinished.size(), plan.folder.string(), jobs));
}

int run_plan_command(const PlanCommandOptions& options, bool engine_given) {
    check_engine_options(options.engine);
    Plan plan = plan_in(options.folder);
    EngineOptions engine = engine_given ? options.engine : engine_from_record(plan.engine);
    engine.dry_run = options.engine.dry_run;
    const int jobs = options.jobs ? options.jobs : jobs_from_record(plan.engine);
    if (engine_given) {
        plan.engine = engine_record(engine, jobs);
        write_manifest(plan);
    }
    return execute_plan(plan, engine, jobs, all_runs(plan),
                        fmt::format("{}: {} run(s) of {}, {} at a time", plan.kind,
                                    plan.runs.size(), plan.folder.string(), jobs));
}

int plan_task_command(const PlanCommandOptions& options) {
    const Plan plan = plan_in(options.folder);
    const std::string& text = options.index;
    if (text.empty() || text.size() > 9 ||
        text.find_first_not_of("0123456789") != std::string::npos ||
        std::stoul(text) >= plan.runs.size())
        throw InputError("command line", "INDEX",
                         fmt::format("\"{}\" is not a run of the plan (0 to {})", text,
                                     plan.runs.size() ? plan.runs.size() - 1 : 0));
    const std::size_t index = std::stoul(text);
    remove_run_record(plan, index);
    const ChildBatch batch = run_children({plan.runs[index].request}, 1, {});
    const ChildRunResult& result = batch.runs[0];
    write_run_record(plan, index, result);
    fmt::print("plan-task: run {} ({}): exit {} after {:.1f} s; its log is {}\n", index,
               plan.runs[index].name, result.exit_code, result.measured_wall_s,
               result.log.string());
    return result.exit_code;
}

} // namespace sph
