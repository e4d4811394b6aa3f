#pragma once
// What `study` and `validate` share: both run a batch of child runs
// (run_child.hpp) with --jobs and --threads, pass the user's --set on after
// a validation case's own, find the reference tables, and read back what
// each run left.

#include "analysis/run_outputs.hpp"
#include "cli/run_child.hpp"
#include "cli/validation_cases.hpp"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sph {

// --threads per run; when not given, all cores for runs one at a time and
// 1 for runs side by side.
int threads_per_run(int threads, int jobs);

// Creates out/inside (--out and a folder in it); throws InputError naming
// --out and `out` when it cannot.
void create_out_folder(const std::filesystem::path& out, const std::filesystem::path& inside = {});

// A run's --set values: a case's own first, so it runs as `validate` runs
// it (none without a case), then the user's, which win.
std::vector<std::string> run_sets(const ValidationCase* scored_case,
                                  const std::vector<std::string>& user_sets);

// Where `c`'s reference table is: `given` (--reference-dir) when not empty,
// else found (data_folders.hpp); `given` as it is when `c` needs no table.
std::filesystem::path reference_folder(const ValidationCase& c, const std::filesystem::path& given);

// The solver the run's resolved scene names; empty when run.json has none.
std::string run_solver(const RunOutputs& run);

// The run's wall time as run.json says it, else as measured from outside.
double run_wall_s(const RunOutputs& run, const ChildRunResult& result);

// Prints `intro`, runs the requests (run_children) and prints
// "[k/n] NAME: STATUS after S s" as run i ends (names[i], status(result)).
// Returns nullopt when the first run found the scene or a --set bad, after
// printing the end of its log: no other run was started.
// `recorded(i, result)` is called first (a plan's exit record).
std::optional<ChildBatch>
run_batch(const std::string& intro, const std::vector<ChildRunRequest>& requests, int jobs,
          const std::vector<std::string>& names, std::string (*status)(const ChildRunResult&),
          const std::function<void(std::size_t, const ChildRunResult&)>& recorded = {});

} // namespace sph
