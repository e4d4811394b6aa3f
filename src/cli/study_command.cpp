#include "cli/study_command.hpp"

#include "analysis/csv_table.hpp"
#include "analysis/frame_series.hpp"
#include "analysis/pareto_front.hpp"
#include "analysis/run_outputs.hpp"
#include "analysis/study_plan.hpp"
#include "cli/batch_runs.hpp"
#include "cli/child_process.hpp"
#include "cli/exit_codes.hpp"
#include "cli/plan_engine.hpp"
#include "cli/run_child.hpp"
#include "cli/set_options.hpp"
#include "cli/study_report.hpp"
#include "cli/validation_cases.hpp"
#include "scene/input_error.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <limits>

namespace sph {

namespace fs = std::filesystem;

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::string status_of(const ChildRunResult& result) {
    if (!result.started)
        return "not_run";
    switch (result.exit_code) {
    case exit_success:
        return "ok";
    case exit_unstable:
        return "unstable";
    case exit_interrupted:
        return "interrupted";
    default:
        return "failed";
    }
}

// The per-frame series --metric names, and the length that makes it
// dimensionless: the domain's largest extent for the centre of mass, its
// height for the surface, the reference's largest value for the energy.
FrameSeries metric_series(const std::string& metric, const fs::path& run) {
    FrameSeries series;
    if (metric == "kinetic_energy") {
        const CsvTable stats = read_csv_table(run / "stats.csv");
        series.time = stats.column("time");
        for (double e : stats.column("kinetic_energy"))
            series.values.push_back({e});
        return series;
    }
    const SceneFacts scene = scene_facts(read_run_outputs(run).scene);
    const auto times = frame_times(run);
    for (const auto& file : particle_frame_files(run)) {
        const std::size_t f = particle_frame_number(file);
        if (f >= times.size() || std::isnan(times[f]))
            continue;
        const ParticleFrame frame = read_particle_frame(file);
        series.time.push_back(times[f]);
        series.values.push_back(metric == "com"
                                    ? centre_of_mass(frame)
                                    : std::vector<double>{surface_height(frame, scene.spacing)});
    }
    return series;
}

double metric_scale(const std::string& metric, const fs::path& reference_run,
                    const FrameSeries& reference) {
    if (metric == "kinetic_energy") {
        double largest = 0;
        for (const auto& v : reference.values)
            largest = std::max(largest, std::abs(v[0]));
        return largest > 0 ? largest : nan;
    }
    const SceneFacts scene = scene_facts(read_run_outputs(reference_run).scene);
    if (metric == "surface_height")
        return scene.domain_max[1] - scene.domain_min[1];
    double extent = 0;
    for (std::size_t a = 0; a < scene.domain_min.size(); ++a)
        extent = std::max(extent, scene.domain_max[a] - scene.domain_min[a]);
    return extent;
}

std::string metric_name(const std::string& metric, std::size_t reference_run) {
    if (metric == "kinetic_energy")
        return fmt::format("RMS |ΔE_k| / max E_k, against run {}", reference_run);
    if (metric == "surface_height")
        return fmt::format("RMS |Δ surface height| / domain height, against run {}", reference_run);
    return fmt::format("RMS |Δ centre of mass| / domain size, against run {}", reference_run);
}

// Errors against the study's finest run (study_plan.hpp, finest_run).
void score_against_finest(const std::string& metric, const fs::path& runs, StudyReport& report) {
    std::vector<RunSize> sizes;
    for (const auto& row : report.rows)
        sizes.push_back({row.status == "ok", row.particles, row.dt_avg_s});
    const auto finest = finest_run(sizes);
    if (!finest) {
        report.error_name = "none: no run completed";
        return;
    }
    auto& reference_row = report.rows[*finest];
    reference_row.reference = true;
    const fs::path reference_run = runs / reference_row.folder;
    const FrameSeries reference = metric_series(metric, reference_run);
    const double scale = metric_scale(metric, reference_run, reference);
    report.error_name = metric_name(metric, reference_row.run);
    report.error_rule = fmt::format(
        "The reference is run {}, the finest of the study: the most particles, among equals the "
        "smallest mean time step. Each run's per-frame series is compared with it at the run's "
        "frame times (the reference interpolated linearly in time), root mean square over the "
        "frames.",
        reference_row.run);
    for (auto& row : report.rows) {
        if (row.status != "ok")
            continue;
        try {
            row.error = row.reference ? 0.0
                                      : rms_difference(metric_series(metric, runs / row.folder),
                                                       reference, scale);
        } catch (const std::exception& e) {
            row.note = fmt::format("cannot measure the error: {}", e.what());
        }
    }
}

// Errors against the experiment or theory of a validation case.
void score_against_case(const ValidationCase& c, const fs::path& references, const fs::path& runs,
                        StudyReport& report) {
    report.error_name = case_error_name(c);
    for (auto& row : report.rows) {
        if (row.status != "ok")
            continue;
        try {
            const fs::path folder = runs / row.folder;
            const CaseScore score = score_case(c, folder, folder, references, false, row.solver);
            row.error = score.error;
        } catch (const std::exception& e) {
            row.note = fmt::format("cannot measure the error: {}", e.what());
        }
    }
    report.error_rule =
        fmt::format("Each run is scored as `sphclip validate {}` scores it; the comparison tables "
                    "are in the run folders.",
                    c.name);
}

// What a finished (or stopped) run left, into its row.
void fill_row(StudyRow& row, const ChildRunResult& result, const fs::path& folder) {
    const RunOutputs run = read_run_outputs(folder);
    row.status = status_of(result);
    row.solver = run_solver(run);
    row.particles = run.particles;
    row.steps = run.steps;
    row.dt_avg_s = run.dt_avg;
    row.wall_s = result.started ? run_wall_s(run, result) : nan;
    row.density_error_avg_pct = run.density_error_avg_pct;
    row.density_error_max_pct = run.density_error_max_pct;
    row.error = nan;
    if (result.started && row.status != "ok")
        row.note = error_line(result.log);
}

// Wall time against error, over the completed runs but the reference.
void mark_pareto_front(StudyReport& report) {
    std::vector<CostAndError> points;
    for (const auto& row : report.rows)
        points.push_back(row.status == "ok" && !row.reference ? CostAndError{row.wall_s, row.error}
                                                              : CostAndError{nan, nan});
    const auto optimal = pareto_optimal(points);
    for (std::size_t i = 0; i < report.rows.size(); ++i)
        report.rows[i].pareto = optimal[i];
}

// The case whose error scores the runs: the one --reference names, or
// without --reference the one the scene is named like
// (scenes/dam_break_2d.json); null: the runs are compared with the finest.
const ValidationCase* scored_case_for(const std::string& reference, const fs::path& scene) {
    if (reference.empty())
        return find_validation_case(scene.stem().string());
    if (reference == "finest")
        return nullptr;
    const ValidationCase* c = find_validation_case(reference);
    if (!c)
        throw InputError("command line", "--reference",
                         fmt::format("\"{}\" is neither finest nor a case ({})", reference,
                                     validation_case_names()));
    return c;
}

// One line a run, then where the report is.
void print_study(const StudyReport& report, const fs::path& out) {
    for (const auto& row : report.rows)
        fmt::print("run {:>3}  {:<40} {:<11} wall={:<8.3g} error={:<10.4g}{}\n", row.run,
                   row.folder, row.status, row.wall_s, row.error, row.pareto ? "  pareto" : "");
    fmt::print("study: error = {}\nstudy: {}, {} and {}\n", report.error_name,
               (out / "study.csv").string(), (out / "study.md").string(),
               (out / "study.png").string());
}

} // namespace

