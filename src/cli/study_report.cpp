#include "cli/study_report.hpp"

#include "cli/plot.hpp"
#include "output/files.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <map>
#include <vector>

namespace sph {

namespace fs = std::filesystem;

namespace {

std::string number(double value, const char* format = "{:.4g}") {
    return std::isfinite(value) ? fmt::format(fmt::runtime(format), value) : "";
}

std::string yes_no(bool value) {
    return value ? "yes" : "no";
}

// A CSV cell: quoted when it holds a comma or a quote (a varied vector).
std::string csv_cell(const std::string& text) {
    if (text.find_first_of(",\"") == std::string::npos)
        return text;
    std::string quoted = "\"";
    for (char c : text)
        quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
    return quoted + "\"";
}

bool plotted(const StudyRow& row) {
    return row.status == "ok" && !row.reference && std::isfinite(row.error) && row.error > 0 &&
           row.wall_s > 0;
}

std::string plot_commands(const StudyReport& report) {
    // One datablock per solver, so each is a series of its own colour.
    std::map<std::string, std::string> series;
    std::vector<const StudyRow*> front;
    double error_min = INFINITY, error_max = 0, wall_min = INFINITY, wall_max = 0;
    for (const auto& row : report.rows) {
        if (!plotted(row))
            continue;
        error_min = std::min(error_min, row.error);
        error_max = std::max(error_max, row.error);
        wall_min = std::min(wall_min, row.wall_s);
        wall_max = std::max(wall_max, row.wall_s);
        series[row.solver] += fmt::format("{:.6g},{:.6g},{}\n", row.wall_s, row.error, row.run);
        if (row.pareto)
            front.push_back(&row);
    }
    std::sort(front.begin(), front.end(),
              [](const StudyRow* a, const StudyRow* b) { return a->wall_s < b->wall_s; });
    std::string text;
    const auto reference = std::find_if(report.rows.begin(), report.rows.end(),
                                        [](const StudyRow& row) { return row.reference; });
    const std::string title =
        fmt::format("set title \"Study of {}: error against wall time\\n{} runs, {} plotted{}; "
                    "labels are run numbers (study.md)\" noenhanced\n",
                    fs::path(report.scene).filename().string(), report.rows.size(),
                    std::count_if(report.rows.begin(), report.rows.end(), plotted),
                    reference == report.rows.end()
                        ? ""
                        : fmt::format(" (not the reference, run {})", reference->run));
    text += title;
    text += "set xlabel 'wall-clock time of the run (s)'\n";
    text += fmt::format("set ylabel \"error: {}\" noenhanced\n", report.error_name);
    text += "set key outside right top box\n";
    if (series.empty()) {
        text += "set label 'no run has an error to plot (see study.md)' at graph 0.5,0.5 center\n"
                "set xrange [0:1]\nset yrange [0:1]\nplot NaN notitle\n";
        return text;
    }
    // Ranges from the data with a margin of a factor 1.6 (graph offsets would
    // add whole decades on log axes and squash the points together).
    text += "set logscale xy\nset format y '%g'\nset format x '%g'\n";
    text += fmt::format("set xrange [{:.6g}:{:.6g}]\nset yrange [{:.6g}:{:.6g}]\n", wall_min / 1.6,
                        wall_max * 1.6, error_min / 1.6, error_max * 1.6);
    // Labelled ticks at 1, 2 and 5 times each power of ten in range (decade
    // ticks alone would leave one or two labels on a short axis); an axis
    // under a decade or so, which that leaves with fewer than four labels
    // (0.1 and 0.2 for errors from 0.09 to 0.24), gets 1.5, 3 and 7 too.
    const auto ticks = [](double lo, double hi) {
        const auto in_range = [&](std::initializer_list<double> mantissas) {
            std::vector<std::string> values;
            for (int k = int(std::floor(std::log10(lo))); k <= int(std::ceil(std::log10(hi))); ++k)
                for (double m : mantissas)
                    if (const double v = m * std::pow(10.0, k); v >= lo && v <= hi)
                        values.push_back(fmt::format("{:g}", v));
            return values;
        };
        std::vector<std::string> values = in_range({1.0, 2.0, 5.0});
        if (values.size() < 4)
            values = in_range({1.0, 1.5, 2.0, 3.0, 5.0, 7.0});
        return fmt::format("({})", fmt::join(values, ", "));
    };
    text += fmt::format("set xtics {}\nset ytics {}\n", ticks(wall_min / 1.6, wall_max * 1.6),
                        ticks(error_min / 1.6, error_max * 1.6));
    std::vector<std::string> plots;
    int index = 0;
    for (const auto& [solver, rows] : series) {
        text += fmt::format("$s{} << EOD\n{}EOD\n", index, rows);
        plots.push_back(fmt::format("$s{} using 1:2 with points pt 7 ps 1.6 lc {} title {}", index,
                                    index + 1, gnuplot_quote("solver " + solver)));
        plots.push_back(fmt::format("$s{} using 1:2:(sprintf('%d', $3)) with labels "
                                    "offset char 1.2,0.8 font ',10' notitle",
                                    index));
        ++index;
    }
    std::string pareto;
    for (const auto* row : front)
        pareto += fmt::format("{:.6g},{:.6g}\n", row->wall_s, row->error);
    text += fmt::format("$pareto << EOD\n{}EOD\n", pareto);
    plots.push_back("$pareto using 1:2 with linespoints pt 6 ps 3.2 lw 1.5 dt 2 "
                    "lc rgb 'black' title 'Pareto front'");
    text += "plot " + fmt::format("{}", fmt::join(plots, ", \\\n     ")) + "\n";
    return text;
}

} // namespace

std::string study_csv(const StudyReport& report) {
    std::string text = "run";
    for (const auto& key : report.keys)
        text += fmt::format(",{}", csv_cell(key));
    text += ",solver,particles,steps,dt_avg_s,wall_s,density_error_avg_pct,"
            "density_error_max_pct,error,status,reference,pareto,folder\n";
    for (const auto& row : report.rows) {
        text += fmt::format("{}", row.run);
        for (const auto& [key, value] : row.values)
            text += fmt::format(",{}", csv_cell(value));
        text +=
            fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_cell(row.solver),
                        row.particles, row.steps, number(row.dt_avg_s, "{:.6g}"),
                        number(row.wall_s), number(row.density_error_avg_pct),
                        number(row.density_error_max_pct), number(row.error, "{:.6g}"), row.status,
                        yes_no(row.reference), yes_no(row.pareto), csv_cell("runs/" + row.folder));
    }
    return text;
}

