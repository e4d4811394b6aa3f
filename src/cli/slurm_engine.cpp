#include "cli/slurm_engine.hpp"

#include "cli/child_process.hpp"
#include "cli/console.hpp"
#include "cli/exit_codes.hpp"
#include "output/files.hpp"
#include "scene/input_error.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fmt/format.h>
#include <fstream>
#include <regex>
#include <sstream>

namespace sph {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

[[noreturn]] void bad_option(const char* flag, const std::string& problem) {
    throw InputError("command line", flag, problem);
}

// A word the shell reads back as it is.
std::string shell_word(const std::string& word) {
    std::string quoted = "'";
    for (char c : word)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

// The #SBATCH lines every job of the plan shares: the site's options.
std::string site_lines(const SlurmOptions& options, bool with_cpus) {
    std::string text;
    if (!options.partition.empty())
        text += fmt::format("#SBATCH --partition={}\n", options.partition);
    if (!options.time.empty())
        text += fmt::format("#SBATCH --time={}\n", options.time);
    if (with_cpus && options.cpus_per_task > 0)
        text += fmt::format("#SBATCH --cpus-per-task={}\n", options.cpus_per_task);
    for (const auto& arg : options.sbatch_args)
        text += fmt::format("#SBATCH {}\n", arg);
    return text;
}

std::string read_text(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// sbatch ARGS..., its output into `log`; the job id --parsable printed
// ("ID" or "ID;cluster"), or nullopt after saying why not.
std::optional<std::string> sbatch(const std::vector<std::string>& args, const fs::path& log) {
    const char* given = std::getenv("SPHCLIP_SBATCH");
    const std::string program = given && *given ? given : "sbatch";
    std::vector<std::string> argv{program};
    argv.insert(argv.end(), args.begin(), args.end());
    int code = -1;
    try {
        code = child_exit_code(start_child(program, argv, log, true), true).value_or(-1);
    } catch (const std::exception& e) {
        say(stderr,
            "sphclip: error: {} (--engine slurm needs Slurm's sbatch in PATH, or "
            "SPHCLIP_SBATCH naming it)\n",
            e.what());
        return std::nullopt;
    }
    const std::string output = read_text(log);
    // The id is the last line that starts with a digit; warnings may come first.
    std::string id;
    std::istringstream lines(output);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty() && std::isdigit(static_cast<unsigned char>(line[0])))
            id = line.substr(0, line.find(';'));
    if (code != 0 || id.empty()) {
        say(stderr, "sphclip: error: {} refused the job (exit {}): {}\n", program, code,
            last_lines(log, 3));
        return std::nullopt;
    }
    return id;
}

} // namespace

void check_slurm_options(const SlurmOptions& options) {
    // Slurm's forms: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S.
    static const std::regex time_form(R"(^(\d+-)?\d+(:\d{1,2}){0,2}$)");
    if (!options.time.empty()) {
        if (!std::regex_match(options.time, time_form))
            bad_option("--time", fmt::format("\"{}\" is not a Slurm time limit (HH:MM:SS, "
                                             "D-HH:MM:SS or minutes)",
                                             options.time));
        const std::string clock = options.time.substr(options.time.find('-') + 1);
        std::size_t colon = clock.find(':');
        while (colon != std::string::npos) {
            if (std::stoi(clock.substr(colon + 1, 2)) >= 60)
                bad_option("--time",
                           fmt::format("\"{}\": minutes and seconds are below 60", options.time));
            colon = clock.find(':', colon + 1);
        }
        if (options.time.find_first_not_of("0-:") == std::string::npos)
            bad_option("--time", fmt::format("\"{}\" is no time at all", options.time));
    }
    static const std::regex partition_form(R"(^[A-Za-z0-9_.-]+(,[A-Za-z0-9_.-]+)*$)");
    if (!options.partition.empty() && !std::regex_match(options.partition, partition_form))
        bad_option("--partition", fmt::format("\"{}\" is not a partition name (letters, digits, "
                                              "_ . -; several separated by commas)",
                                              options.partition));
    for (const auto& arg : options.sbatch_args)
        if (arg.empty() || arg[0] != '-' || arg.find_first_of("\n\r") != std::string::npos)
            bad_option("--sbatch-arg",
                       fmt::format("\"{}\": one sbatch option on one line, starting with -", arg));
}

json slurm_options_json(const SlurmOptions& o) {
    return {{"name", "slurm"},
            {"partition", o.partition},
            {"time", o.time},
            {"cpus_per_task", o.cpus_per_task},
            {"max_running", o.max_running},
            {"sbatch_args", o.sbatch_args}};
}

SlurmOptions slurm_options_from_json(const json& r) {
    SlurmOptions o;
    o.partition = r.value("partition", "");
    o.time = r.value("time", "");
    o.cpus_per_task = r.value("cpus_per_task", 0);
    o.max_running = r.value("max_running", 0);
    o.sbatch_args = r.value("sbatch_args", std::vector<std::string>{});
    return o;
}

std::string array_spec(const std::vector<std::size_t>& indices, int max_running) {
    std::string spec;
    for (std::size_t k = 0; k < indices.size();) {
        std::size_t end = k;
        while (end + 1 < indices.size() && indices[end + 1] == indices[end] + 1)
            ++end;
        if (!spec.empty())
            spec += ',';
        spec += end > k ? fmt::format("{}-{}", indices[k], indices[end])
                        : fmt::format("{}", indices[k]);
        k = end + 1;
    }
    if (max_running > 0)
        spec += fmt::format("%{}", max_running);
    return spec;
}

std::string array_script(const Plan& plan, const SlurmOptions& options,
                         const std::vector<std::size_t>& indices) {
    const fs::path slurm = plan.folder / "slurm";
    std::string text =
        fmt::format("#!/bin/sh\n# The runs of the {} plan {} as one job array, "
                    "written by sphclip ({} of {} runs).\n",
                    plan.kind, plan.folder.string(), indices.size(), plan.runs.size());
    text += fmt::format("#SBATCH --job-name=sphclip-{}\n", plan.kind);
    text += fmt::format("#SBATCH --array={}\n", array_spec(indices, options.max_running));
    text += fmt::format("#SBATCH --output={}\n", (slurm / "task-%A_%a.out").string());
    text += site_lines(options, true);
    // The array task's id is the run's index in plan.json; plan-task records
    // the run's exit code in plan/NN/exit.json.
    text += fmt::format("exec {} plan-task {} \"$SLURM_ARRAY_TASK_ID\"\n",
                        shell_word(plan.program.string()), shell_word(plan.folder.string()));
    return text;
}

std::string collect_script(const Plan& plan, const SlurmOptions& options) {
    const fs::path slurm = plan.folder / "slurm";
    std::string text = fmt::format(
        "#!/bin/sh\n# Collects the {} plan {} once its array has ended, written by sphclip.\n",
        plan.kind, plan.folder.string());
    text += "#SBATCH --job-name=sphclip-collect\n";
    text += fmt::format("#SBATCH --output={}\n", (slurm / "collect-%j.out").string());
    text += site_lines(options, false);
    text += fmt::format("exec {} collect {}\n", shell_word(plan.program.string()),
                        shell_word(plan.folder.string()));
    return text;
}

int submit_to_slurm(const Plan& plan, const SlurmOptions& options,
                    const std::vector<std::size_t>& indices, bool dry_run) {
    const fs::path slurm = plan.folder / "slurm";
    fs::create_directories(slurm);
    const fs::path array_file = slurm / "array.sbatch";
    const fs::path collect_file = slurm / "collect.sbatch";
    write_file_atomically(array_file, array_script(plan, options, indices));
    write_file_atomically(collect_file, collect_script(plan, options));
    if (dry_run) {
        fmt::print("{}: --dry-run: nothing submitted; to submit:\n"
                   "  sbatch --parsable {}\n"
                   "  sbatch --dependency=afterany:ARRAY_JOB_ID {}\n",
                   plan.kind, array_file.string(), collect_file.string());
        return exit_success;
    }
    const auto array_job = sbatch({"--parsable", array_file.string()}, slurm / "sbatch.log");
    if (!array_job)
        return exit_scheduler;
    const auto collect_job =
        sbatch({"--parsable", "--dependency=afterany:" + *array_job, collect_file.string()},
               slurm / "sbatch.log");
    if (!collect_job) {
        say(stderr,
            "sphclip: the array job {} was submitted; `sphclip collect {}` collects "
            "it once it has ended\n",
            *array_job, plan.folder.string());
        return exit_scheduler;
    }
    json submissions = json::array();
    const fs::path record = slurm / "submissions.json";
    if (fs::is_regular_file(record))
        submissions = json::parse(read_input_file(record, plan_file_limit), nullptr, false);
    if (!submissions.is_array())
        submissions = json::array();
    submissions.push_back(
        {{"array_job", *array_job}, {"collect_job", *collect_job}, {"indices", indices}});
    write_file_atomically(record, submissions.dump(1) + "\n");
    fmt::print("{}: {} run(s) submitted as the job array {}; job {} collects them into {}/\n",
               plan.kind, indices.size(), *array_job, *collect_job, plan.folder.string());
    fmt::print("{}: follow with `squeue -j {},{}`; the runs' Slurm output is in {}/\n", plan.kind,
               *array_job, *collect_job, slurm.string());
    return exit_success;
}

} // namespace sph
