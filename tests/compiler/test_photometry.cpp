// Photometric input: IES LM-63 and EULUMDAT tables (symmetries, scaling, flux, bad files), colour
// temperature, and measured distributions shot by the solver and gathered by direct light alike.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "compiler/geometry/mesher.hpp"
#include "compiler/lighting/direct_light.hpp"
#include "compiler/photometry/colour_temperature.hpp"
#include "compiler/photometry/emission.hpp"
#include "compiler/photometry/eulumdat_reader.hpp"
#include "compiler/photometry/ies_reader.hpp"
#include "compiler/radiosity/progressive_solver.hpp"
#include "model/error.hpp"
#include "model/photometric_units.hpp"

namespace walk::compiler {
namespace test_photometry {  // named, not anonymous: the suite compiles as unity batches

using model::Vec3;
constexpr double kDeg = std::numbers::pi / 180.0;

// An LM-63-2002 file with the given angles and candela(gamma, c), one lamp of `lumens` (-1: absolute).
template <typename F>
std::string ies_text(const std::vector<double>& gammas, const std::vector<double>& cs, F candela,
                     double multiplier = 1.0, double ballast = 1.0, double lumens = -1.0, int type = 1) {
  std::ostringstream o;
  o << "IESNA:LM-63-2002\n[TEST] unit test\n[MANUFAC] none\nTILT=NONE\n";
  o << "1 " << lumens << " " << multiplier << " " << gammas.size() << " " << cs.size() << " " << type
    << " 2 0.1 0.1 0.0\n";
  o << ballast << " 1.0 20\n";
  for (double g : gammas) o << g << " ";
  o << "\n";
  for (double c : cs) o << c << " ";
  o << "\n";
  for (double c : cs) {
    for (double g : gammas) o << candela(g, c) << " ";
    o << "\n";
  }
  return o.str();
}

std::vector<double> steps(double from, double to, double step) {
  std::vector<double> v;
  for (double a = from; a <= to + 1e-9; a += step) v.push_back(a);
  return v;
}

TEST(Photometry, IsotropicTableIntegratesToFourPiTimesItsIntensity) {
  const auto d = parse_ies(ies_text(steps(0, 180, 10), {0}, [](double, double) { return 100.0; }), "iso.ies");
  EXPECT_EQ(d.c_deg.size(), 1u);
  EXPECT_NEAR(d.lumens, 4.0 * std::numbers::pi * 100.0, 1e-4 * d.lumens);
  EXPECT_DOUBLE_EQ(d.candela_at(37.0, 123.0), 100.0);
}

TEST(Photometry, LambertianDownlightIntegratesToPiTimesItsPeak) {
  // I = 1000 cos(gamma) below the horizon, tabulated every 2.5 degrees: flux pi * 1000 up to the table's
  // linear interpolation of the cosine (under 0.05 % at this spacing).
  const auto d = parse_ies(
      ies_text(steps(0, 90, 2.5), {0}, [](double g, double) { return 1000.0 * std::cos(g * kDeg); }),
      "l.ies");
  EXPECT_NEAR(d.lumens, std::numbers::pi * 1000.0, 5e-4 * d.lumens);
  EXPECT_EQ(d.candela_at(120.0, 0.0), 0.0);  // beyond the table's last angle: dark
}

TEST(Photometry, MultiplierAndBallastFactorScaleTheCandela) {
  auto flat = [](double, double) { return 10.0; };
  const auto d = parse_ies(ies_text(steps(0, 180, 30), {0}, flat, 2.5, 0.8, 1500.0), "s.ies");
  EXPECT_DOUBLE_EQ(d.candela_at(0.0, 0.0), 10.0 * 2.5 * 0.8);
  EXPECT_DOUBLE_EQ(d.declared_lumens, 1500.0);
}

TEST(Photometry, HorizontalSymmetriesExpandToTheWholeCircle) {
  // A value that tells C planes apart: candela = 100 + C in the stored range.
  auto by_c = [](double, double c) { return 100.0 + c; };
  const auto g = steps(0, 90, 45);
  const auto quadrant = parse_ies(ies_text(g, steps(0, 90, 30), by_c), "q.ies");
  EXPECT_DOUBLE_EQ(quadrant.candela_at(45, 30), 130.0);
  EXPECT_DOUBLE_EQ(quadrant.candela_at(45, 150), 130.0);  // mirrored about C90
  EXPECT_DOUBLE_EQ(quadrant.candela_at(45, 210), 130.0);  // and about C180
  EXPECT_DOUBLE_EQ(quadrant.candela_at(45, 330), 130.0);
  EXPECT_DOUBLE_EQ(quadrant.candela_at(45, 45), 145.0);  // between stored planes: linear
  const auto bilateral = parse_ies(ies_text(g, steps(0, 180, 30), by_c), "b.ies");
  EXPECT_DOUBLE_EQ(bilateral.candela_at(45, 120), 220.0);
  EXPECT_DOUBLE_EQ(bilateral.candela_at(45, 240), 220.0);  // mirrored about the C0-C180 plane
  const auto bilateral90 = parse_ies(ies_text(g, steps(90, 270, 30), by_c), "b90.ies");
  EXPECT_DOUBLE_EQ(bilateral90.candela_at(45, 60), 220.0);   // C60 sees C120
  EXPECT_DOUBLE_EQ(bilateral90.candela_at(45, 300), 340.0);  // C300 sees C240
  const auto full = parse_ies(ies_text(g, steps(0, 360, 30), by_c), "f.ies");
  EXPECT_DOUBLE_EQ(full.candela_at(45, 300), 400.0);
  EXPECT_DOUBLE_EQ(full.candela_at(45, -60), 400.0);  // periodic
  for (const auto* d : {&quadrant, &bilateral, &bilateral90, &full}) {
    EXPECT_EQ(d->c_deg.front(), 0.0);
    EXPECT_EQ(d->c_deg.back(), 360.0);
  }
}

TEST(Photometry, TiltIncludeIsReadPast) {
  std::string text = ies_text(steps(0, 180, 90), {0}, [](double, double) { return 5.0; });
  text.replace(text.find("TILT=NONE"), 9, "TILT=INCLUDE\n1\n3\n0 45 90\n1.0 0.9 0.8");
  EXPECT_DOUBLE_EQ(parse_ies(text, "t.ies").candela_at(90, 0), 5.0);
}

// The message of the walk::Error that parsing `text` throws.
template <typename Parse>
std::string error_of(Parse parse, const std::string& text, const std::string& path) {
  try {
    (void)parse(text, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(Photometry, BadIesFilesNameTheFileLineAndWhat) {
  auto flat = [](double, double) { return 5.0; };
  const std::string good = ies_text(steps(0, 180, 90), {0}, flat);
  EXPECT_NE(error_of(parse_ies, "IESNA:LM-63-2002\n[TEST] x\n", "a.ies").find("a.ies: no TILT= line"),
            std::string::npos);
  std::string garbage = good;
  garbage.replace(garbage.rfind("5 "), 1, "x5");  // a candela value on line 9
  EXPECT_NE(error_of(parse_ies, garbage, "g.ies").find("g.ies:9: 'x5' where a candela value should be"),
            std::string::npos)
      << error_of(parse_ies, garbage, "g.ies");
  const std::string short_file = good.substr(0, good.rfind("5 "));
  EXPECT_NE(error_of(parse_ies, short_file, "s.ies").find("the file ends where a candela value should be"),
            std::string::npos);
  EXPECT_NE(error_of(parse_ies, ies_text(steps(0, 180, 90), {0}, flat, 1, 1, -1, 2), "b.ies")
                .find("b.ies:5: photometric type B"),
            std::string::npos);
  EXPECT_NE(error_of(parse_ies, ies_text(steps(0, 180, 90), {0}, [](double, double) { return 0.0; }), "z.ies")
                .find("every intensity is 0"),
            std::string::npos);
  EXPECT_NE(error_of(parse_ies, ies_text({0, 90, 200}, {0}, flat), "o.ies").find("outside 0 to 180"),
            std::string::npos);
  EXPECT_NE(error_of(parse_ies, ies_text({0, 90}, {0, 45}, flat), "h.ies").find("no LM-63 type C layout"),
            std::string::npos);
}

// A EULUMDAT file: Mc planes every 360/Mc degrees, gammas 0..180 every 10, intensities per 1000 lm from
// `cd_klm(gamma, c)` for the planes Isym stores; one lamp set of `lamp_lm`.
template <typename F>
std::string ldt_text(int isym, int mc, F cd_klm, double lamp_lm = 2000.0) {
  std::ostringstream o;
  const int ng = 19;
  const double dc = 360.0 / mc;
  o << "Unit test\n1\n"
    << isym << "\n"
    << mc << "\n"
    << dc << "\n"
    << ng << "\n10\nreport\nname\nnumber\nf.ldt\n"
    << "date\n600\n600\n80\n580\n580\n0\n0\n0\n0\n100\n80\n1.0\n0\n1\n2\nT5\n"
    << lamp_lm << "\n3000\n1B\n54\n";
  for (int i = 0; i < 10; ++i) o << "0.5\n";
  for (int i = 0; i < mc; ++i) o << i * dc << "\n";
  for (int i = 0; i < ng; ++i) o << i * 10 << "\n";
  int first = 0, stored = mc;
  if (isym == 1) stored = 1;
  if (isym == 2) stored = mc / 2 + 1;
  if (isym == 3) first = mc / 4, stored = mc / 2 + 1;
  if (isym == 4) stored = mc / 4 + 1;
  for (int j = first; j < first + stored; ++j)
    for (int i = 0; i < ng; ++i) o << cd_klm(i * 10.0, j * dc) << "\n";
  return o.str();
}

TEST(Photometry, EulumdatScalesPerKilolumenAndExpandsItsSymmetry) {
  auto flat = [](double g, double) { return g <= 90.0 ? 100.0 : 0.0; };
  const auto rot = parse_eulumdat(ldt_text(1, 24, flat), "r.ldt");
  EXPECT_EQ(rot.c_deg.size(), 1u);
  EXPECT_DOUBLE_EQ(rot.candela_at(30, 77), 200.0);  // 100 cd/klm x 2000 lm
  EXPECT_DOUBLE_EQ(rot.declared_lumens, 2000.0);
  auto by_c = [](double, double c) { return 100.0 + c; };
  const auto quadrant = parse_eulumdat(ldt_text(4, 24, by_c), "q.ldt");
  EXPECT_DOUBLE_EQ(quadrant.candela_at(40, 195), 2.0 * (100.0 + 15.0));
  const auto c90 = parse_eulumdat(ldt_text(3, 24, by_c), "c.ldt");
  EXPECT_DOUBLE_EQ(c90.candela_at(40, 30), 2.0 * (100.0 + 150.0));
  const auto none = parse_eulumdat(ldt_text(0, 24, by_c), "n.ldt");
  EXPECT_DOUBLE_EQ(none.candela_at(40, 345), 2.0 * 445.0);
  EXPECT_NEAR(none.candela_at(40, 352.5), 2.0 * (445.0 + 100.0) / 2.0, 1e-9);  // between C345 and C360 = C0
}

TEST(Photometry, BadEulumdatFilesNameTheLine) {
  auto flat = [](double, double) { return 100.0; };
  std::string text = ldt_text(1, 24, flat);
  const std::size_t at = text.find("\n1B\n");  // lamp colour rendering, then wattage on line 32
  std::string bad = text;
  bad.replace(bad.find("\n54\n", at), 4, "\nfifty\n");
  EXPECT_NE(error_of(parse_eulumdat, bad, "w.ldt").find("w.ldt:32: 'fifty' where a lamp set's wattage"),
            std::string::npos)
      << error_of(parse_eulumdat, bad, "w.ldt");
  EXPECT_NE(error_of(parse_eulumdat, text.substr(0, text.size() - 20), "s.ldt").find("the file ends"),
            std::string::npos);
  EXPECT_NE(error_of(parse_eulumdat, "Maker\n1\n7\n", "i.ldt").find("i.ldt:3: the symmetry indicator"),
            std::string::npos);
}

// CIE 1931 colour matching functions by Wyman, Sloan & Shirley 2013 (multi-lobe fit, JCGT 2(2)): an
// independent path to a black body's chromaticity.
double lobe(double l, double mu, double s1, double s2) {
  const double t = (l - mu) / (l < mu ? s1 : s2);
  return std::exp(-0.5 * t * t);
}
void planck_xy(double kelvin, double& x, double& y) {
  double X = 0, Y = 0, Z = 0;
  for (double l = 360.0; l <= 830.0; l += 1.0) {
    const double m = l * 1e-9;
    const double b = 1.0 / (std::pow(m, 5) * (std::exp(1.4387769e-2 / (m * kelvin)) - 1.0));
    X += b * (1.056 * lobe(l, 599.8, 37.9, 31.0) + 0.362 * lobe(l, 442.0, 16.0, 26.7) -
              0.065 * lobe(l, 501.1, 20.4, 26.2));
    Y += b * (0.821 * lobe(l, 568.8, 46.9, 40.5) + 0.286 * lobe(l, 530.9, 16.3, 31.1));
    Z += b * (1.217 * lobe(l, 437.0, 11.8, 36.0) + 0.681 * lobe(l, 459.0, 26.0, 13.8));
  }
  x = X / (X + Y + Z);
  y = Y / (X + Y + Z);
}

TEST(Photometry, ColourTemperatureFollowsThePlanckianLocus) {
  double previous_ratio = 1e9;
  for (double k : {2000.0, 2700.0, 3000.0, 4000.0, 5000.0, 6500.0, 10000.0}) {
    const model::Rgb c = cct_colour(k);
    EXPECT_NEAR(model::luminance_weight(c), 1.0, 1e-12);
    // Back to xy through the Rec. 709 matrix, against the locus integrated from Planck's law.
    const double X = 0.4124564 * c.r + 0.3575761 * c.g + 0.1804375 * c.b;
    const double Y = 0.2126729 * c.r + 0.7151522 * c.g + 0.0721750 * c.b;
    const double Z = 0.0193339 * c.r + 0.1191920 * c.g + 0.9503041 * c.b;
    double x = 0, y = 0;
    planck_xy(k, x, y);
    if (c.b > 0.0) {  // inside the Rec. 709 gamut (2000 K is not: its blue is clipped)
      EXPECT_NEAR(X / (X + Y + Z), x, 3e-3) << k << " K";
      EXPECT_NEAR(Y / (X + Y + Z), y, 3e-3) << k << " K";
    }
    EXPECT_LT(c.r / std::max(c.b, 1e-9), previous_ratio) << k << " K is not bluer than the one before";
    previous_ratio = c.r / std::max(c.b, 1e-9);
  }
  // Near the display white; the locus passes a little below D65 (less green), so red and blue lead by 6 %.
  const model::Rgb d65ish = cct_colour(6504.0);
  EXPECT_NEAR(d65ish.r / d65ish.g, 1.0, 0.08);
  EXPECT_NEAR(d65ish.b / d65ish.g, 1.0, 0.08);
}

TEST(Photometry, LumensBecomeWattsThatGiveBackTheLumens) {
  const model::Rgb warm = cct_colour(3000.0);
  const model::Rgb p = model::power_from_lumens(1000.0, warm);
  EXPECT_NEAR(model::lux_from_irradiance(p), 1000.0, 1e-9);  // the same map, power for irradiance
}

// A table brighter towards C0 (+x): I = 100 (1 + 0.8 cos C sin gamma) cos gamma below the horizon (one
// value at the nadir, as a real table has).
model::IntensityDistribution lopsided() {
  return parse_ies(ies_text(steps(0, 90, 5), steps(0, 360, 15),
                            [](double g, double c) {
                              return 100.0 * (1.0 + 0.8 * std::cos(c * kDeg) * std::sin(g * kDeg)) *
                                     std::cos(g * kDeg);
                            }),
                   "lopsided.ies");
}

model::Luminaire fixture_at(const Vec3& p, const model::IntensityDistribution& d) {
  model::Luminaire l;
  l.kind = model::LuminaireKind::Photometric;
  l.position = p;
  l.normal = {0, 0, -1};
  l.u_axis = {1, 0, 0};
  l.distribution = std::make_shared<const model::IntensityDistribution>(d);
  l.power = model::power_from_lumens(d.lumens, model::Rgb(1.0));
  return l;
}

TEST(Photometry, GatheredIlluminanceIsTheTableOverDistanceSquared) {
  const auto d = lopsided();
  const model::Luminaire l = fixture_at({0, 0, 2}, d);
  const TriangleBvh empty({});
  // Floor points 1 m towards +x (C0) and -x (C180): E = I(gamma, C) cos(gamma) / r^2, in lux.
  for (const auto& [x, c] : {std::pair{1.0, 0.0}, std::pair{-1.0, 180.0}, std::pair{0.0, 0.0}}) {
    const SurfaceSample s{{x, 0, 0}, {0, 0, 1}, {1, 1, 1}};
    const auto b = direct_light({&s, 1}, {l}, 1, empty, {1, 1}).dense(1);
    const double r2 = x * x + 4.0, cos_g = 2.0 / std::sqrt(r2);
    const double gamma = std::acos(cos_g) / kDeg;
    const double expected = d.candela_at(gamma, c) * cos_g / r2;
    // Radiosity of a white receiver is its irradiance; shadow rays start 0.1 mm up (2e-4 relative).
    EXPECT_NEAR(model::lux_from_irradiance(model::Rgb(b[0], b[1], b[2])), expected, 3e-4 * expected) << x;
  }
}

TEST(Photometry, ShotLightAgreesWithGatheredLightOnAFloor) {
  // A 4 m floor under the lopsided fixture; black walls and ceiling so only direct light lands.
  const auto d = lopsided();
  const model::Luminaire l = fixture_at({0, 0, 2}, d);
  PatchSet set;
  model::Polygon floor;
  floor.vertices = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  const PolygonMesh mesh = mesh_polygon(floor, 0.5);
  set.vertices = mesh.vertices;
  for (std::size_t i = 0; i + 2 < mesh.triangles.size(); i += 3)
    set.add(mesh.triangles[i], mesh.triangles[i + 1], mesh.triangles[i + 2], model::Rgb(0.5), 0);
  PointEmitter e;
  e.position = l.position;
  e.axis = l.normal;
  e.power = l.power;
  e.sampler = std::make_shared<const EmissionSampler>(d, PhotometricFrame(l));
  RadiosityOptions o;
  o.rays_per_watt = 20000;
  o.residual = 0.999;  // the first shot only: direct light
  const auto shot = solve_radiosity(set, {}, std::span<const PointEmitter>(&e, 1), 1, o);
  // Power landing on each half of the floor (x > 0 and x < 0): shot, against gathered on a 2 cm grid.
  double shot_half[2] = {0, 0}, gathered_half[2] = {0, 0};
  for (std::size_t i = 0; i < set.patches.size(); ++i) {
    const auto& p = set.patches[i];
    const Vec3 c = (set.vertices[p.v[0]] + set.vertices[p.v[1]] + set.vertices[p.v[2]]) / 3.0;
    shot_half[c.x > 0] += shot.radiosity.value(i, 0) * p.area;
  }
  constexpr int kSide = 200;
  constexpr double kStep = 4.0 / kSide;
  std::vector<SurfaceSample> grid;
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j)
      grid.push_back({{-2 + (i + 0.5) * kStep, -2 + (j + 0.5) * kStep, 0}, {0, 0, 1}, {0.5, 0.5, 0.5}});
  const TriangleBvh empty({});
  const auto gathered = direct_light(grid, {l}, 1, empty, {1, 2}).dense(1);
  for (std::size_t k = 0; k < grid.size(); ++k)
    gathered_half[grid[k].position.x > 0] += gathered[k * 3] * kStep * kStep;
  for (int h = 0; h < 2; ++h) EXPECT_NEAR(shot_half[h] / gathered_half[h], 1.0, 0.02) << "half " << h;
  EXPECT_GT(shot_half[1] / shot_half[0], 1.5);  // the table's bright side lands on +x
}

}  // namespace test_photometry
}  // namespace walk::compiler
