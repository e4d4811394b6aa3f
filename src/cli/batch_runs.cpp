#include "cli/batch_runs.hpp"

#include "cli/child_process.hpp"
#include "cli/data_folders.hpp"
#include "scene/input_error.hpp"

#include <cmath>
#include <cstdio>
#include <fmt/format.h>

namespace sph {

namespace fs = std::filesystem;

int threads_per_run(int threads, int jobs) {
    return threads ? threads : (jobs > 1 ? 1 : 0);
}

void create_out_folder(const fs::path& out, const fs::path& inside) {
    std::error_code ec;
    fs::create_directories(out / inside, ec);
    if (ec)
        throw InputError("command line", "--out",
                         fmt::format("cannot create {}: {}", out.string(), ec.message()));
}

std::vector<std::string> run_sets(const ValidationCase* scored_case,
                                  const std::vector<std::string>& user_sets) {
    std::vector<std::string> sets = scored_case ? scored_case->sets : std::vector<std::string>{};
    sets.insert(sets.end(), user_sets.begin(), user_sets.end());
    return sets;
}

fs::path reference_folder(const ValidationCase& c, const fs::path& given) {
    if (reference_file(c).empty() || !given.empty())
        return given;
    return find_reference_folder();
}

std::string run_solver(const RunOutputs& run) {
    const nlohmann::json::json_pointer solver_key("/solver/name");
    return run.scene.contains(solver_key) ? run.scene.at(solver_key).get<std::string>() : "";
}

double run_wall_s(const RunOutputs& run, const ChildRunResult& result) {
    return std::isnan(run.wall_s) ? result.measured_wall_s : run.wall_s;
}

std::optional<ChildBatch>
run_batch(const std::string& intro, const std::vector<ChildRunRequest>& requests, int jobs,
          const std::vector<std::string>& names, std::string (*status)(const ChildRunResult&),
          const std::function<void(std::size_t, const ChildRunResult&)>& recorded) {
    fmt::print("{}\n", intro);
    std::fflush(stdout);
    std::size_t done = 0;
    ChildBatch batch = run_children(requests, jobs, [&](std::size_t i, const ChildRunResult& r) {
        if (recorded)
            recorded(i, r);
        fmt::print("[{}/{}] {}: {} after {:.1f} s\n", ++done, requests.size(), names[i], status(r),
                   r.measured_wall_s);
        std::fflush(stdout);
    });
    if (batch.bad_input) {
        fmt::print(stderr, "{}\n", last_lines(batch.runs[0].log, 5));
        return std::nullopt;
    }
    return batch;
}

} // namespace sph
