#pragma once
// A small RFC 4180 CSV table: header row + string cells, with errors that name file, row and column.
// Used for every tabular file crowdlab reads or writes (manifests, responses, trajectories).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace crowdlab {

struct CsvTable {
  std::string source;  ///< file path (for error messages)
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  ///< every row has header.size() cells
  std::vector<int> line_numbers;               ///< 1-based file line of each row

  /// Column index by name; throws InputError "<file>: missing column '<name>'" when absent.
  size_t column(const std::string& name) const;
  bool has_column(const std::string& name) const;
  /// Cell as a number; throws InputError "<file>:<line>: column '<name>': not a number: '<cell>'".
  double number(size_t row, size_t col) const;
  const std::string& cell(size_t row, size_t col) const { return rows[row][col]; }
};

/// Parses CSV text. Quoted fields may contain commas, quotes ("") and newlines.
/// Throws InputError on a ragged row or an unterminated quote, naming the line.
CsvTable parse_csv(const std::string& text, const std::string& source);
/// Reads and parses a file; throws InputError when it cannot be opened.
/// Largest CSV file read (the parsed table takes several times its size in memory).
inline constexpr std::uintmax_t kMaxCsvBytes = std::uintmax_t{1} << 30;

/// parse_csv of a regular file of at most kMaxCsvBytes; a FIFO or device is refused before it is opened.
CsvTable read_csv(const std::string& path);

/// Quotes a field when it contains a comma, quote, CR or LF.
std::string csv_escape(const std::string& field);
/// One CSV line (with trailing '\n') from fields.
std::string csv_line(const std::vector<std::string>& fields);
/// Shortest round-trip decimal text of a double ("%.17g" trimmed); "nan"/"inf" never written: empty.
std::string csv_number(double value);

}  // namespace crowdlab