std::string study_markdown(const StudyReport& report) {
    std::string text = fmt::format("# Study of `{}`\n\n", report.scene);
    if (!report.command_line.empty())
        text += fmt::format("```\n{}\n```\n\n", report.command_line);
    text += fmt::format("{} runs, one per combination of the varied keys ({}); each in "
                        "`runs/<run>_<key=value>...`.\n\n",
                        report.rows.size(), fmt::join(report.keys, ", "));
    text += fmt::format("**Error**: {}. {}\n\n", report.error_name, report.error_rule);
    const bool has_reference = std::any_of(report.rows.begin(), report.rows.end(),
                                           [](const StudyRow& row) { return row.reference; });
    text += fmt::format("**Pareto**: a completed run that no other beats on both wall time and "
                        "error{}.\n\n",
                        has_reference ? " (the reference run, whose error is 0 by definition, is "
                                        "left out)"
                                      : "");
    text += "| run";
    for (const auto& key : report.keys)
        text += fmt::format(" | `{}`", key);
    text += " | solver | particles | steps | mean dt (s) | wall (s) | density error avg (%) | "
            "density error max (%) | error | status | Pareto |\n|---";
    for (std::size_t k = 0; k < report.keys.size() + 10; ++k)
        text += "|---";
    text += "|\n";
    for (const auto& row : report.rows) {
        text += fmt::format("| {}", row.run);
        for (const auto& [key, value] : row.values)
            text += fmt::format(" | {}", value);
        text +=
            fmt::format(" | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", row.solver,
                        row.particles, row.steps, number(row.dt_avg_s, "{:.3g}"),
                        number(row.wall_s, "{:.3g}"), number(row.density_error_avg_pct, "{:.3g}"),
                        number(row.density_error_max_pct, "{:.3g}"),
                        row.reference ? std::string("reference") : number(row.error, "{:.4g}"),
                        row.status, row.pareto ? "**yes**" : "");
    }
    text += "\n![error against wall time](study.png)\n";
    std::string notes;
    for (const auto& row : report.rows)
        if (!row.note.empty())
            notes += fmt::format("- run {} ({}): {}\n", row.run, row.status, row.note);
    if (!notes.empty())
        text += "\nRuns that did not complete (the end of `runs/<run>/run.log`):\n\n" + notes;
    return text;
}

void write_study_report(const StudyReport& report, const fs::path& folder) {
    write_file_atomically(folder / "study.csv", study_csv(report));
    write_file_atomically(folder / "study.md", study_markdown(report));
    plot_png(folder / "study.png", plot_commands(report));
}

} // namespace sph
