#include "cli/plot.hpp"

#include "cli/child_process.hpp"
#include "output/files.hpp"

#include <fmt/format.h>

namespace sph {

namespace fs = std::filesystem;

std::string gnuplot_quote(const std::string& text) {
    std::string quoted = "'";
    for (char c : text)
        quoted += c == '\'' ? std::string("''") : std::string(1, c);
    return quoted + "'";
}

bool plot_png(const fs::path& png, const std::string& commands) {
    const fs::path folder = png.parent_path().empty() ? fs::path(".") : png.parent_path();
    fs::path script = png;
    script.replace_extension(".gp");
    fs::path log = png;
    log.replace_extension(".gnuplot.log");
    const std::string text = fmt::format(
        "# Redraw with: cd {} && gnuplot {}\n"
        "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {{\n"
        "    set terminal pngcairo size 1000,680 enhanced font 'sans,11' linewidth 1.5\n"
        "}} else {{\n"
        "    set terminal png size 1000,680 enhanced\n"
        "}}\n"
        "set output {}\n"
        "set encoding utf8\n"
        "set datafile separator comma\n"
        "set grid lc rgb '#dddddd'\n"
        "{}",
        folder.string(), script.filename().string(), gnuplot_quote(png.filename().string()),
        commands);
    try {
        write_file_atomically(script, text);
        const pid_t pid =
            start_child("gnuplot", {"gnuplot", script.filename().string()}, log, true, folder);
        const int code = child_exit_code(pid, true).value_or(-1);
        if (code != 0) {
            fmt::print(stderr, "sphclip: warning: gnuplot failed on {} (exit {}); no plot:\n{}\n",
                       script.string(), code, last_lines(log, 5));
            return false;
        }
    } catch (const std::exception& e) {
        std::error_code ec;
        fs::remove(log, ec);
        fmt::print(stderr, "sphclip: warning: no plot {} ({}); is gnuplot installed?\n",
                   png.string(), e.what());
        return false;
    }
    std::error_code ec;
    fs::remove(log, ec);
    return true;
}

} // namespace sph
