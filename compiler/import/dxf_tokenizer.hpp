#pragma once
// Reads an ASCII DXF file as a stream of (group code, value) pairs, remembering the line of each, so that
// every later error can point at the exact line. Knows nothing about entities.
#include <cstddef>
#include <istream>
#include <string>

namespace walk::compiler {

struct DxfPair {
  int code = 0;
  std::string value;           // trimmed of surrounding blanks and a trailing CR
  std::size_t code_line = 0;   // 1-based line of the group code
  std::size_t value_line = 0;  // 1-based line of the value
};

// The value of a pair as a finite number or an integer; throws walk::Error naming `file` and the value's
// line.
[[nodiscard]] double dxf_number(const DxfPair& pair, const std::string& file);
[[nodiscard]] int dxf_integer(const DxfPair& pair, const std::string& file);

class DxfTokenizer {
 public:
  // `file` is only used in error messages.
  DxfTokenizer(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}

  // Reads the next pair; false at the end of the input. Throws walk::Error for a non-numeric group code or a
  // group code without a value line (a truncated file).
  bool next(DxfPair& out);

  // The value as a number; throws walk::Error naming the value's line when it is not one.
  [[nodiscard]] double number(const DxfPair& pair) const { return dxf_number(pair, file_); }
  [[nodiscard]] int integer(const DxfPair& pair) const { return dxf_integer(pair, file_); }

  [[nodiscard]] std::size_t lines_read() const { return line_; }
  [[nodiscard]] const std::string& file() const { return file_; }

 private:
  bool read_line(std::string& out);

  std::istream& in_;
  std::string file_;
  std::size_t line_ = 0;
};

}  // namespace walk::compiler
