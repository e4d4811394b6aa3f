#pragma once
// Shared by the end-to-end tests of validate and study: runs the real program
// (SPHCLIP_EXE, from CMake) and reads the CSV files it writes.

#include "temp_folder.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace sph::test {

struct ProgramResult {
    int exit_code = -1;
    std::string output; // stdout and stderr together
};

inline std::string shell_quote(const std::string& word) {
    std::string quoted = "'";
    for (char c : word)
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

// `sphclip ARGS...` in the folder `cwd`. Idle OpenMP threads sleep rather
// than spin, so that runs side by side on two cores do not starve each other.
inline ProgramResult
run_sphclip(const TempFolder& tmp, const std::vector<std::string>& args,
            const std::filesystem::path& cwd = std::filesystem::current_path()) {
    const auto log = tmp / "sphclip.log";
    // fmt, not operator+: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string.
    std::string command = fmt::format("cd {} && OMP_WAIT_POLICY=passive {}",
                                      shell_quote(cwd.string()), shell_quote(SPHCLIP_EXE));
    for (const auto& arg : args)
        command += fmt::format(" {}", shell_quote(arg));
    command += fmt::format(" > {} 2>&1", shell_quote(log.string()));
    const int status = std::system(command.c_str());
    ProgramResult result;
    result.exit_code = status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    result.output = read_text(log);
    return result;
}

// A CSV file as text cells, by column name. Quoted cells are not split.
struct TextCsv {
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;

    bool has(const std::string& name) const {
        return std::find(header.begin(), header.end(), name) != header.end();
    }
    const std::string& at(std::size_t row, const std::string& name) const {
        const auto column =
            std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
        return rows.at(row).at(column);
    }
};

inline std::vector<std::string> split_csv_line(const std::string& line) {
    std::vector<std::string> cells(1);
    bool quoted = false;
    for (char c : line) {
        if (c == '"')
            quoted = !quoted;
        else if (c == ',' && !quoted)
            cells.emplace_back();
        else
            cells.back() += c;
    }
    return cells;
}

inline TextCsv read_text_csv(const std::filesystem::path& path) {
    std::istringstream in(read_text(path));
    TextCsv csv;
    std::string line;
    while (std::getline(in, line)) {
        if (line.empty())
            continue;
        if (csv.header.empty())
            csv.header = split_csv_line(line);
        else
            csv.rows.push_back(split_csv_line(line));
    }
    return csv;
}

inline bool is_png(const std::filesystem::path& path) {
    const std::string text = read_text(path);
    return text.size() > 1000 && text.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0;
}

} // namespace sph::test
