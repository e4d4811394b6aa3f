#pragma once
// A numeric CSV file with a header row, read by column name: a writer that
// adds columns (stats.csv grows with the solvers) never shifts what a reader
// sees. Lines starting with '#' are comments (the reference tables use them).

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace sph {

struct CsvTable {
    std::string source; // the file, for messages
    std::vector<std::string> names;
    std::vector<std::vector<double>> columns; // one per name; a cell that is no number is NaN

    std::size_t rows() const { return columns.empty() ? 0 : columns.front().size(); }
    bool has(std::string_view name) const;
    // Throws std::runtime_error naming the file and the missing column.
    const std::vector<double>& column(std::string_view name) const;
};

// Rows shorter than the header are padded with NaN; a row cut off by a run
// that stopped mid-write is kept as far as it goes.
CsvTable parse_csv_table(std::string_view text, std::string source);

// Throws std::runtime_error when the file cannot be read.
CsvTable read_csv_table(const std::filesystem::path& path);

} // namespace sph
