#include "compiler/photometry/ies_reader.hpp"

#include <spdlog/spdlog.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <vector>

#include "compiler/photometry/symmetry.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

// A published table at 0.1 degree by 1 degree holds 650,000 values: more is a corrupt count, refused before
// memory is reserved for it.
constexpr std::int64_t kMaxTableValues = 1'000'000;

// The numbers after the TILT line, each with the line it is on: LM-63 lets them wrap anywhere.
class NumberStream {
 public:
  NumberStream(std::string_view text, std::size_t first_line, const std::string& path)
      : text_(text), line_(first_line), path_(path) {}

  double next(const char* what) {
    skip_space();
    if (pos_ >= text_.size())
      throw Error(located(path_, line_, std::string("the file ends where ") + what + " should be",
                          "check the counts of angles against the values that follow"));
    std::size_t end = pos_;
    while (end < text_.size() && !is_space(text_[end])) ++end;
    const std::string token(text_.substr(pos_, end - pos_));
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v))
      throw Error(located(path_, line_, "'" + token + "' where " + what + " should be: not a number"));
    pos_ = end;
    return v;
  }
  int count(const char* what, int lo, int hi) {
    const double v = next(what);
    if (v != std::floor(v) || v < lo || v > hi)
      throw Error(located(path_, line_,
                          std::string(what) + " is " + fmt_number(v) + ", expected a whole number from " +
                              std::to_string(lo) + " to " + std::to_string(hi)));
    return static_cast<int>(v);
  }
  std::size_t line() const { return line_; }
  bool at_end() {
    skip_space();
    return pos_ >= text_.size();
  }

 private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == ','; }
  static std::string fmt_number(double v) { return std::to_string(v); }
  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_;
  const std::string& path_;
};

// Type C files mark their symmetry by their first and last horizontal angle (LM-63-2002 section 5.6).
CSymmetry symmetry_of(const std::vector<double>& c, const std::string& path, std::size_t line) {
  const double first = c.front(), last = c.back();
  if (c.size() == 1 && first == 0.0) return CSymmetry::Rotational;
  if (first == 0.0 && last == 90.0) return CSymmetry::Quadrant;
  if (first == 0.0 && last == 180.0) return CSymmetry::BilateralC0;
  if (first == 90.0 && last == 270.0) return CSymmetry::BilateralC90;
  if (first == 0.0 && last > 180.0 && last <= 360.0) return CSymmetry::None;
  throw Error(located(path, line,
                      "horizontal angles run from " + std::to_string(first) + " to " + std::to_string(last) +
                          ", which is no LM-63 type C layout (0; 0-90; 0-180; 90-270; 0-360)"));
}

}  // namespace

model::IntensityDistribution parse_ies(std::string_view text, const std::string& path) {
  // Header: keyword and text lines up to TILT=.
  std::size_t line = 1, pos = 0;
  std::string tilt;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    std::string_view l = text.substr(pos, end - pos);
    pos = end + 1;
    if (l.rfind("TILT=", 0) == 0 || l.rfind("TILT =", 0) == 0) {
      tilt = std::string(l.substr(l.find('=') + 1));
      while (!tilt.empty() && (tilt.back() == '\r' || tilt.back() == ' ')) tilt.pop_back();
      while (!tilt.empty() && tilt.front() == ' ') tilt.erase(tilt.begin());
      break;
    }
    ++line;
  }
  if (tilt.empty())
    throw Error(located(path, 0, "no TILT= line: not an IES LM-63 photometric file",
                        "export the luminaire's photometry as IES LM-63 (.ies) or EULUMDAT (.ldt)"));
  NumberStream in(pos < text.size() ? text.substr(pos) : std::string_view{}, line + 1, path);
  if (tilt == "INCLUDE") {
    // Lamp-to-luminaire geometry, then angle/multiplier pairs: only for lamps tilted in use; the luminaire
    // is simulated as photometered.
    in.count("the lamp-to-luminaire geometry", 1, 3);
    const int pairs = in.count("the number of tilt angles", 0, 10000);
    for (int i = 0; i < 2 * pairs; ++i) in.next("a tilt angle or multiplier");
    spdlog::warn("{}: TILT=INCLUDE: the tilt table is ignored (the lamp is taken as photometered)", path);
  } else if (tilt != "NONE") {
    spdlog::warn("{}: TILT={}: the tilt file is ignored (the lamp is taken as photometered)", path, tilt);
  }
  model::IntensityDistribution d;
  d.source = path;
  const int lamps = in.count("the number of lamps", 1, 1000);
  const double lumens_per_lamp = in.next("lumens per lamp");
  const double multiplier = in.next("the candela multiplier");
  const int n_vertical = in.count("the number of vertical angles", 1, 100000);
  const int n_horizontal = in.count("the number of horizontal angles", 1, 100000);
  const std::size_t type_line = in.line();
  const int photometric_type = in.count("the photometric type", 1, 3);
  in.count("the units type", 1, 2);
  for (const char* dim : {"the luminous width", "the luminous length", "the luminous height"}) in.next(dim);
  const double ballast = in.next("the ballast factor");
  const double ballast_lamp = in.next("the ballast-lamp photometric factor");
  in.next("the input watts");
  if (photometric_type != 1)
    throw Error(
        located(path, type_line,
                std::string("photometric type ") +
                    (photometric_type == 2 ? "B (floodlights)" : "A (automotive)") + " is not supported",
                "ask the manufacturer for type C photometry, the usual kind for building luminaires"));
  if (!(multiplier > 0.0) || !(ballast > 0.0) || !(ballast_lamp > 0.0))
    throw Error(
        located(path, type_line, "the candela multiplier and ballast factors must be greater than 0"));
  if (std::int64_t(n_vertical) * n_horizontal > kMaxTableValues)
    throw Error(located(path, type_line,
                        std::to_string(n_vertical) + " x " + std::to_string(n_horizontal) +
                            " angles is more than the " + std::to_string(kMaxTableValues) +
                            " intensities a photometric table may hold"));
  std::vector<double> horizontal(n_horizontal);
  d.gamma_deg.resize(n_vertical);
  for (auto& g : d.gamma_deg) g = in.next("a vertical angle");
  const std::size_t horizontal_line = in.line();
  for (auto& c : horizontal) c = in.next("a horizontal angle");
  const double scale = multiplier * ballast * ballast_lamp;
  std::vector<std::vector<double>> rows(n_horizontal, std::vector<double>(n_vertical));
  for (auto& row : rows)
    for (auto& v : row) v = in.next("a candela value") * scale;
  if (!in.at_end()) spdlog::warn("{}:{}: values after the last candela value are ignored", path, in.line());
  for (std::size_t i = 1; i < horizontal.size(); ++i)
    if (!(horizontal[i] > horizontal[i - 1]))
      throw Error(located(path, horizontal_line, "horizontal angles must increase"));
  if (lumens_per_lamp > 0.0) d.declared_lumens = lamps * lumens_per_lamp;
  expand_symmetry(d, symmetry_of(horizontal, path, horizontal_line), horizontal, rows);
  model::finish(d);
  return d;
}

}  // namespace walk::compiler
