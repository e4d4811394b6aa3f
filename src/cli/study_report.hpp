#pragma once
// What `sphclip study` writes once its runs are done: study.csv (one row per
// run), study.md (the same as a Markdown table, with how the error was
// measured) and study.png (error against wall time, log-log, Pareto front).

#include "analysis/study_plan.hpp"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace sph {

struct StudyRow {
    std::size_t run = 0; // index, as in the folder name
    std::string folder;  // under runs/
    Combination values;  // the varied keys' values
    std::string solver;  // solver.name as the run resolved it
    std::string status;  // ok, unstable, failed, interrupted, not_run
    std::string note;    // the last line of a run that did not finish
    std::size_t particles = 0;
    std::uint64_t steps = 0;
    double dt_avg_s = 0; // mean time step over the frames
    double wall_s = 0;   // run.json wall_s, else as measured from here
    double density_error_avg_pct = 0;
    double density_error_max_pct = 0;
    double error = 0;       // NaN when it could not be measured
    bool reference = false; // the finest run, which the others are compared with
    bool pareto = false;
};

struct StudyReport {
    std::string scene;
    std::string command_line;
    std::vector<std::string> keys; // varied, in --vary order
    std::string error_name;        // what the error column measures
    std::string error_rule;        // a sentence for study.md
    std::vector<StudyRow> rows;
};

// study.csv; a number that could not be measured is an empty cell.
std::string study_csv(const StudyReport& report);
std::string study_markdown(const StudyReport& report);

// Writes study.csv, study.md and study.png (with study.gp) into `folder`.
void write_study_report(const StudyReport& report, const std::filesystem::path& folder);

} // namespace sph