CLI::App* add_study_command(CLI::App& app, StudyOptions& options) {
    auto* cmd = app.add_subcommand(
        "study", "Run a scene for every combination of varied settings; error against cost.");
    cmd->add_option("scene", options.scene, "Scene file (JSON)")->required();
    cmd->add_option("--vary", options.vary,
                    "A key and its values: --vary fluid.spacing=0.004,0.002 (repeatable)")
        ->type_name("KEY=V1,V2,...")
        ->allow_extra_args(false)
        ->required();
    cmd->add_option("--set", options.sets, "Override a scene field in every run (repeatable)")
        ->type_name("KEY=VALUE")
        ->allow_extra_args(false);
    cmd->add_option("--duration", options.duration, "Simulated seconds (--set duration=S)")
        ->check(positive_finite_number());
    cmd->add_option("--fps", options.fps, "Frames per second (--set fps=N)")
        ->check(positive_finite_number());
    cmd->add_option("--metric", options.metric,
                    "Series compared with the finest run: com (default), kinetic_energy, "
                    "surface_height")
        ->check(CLI::IsMember({"com", "kinetic_energy", "surface_height"}));
    cmd->add_option("--reference", options.reference,
                    "finest, or a validation case (default: the case named like the scene file, "
                    "else finest)");
    cmd->add_option("--out", options.out, "Output folder (default out/study_<scene name>)");
    cmd->add_option("--jobs", options.jobs, "Runs at once")
        ->check(CLI::Range(1, 256))
        ->capture_default_str();
    cmd->add_option("--threads", options.threads,
                    "Threads per run (default: all cores, or 1 when --jobs > 1)")
        ->check(CLI::Range(1, 1024));
    cmd->add_option("--reference-dir", options.reference_dir,
                    "Folder of the reference tables (default: the repository's "
                    "data/reference, searched)");
    add_engine_options(cmd, options.engine);
    return cmd;
}

