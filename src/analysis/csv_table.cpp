#include "analysis/csv_table.hpp"

#include "output/files.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace sph {

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

double parse_number(std::string_view cell) {
    cell = trim(cell);
    if (cell.empty())
        return std::numeric_limits<double>::quiet_NaN();
    // strtod needs a terminated string; cells are short.
    const std::string text(cell);
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    return end == text.c_str() + text.size() ? value : std::numeric_limits<double>::quiet_NaN();
}

} // namespace

bool CsvTable::has(std::string_view name) const {
    return std::find(names.begin(), names.end(), name) != names.end();
}

const std::vector<double>& CsvTable::column(std::string_view name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
        throw std::runtime_error(source + ": no column \"" + std::string(name) + "\"");
    return columns[std::size_t(it - names.begin())];
}

CsvTable parse_csv_table(std::string_view text, std::string source) {
    CsvTable table;
    table.source = std::move(source);
    bool header = true;
    while (!text.empty()) {
        const std::size_t eol = text.find('\n');
        std::string_view line = text.substr(0, eol);
        text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
        line = trim(line);
        if (line.empty() || line.front() == '#')
            continue;
        std::size_t column = 0;
        while (true) {
            const std::size_t comma = line.find(',');
            const std::string_view cell = line.substr(0, comma);
            if (header) {
                table.names.emplace_back(trim(cell));
                table.columns.emplace_back();
            } else if (column < table.columns.size()) {
                table.columns[column].push_back(parse_number(cell));
            }
            ++column;
            if (comma == std::string_view::npos)
                break;
            line.remove_prefix(comma + 1);
        }
        if (!header)
            for (; column < table.columns.size(); ++column)
                table.columns[column].push_back(std::numeric_limits<double>::quiet_NaN());
        header = false;
    }
    return table;
}

CsvTable read_csv_table(const std::filesystem::path& path) {
    // FileReadError is a runtime_error that names the file.
    return parse_csv_table(read_input_file(path, table_file_limit), path.string());
}

} // namespace sph
