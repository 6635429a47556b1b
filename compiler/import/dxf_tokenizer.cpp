#include "compiler/import/dxf_tokenizer.hpp"

#include <charconv>
#include <cmath>
#include <string_view>

#include "model/error.hpp"

namespace walk::compiler {
namespace {

std::string trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return std::string(text.substr(first, last - first + 1));
}

}  // namespace

bool DxfTokenizer::read_line(std::string& out) {
  if (!std::getline(in_, out)) return false;
  ++line_;
  return true;
}

bool DxfTokenizer::next(DxfPair& out) {
  std::string code_text;
  if (!read_line(code_text)) return false;
  out.code_line = line_;
  const std::string code = trimmed(code_text);
  int value = 0;
  const auto [end, ec] = std::from_chars(code.data(), code.data() + code.size(), value);
  if (code.empty() || ec != std::errc() || end != code.data() + code.size()) {
    throw Error(located(file_, line_, "expected a DXF group code (an integer), found \"" + code + "\"",
                        "the file is not an ASCII DXF or its code/value lines are out of step; re-export it "
                        "as ASCII DXF"));
  }
  out.code = value;
  std::string value_text;
  if (!read_line(value_text)) {
    throw Error(located(file_, out.code_line, "group code " + code + " has no value: the file is truncated",
                        "the file ends in the middle of a code/value pair; copy or export it again"));
  }
  out.value_line = line_;
  out.value = trimmed(value_text);
  return true;
}

double dxf_number(const DxfPair& pair, const std::string& file_) {
  double value = 0.0;
  const std::string& text = pair.value;
  // from_chars does not accept a leading '+', which some writers emit.
  const char* begin = text.data() + ((!text.empty() && text[0] == '+') ? 1 : 0);
  const auto [end, ec] = std::from_chars(begin, text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    throw Error(
        located(file_, pair.value_line,
                "group code " + std::to_string(pair.code) + " needs a finite number, found \"" + text + "\"",
                "fix or remove this value in the DXF file"));
  }
  return value;
}

int dxf_integer(const DxfPair& pair, const std::string& file_) {
  int value = 0;
  const std::string& text = pair.value;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
    throw Error(
        located(file_, pair.value_line,
                "group code " + std::to_string(pair.code) + " needs an integer, found \"" + text + "\"",
                "fix or remove this value in the DXF file"));
  }
  return value;
}

}  // namespace walk::compiler