int study_command(const StudyOptions& options) {
    std::vector<Variation> variations;
    for (const auto& v : options.vary)
        variations.push_back(parse_variation(v));
    const auto combinations = expand_combinations(variations);
    check_sets(options.sets);
    check_engine_options(options.engine);
    const fs::path scene = options.scene;
    if (!fs::is_regular_file(scene))
        throw InputError(scene.string(), "", "no such scene file");

    const ValidationCase* scored_case = scored_case_for(options.reference, scene);
    const fs::path references = scored_case ? reference_folder(*scored_case, options.reference_dir)
                                            : fs::path(options.reference_dir);

    const fs::path out = options.out.empty() ? fs::path("out") / ("study_" + scene.stem().string())
                                             : fs::path(options.out);
    create_out_folder(out, "runs");

    // Runs scored as a case run as validate runs them (the case's own --set
    // first); the user's --set, --duration and --fps win.
    std::vector<std::string> common = run_sets(scored_case, options.sets);
    if (options.duration > 0)
        common.push_back(fmt::format("duration={}", options.duration));
    if (options.fps > 0)
        common.push_back(fmt::format("fps={}", options.fps));
    const std::string metric = options.metric.empty() ? "com" : options.metric;
    if (scored_case && !options.metric.empty())
        fmt::print("study: --metric {} is not used: runs are scored as the case {} "
                   "(--reference finest compares them with the finest run)\n",
                   options.metric, scored_case->name);
    const bool particles_needed = scored_case || metric != "kinetic_energy";
    const int threads = plan_threads(options.threads, options.jobs, options.engine);

    // The plan: every run's request, and what collect needs to score them.
    Plan plan;
    plan.kind = "study";
    plan.folder = fs::absolute(out).lexically_normal();
    plan.program = self_executable();
    plan.engine = engine_record(options.engine, options.jobs);
    nlohmann::json rows = nlohmann::json::array();
    std::vector<std::string> keys;
    for (const auto& v : variations)
        keys.push_back(v.key);
    for (std::size_t i = 0; i < combinations.size(); ++i) {
        const std::string folder = run_folder_name(i, combinations.size(), combinations[i]);
        rows.push_back({{"folder", folder}, {"values", combinations[i]}});
        ChildRunRequest request{fs::absolute(scene), plan.folder / "runs" / folder, common,
                                particles_needed, threads};
        for (const auto& [key, value] : combinations[i])
            request.sets.push_back(key + "=" + value);
        plan.runs.push_back({"run " + folder, request});
    }
    plan.details = {
        {"scene", options.scene},
        {"out", out.string()},
        {"command_line", options.command_line},
        {"keys", keys},
        {"rows", rows},
        {"case", scored_case ? scored_case->name : ""},
        {"references", references.empty() ? std::string() : fs::absolute(references).string()},
        {"metric", metric}};
    write_plan(plan, options.engine.engine == "slurm");
    return execute_plan(plan, options.engine, options.jobs, all_runs(plan),
                        fmt::format("study: {} runs of {} into {}/, {} at a time", plan.runs.size(),
                                    scene.string(), out.string(), options.jobs));
}

std::string study_run_status(const ChildRunResult& result) {
    return status_of(result);
}

int collect_study(const Plan& plan) {
    const auto& d = plan.details;
    StudyReport report;
    report.scene = d.at("scene").get<std::string>();
    report.command_line = d.at("command_line").get<std::string>();
    report.keys = d.at("keys").get<std::vector<std::string>>();
    const auto& rows = d.at("rows");
    for (std::size_t i = 0; i < plan.runs.size(); ++i) {
        StudyRow row;
        row.run = i;
        row.folder = rows.at(i).at("folder").get<std::string>();
        row.values = rows.at(i).at("values").get<Combination>();
        fill_row(row, read_run_record(plan, i), plan.runs[i].request.out);
        report.rows.push_back(row);
    }
    const fs::path runs = plan.folder / "runs";
    const std::string case_name = d.at("case").get<std::string>();
    if (const ValidationCase* scored_case = find_validation_case(case_name))
        score_against_case(*scored_case, d.at("references").get<std::string>(), runs, report);
    else
        score_against_finest(d.at("metric").get<std::string>(), runs, report);

    mark_pareto_front(report);
    write_study_report(report, plan.folder);
    print_study(report, d.at("out").get<std::string>());
    return exit_success;
}

} // namespace sph
