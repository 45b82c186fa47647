#include "framework/core/csv.hpp"

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/core/printable_excerpt.hpp"

namespace crowdlab {

size_t CsvTable::column(const std::string& name) const {
  for (size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  throw InputError(SourceLocation{source, 1, 0, name}, "missing column '" + name + "'");
}

bool CsvTable::has_column(const std::string& name) const {
  for (const auto& h : header)
    if (h == name) return true;
  return false;
}

double CsvTable::number(size_t row, size_t col) const {
  const std::string& s = rows[row][col];
  double v = 0.0;
  const char* begin = s.data();
  const char* end = s.data() + s.size();
  while (begin < end && *begin == ' ') ++begin;
  auto [ptr, ec] = std::from_chars(begin, end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v))
    throw InputError(
        SourceLocation{source, line_numbers[row], static_cast<int>(col) + 1, "column '" + header[col] + "'"},
        (ec == std::errc::result_out_of_range ? "a number outside the range of a double: "
                                              : "not a finite number: ") +
            quote_value(s));
  return v;
}

CsvTable parse_csv(const std::string& text, const std::string& source) {
  CsvTable t;
  t.source = source;
  std::vector<std::string> record;
  std::string field;
  bool in_quotes = false, field_started = false;
  int line = 1, record_line = 1;
  // A UTF-8 byte-order mark (Excel's "CSV UTF-8") is not part of the first column's name.
  const size_t start = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  auto end_record = [&] {
    record.push_back(field);
    field.clear();
    field_started = false;
    const bool blank = record.size() == 1 && record[0].empty();
    if (!blank) {
      if (t.header.empty()) {
        t.header = record;
      } else {
        if (record.size() != t.header.size())
          throw InputError(SourceLocation{source, record_line, 0, ""},
                           "row has " + std::to_string(record.size()) + " fields, header has " +
                               std::to_string(t.header.size()));
        t.rows.push_back(record);
        t.line_numbers.push_back(record_line);
      }
    }
    record.clear();
  };
  for (size_t i = start; i < text.size(); ++i) {
    const char c = text[i];
    if (in_quotes) {
      if (c == '"') {
        if (i + 1 < text.size() && text[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          in_quotes = false;
        }
      } else {
        if (c == '\n') ++line;
        field += c;
      }
      continue;
    }
    if (c == '"' && !field_started) {
      in_quotes = true;
      field_started = true;
    } else if (c == ',') {
      record.push_back(field);
      field.clear();
      field_started = false;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
      end_record();
      ++line;
      record_line = line;
    } else {
      field += c;
      field_started = true;
    }
  }
  if (in_quotes) throw InputError(SourceLocation{source, record_line, 0, ""}, "unterminated quoted field");
  if (!field.empty() || !record.empty()) end_record();
  if (t.header.empty()) throw InputError(SourceLocation{source, 1, 0, ""}, "empty CSV file (no header row)");
  return t;
}

CsvTable read_csv(const std::string& path) {
  // FIFOs and devices (/dev/zero never ends) are refused before they are opened (issue 32).
  return parse_csv(
      read_regular_file(path, "CSV", kMaxCsvBytes, "nothing: split the table into several files"), path);
}

std::string csv_escape(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (char c : field) out += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
  std::string out;
  for (size_t i = 0; i < fields.size(); ++i) {
    if (i) out += ',';
    out += csv_escape(fields[i]);
  }
  return out + "\n";
}

std::string csv_number(double value) {
  if (!std::isfinite(value)) return "";
  char buf[64];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, value);
  return ec == std::errc() ? std::string(buf, ptr) : std::string();
}

}  // namespace crowdlab
