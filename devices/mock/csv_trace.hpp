#pragma once
// A recorded device trace: a CSV file whose header names the columns, the first being `time` (seconds).
// Loading validates every row so a bad trace fails at start-up with file:line, never mid-walk.
#include <cstddef>
#include <string>
#include <vector>

namespace walk::devices {

class CsvTrace {
 public:
  // Reads `path`. `required` columns must be present (after `time`); `optional` ones may be; any other
  // column is an error unless `allow_extra` is set. Throws walk::Error naming the file and line.
  static CsvTrace load(const std::string& path, const std::vector<std::string>& required,
                       const std::vector<std::string>& optional = {}, bool allow_extra = false);

  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const std::vector<std::string>& columns() const { return columns_; }  // without `time`
  [[nodiscard]] std::size_t size() const { return times_.size(); }
  [[nodiscard]] double time(std::size_t row) const { return times_[row]; }
  [[nodiscard]] std::size_t line(std::size_t row) const { return lines_[row]; }  // file line, for errors
  [[nodiscard]] double value(std::size_t row, std::size_t column) const {
    return values_[row * columns_.size() + column];
  }
  // Index of a column (without `time`), or npos when absent.
  [[nodiscard]] std::size_t column(const std::string& name) const;
  // The newest row with time <= now, or npos when none has been reached yet.
  [[nodiscard]] std::size_t row_at(double now) const;

  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

 private:
  std::string path_;
  std::vector<std::string> columns_;
  std::vector<double> times_;
  std::vector<std::size_t> lines_;
  std::vector<double> values_;  // row-major, columns_.size() per row
};

}  // namespace walk::devices
