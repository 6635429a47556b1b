#include "compiler/photometry/eulumdat_reader.hpp"

#include <charconv>
#include <cmath>
#include <vector>

#include "compiler/photometry/symmetry.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

class Lines {
 public:
  Lines(std::string_view text, const std::string& path) : path_(path) {
    std::size_t pos = 0;
    while (pos < text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      std::string_view l = text.substr(pos, end - pos);
      while (!l.empty() && (l.back() == '\r' || l.back() == ' ' || l.back() == '\t')) l.remove_suffix(1);
      while (!l.empty() && (l.front() == ' ' || l.front() == '\t')) l.remove_prefix(1);
      lines_.push_back(l);
      pos = end + 1;
    }
  }
  std::string_view text(const char* what) {
    if (next_ >= lines_.size())
      throw Error(located(path_, next_ + 1, std::string("the file ends where ") + what + " should be",
                          "EULUMDAT has one field per line; check the counts of C planes and angles"));
    return lines_[next_++];
  }
  double number(const char* what) {
    const std::string_view t = text(what);
    std::string token(t);
    for (auto& c : token)
      if (c == ',') c = '.';  // some exporters write a decimal comma
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), v);
    if (token.empty() || ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(v))
      throw Error(
          located(path_, next_, "'" + std::string(t) + "' where " + what + " should be: not a number"));
    return v;
  }
  int count(const char* what, int lo, int hi) {
    const double v = number(what);
    if (v != std::floor(v) || v < lo || v > hi)
      throw Error(located(path_, next_,
                          std::string(what) + " is " + std::to_string(v) + ", expected a whole number from " +
                              std::to_string(lo) + " to " + std::to_string(hi)));
    return static_cast<int>(v);
  }
  std::size_t line() const { return next_; }  // of the field read last

 private:
  std::vector<std::string_view> lines_;
  std::size_t next_ = 0;
  const std::string& path_;
};

}  // namespace

model::IntensityDistribution parse_eulumdat(std::string_view text, const std::string& path) {
  Lines in(text, path);
  model::IntensityDistribution d;
  d.source = path;
  in.text("the company");
  in.count("the type indicator Ityp", 0, 3);
  const int isym = in.count("the symmetry indicator Isym", 0, 4);
  const std::size_t isym_line = in.line();
  const int mc = in.count("the number of C planes Mc", 1, 721);
  in.number("the C plane spacing Dc");
  const int ng = in.count("the number of intensities per plane Ng", 1, 3601);
  in.number("the intensity spacing Dg");
  for (const char* field : {"the measurement report", "the luminaire name", "the luminaire number",
                            "the file name", "the date and user"})
    in.text(field);
  for (const char* field : {"the luminaire length", "the luminaire width", "the luminaire height",
                            "the luminous area length", "the luminous area width", "the luminous height C0",
                            "the luminous height C90", "the luminous height C180", "the luminous height C270",
                            "the downward flux fraction", "the light output ratio"})
    in.number(field);
  const double conversion = in.number("the intensity conversion factor");
  const std::size_t conversion_line = in.line();
  in.number("the tilt during measurement");
  const int sets = in.count("the number of lamp sets", 1, 20);
  std::vector<double> lamps(sets), flux(sets);
  for (auto& n : lamps) n = in.number("a number of lamps");
  for (int i = 0; i < sets; ++i) in.text("a lamp type");
  for (auto& f : flux) f = in.number("a lamp set's luminous flux");
  for (int i = 0; i < sets; ++i) in.text("a colour appearance");
  for (int i = 0; i < sets; ++i) in.text("a colour rendering group");
  for (int i = 0; i < sets; ++i) in.number("a lamp set's wattage");
  for (int i = 0; i < 10; ++i) in.number("a direct ratio");
  std::vector<double> all_c(mc);
  for (auto& c : all_c) c = in.number("a C angle");
  d.gamma_deg.resize(ng);
  for (auto& g : d.gamma_deg) g = in.number("a gamma angle");
  double lamp_flux = 0.0;
  for (double f : flux) lamp_flux += f;
  if (!(lamp_flux > 0.0) || !(conversion > 0.0))
    throw Error(located(path, conversion_line,
                        "the lamp flux and the conversion factor must be greater than 0: intensities are per "
                        "1000 lm of lamp flux"));
  d.declared_lumens = lamp_flux;
  // Which planes the file stores: EN 13032-1 annex B.
  CSymmetry symmetry = CSymmetry::None;
  std::size_t first = 0, stored = mc;
  switch (isym) {
    case 1:
      symmetry = CSymmetry::Rotational, stored = 1;
      break;
    case 2:
      symmetry = CSymmetry::BilateralC0, stored = mc / 2 + 1;
      break;
    case 3:
      symmetry = CSymmetry::BilateralC90, first = mc / 4, stored = mc / 2 + 1;
      break;
    case 4:
      symmetry = CSymmetry::Quadrant, stored = mc / 4 + 1;
      break;
    default:
      break;
  }
  if (first + stored > all_c.size())
    throw Error(
        located(path, isym_line,
                "Isym " + std::to_string(isym) + " needs more C planes than Mc = " + std::to_string(mc)));
  std::vector<double> c(all_c.begin() + first, all_c.begin() + first + stored);
  const double scale = conversion * lamp_flux / 1000.0;
  std::vector<std::vector<double>> rows(stored, std::vector<double>(ng));
  for (auto& row : rows)
    for (auto& v : row) v = in.number("an intensity (cd/klm)") * scale;
  expand_symmetry(d, symmetry, c, rows);
  model::finish(d);
  return d;
}

}  // namespace walk::compiler
