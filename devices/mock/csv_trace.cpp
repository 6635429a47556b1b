#include "devices/mock/csv_trace.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>

#include "model/error.hpp"

namespace walk::devices {
namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(
        trim(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return fields;
}

bool parse_number(const std::string& text, double& out) {
  if (text.empty()) return false;
  const char* begin = text.data();
  if (*begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, text.data() + text.size(), out);
  return ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(out);
}

bool contains(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

}  // namespace

CsvTrace CsvTrace::load(const std::string& path, const std::vector<std::string>& required,
                        const std::vector<std::string>& optional, bool allow_extra) {
  std::ifstream in(path);
  if (!in) throw Error(located(path, 0, "cannot open trace file", "check the path in the kiosk config"));

  CsvTrace trace;
  trace.path_ = path;
  std::string line;
  std::size_t line_number = 0;
  std::size_t header_fields = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string text = trim(line);
    if (text.empty() || text[0] == '#') continue;  // blank lines and comments are allowed anywhere
    auto fields = split(text);
    if (header_fields == 0) {
      if (fields[0] != "time")
        throw Error(located(path, line_number, "first column is '" + fields[0] + "', expected 'time'",
                            "the first line must name the columns, e.g. time,speed"));
      for (std::size_t i = 1; i < fields.size(); ++i) {
        const auto& name = fields[i];
        if (name.empty() || contains(trace.columns_, name))
          throw Error(located(path, line_number, "empty or repeated column name '" + name + "'"));
        if (!allow_extra && !contains(required, name) && !contains(optional, name))
          throw Error(located(path, line_number, "unknown column '" + name + "'"));
        trace.columns_.push_back(name);
      }
      for (const auto& name : required)
        if (!contains(trace.columns_, name))
          throw Error(located(path, line_number, "missing column '" + name + "'"));
      header_fields = fields.size();
      continue;
    }
    if (fields.size() != header_fields)
      throw Error(located(path, line_number,
                          "has " + std::to_string(fields.size()) + " columns, the header has " +
                              std::to_string(header_fields)));
    for (std::size_t i = 0; i < fields.size(); ++i) {
      double v = 0.0;
      if (!parse_number(fields[i], v))
        throw Error(located(path, line_number,
                            "'" + fields[i] + "' in column '" + (i == 0 ? "time" : trace.columns_[i - 1]) +
                                "' is not a number"));
      if (i == 0) {
        if (v < 0.0)
          throw Error(located(path, line_number, "time " + fields[i] + " is negative",
                              "times are seconds from the start of the walk, from 0"));
        if (!trace.times_.empty() && v <= trace.times_.back())
          throw Error(located(path, line_number, "time " + fields[i] + " is not after the previous row's",
                              "times must increase strictly"));
        trace.times_.push_back(v);
        trace.lines_.push_back(line_number);
      } else {
        trace.values_.push_back(v);
      }
    }
  }
  if (header_fields == 0) throw Error(located(path, 0, "trace is empty", "expected a header line"));
  return trace;
}

std::size_t CsvTrace::column(const std::string& name) const {
  const auto it = std::find(columns_.begin(), columns_.end(), name);
  return it == columns_.end() ? npos : static_cast<std::size_t>(it - columns_.begin());
}

std::size_t CsvTrace::row_at(double now) const {
  const auto it = std::upper_bound(times_.begin(), times_.end(), now);
  if (it == times_.begin()) return npos;
  return static_cast<std::size_t>(it - times_.begin()) - 1;
}

}  // namespace walk::devices
