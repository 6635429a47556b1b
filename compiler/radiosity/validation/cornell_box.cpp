#include "compiler/radiosity/validation/cornell_box.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <sstream>

#include "compiler/geometry/mesher.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

// The data's light quad lies in the ceiling plane; it is lowered by this much (metres) so the two surfaces do
// not coincide, as renderers of this scene usually do (0.1 mm, far below the patch size).
constexpr double kLightDrop = 1e-4;
// A quad whose corners leave their best-fit plane by more than this (metres) is split into triangles.
constexpr double kPlanarTolerance = 1e-5;
constexpr double kMillimetre = 1e-3;

// Band means of a sampled spectrum (wavelength -> value), with linear interpolation.
model::Rgb band_means(const std::vector<std::pair<double, double>>& s) {
  auto value = [&](double nm) {
    if (nm <= s.front().first) return s.front().second;
    for (std::size_t i = 1; i < s.size(); ++i)
      if (nm <= s[i].first) {
        const double t = (nm - s[i - 1].first) / (s[i].first - s[i - 1].first);
        return s[i - 1].second + t * (s[i].second - s[i - 1].second);
      }
    return s.back().second;
  };
  auto mean = [&](double lo, double hi) {
    double sum = 0.0;
    const int steps = 100;
    for (int i = 0; i < steps; ++i) sum += value(lo + (hi - lo) * (i + 0.5) / steps);
    return sum / steps;
  };
  return {mean(600, 700), mean(500, 600), mean(400, 500)};
}

}  // namespace

CornellBox load_cornell_box(const std::string& geometry_path, const std::string& spectra_path) {
  CornellBox box;
  std::ifstream in(geometry_path);
  if (!in) throw Error(located(geometry_path, 0, "cannot open the Cornell box geometry"));
  std::string line;
  std::size_t n = 0;
  CornellSurface* current = nullptr;
  while (std::getline(in, line)) {
    ++n;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream ls(line);
    std::string word;
    if (!(ls >> word)) continue;
    if (word == "surface") {
      box.surfaces.push_back({});
      current = &box.surfaces.back();
      if (!(ls >> current->name >> current->material))
        throw Error(located(geometry_path, n, "surface needs a name and a material"));
    } else if (word == "light") {
      std::string key;
      ls >> key;
      if (key == "emission_spectrum_nm") {
        std::vector<std::pair<double, double>> spectrum;
        double nm, v;
        while (ls >> nm >> v) spectrum.emplace_back(nm, v);
        if (spectrum.size() < 2)
          throw Error(located(geometry_path, n, "emission spectrum needs two samples"));
        box.emission = band_means(spectrum);
      } else if (key == "reflectance") {
        double r;
        if (!(ls >> r)) throw Error(located(geometry_path, n, "light reflectance is not a number"));
        box.light_reflectance = model::Rgb(r);
      }
    } else if (word == "camera") {
      continue;
    } else {
      if (!current) throw Error(located(geometry_path, n, "vertex before any surface"));
      double x, y, z;
      std::istringstream vs(line);
      if (!(vs >> x >> y >> z))
        throw Error(located(geometry_path, n, "expected a vertex 'x y z' in millimetres"));
      // The data is y-up; the walkthrough is z-up: (x, y, z) -> (x, z, y) mirrors, so reverse the winding
      // after.
      current->vertices.emplace_back(x * kMillimetre, z * kMillimetre, y * kMillimetre);
    }
  }
  for (auto& s : box.surfaces) {
    if (s.vertices.size() < 3)
      throw Error(located(geometry_path, 0, "surface " + s.name + " has under 3 vertices"));
    std::reverse(s.vertices.begin(), s.vertices.end());
    if (s.material == "emitter")
      for (auto& v : s.vertices) v.z -= kLightDrop;
  }
  std::ifstream sp(spectra_path);
  if (!sp) throw Error(located(spectra_path, 0, "cannot open the reflectance spectra"));
  std::vector<std::pair<double, double>> white, green, red;
  n = 0;
  while (std::getline(sp, line)) {
    ++n;
    if (line.empty() || line[0] == '#' || line.rfind("wavelength", 0) == 0) continue;
    double nm, w, g, r;
    char c1, c2, c3;
    std::istringstream ls(line);
    if (!(ls >> nm >> c1 >> w >> c2 >> g >> c3 >> r))
      throw Error(located(spectra_path, n, "expected 'nm,white,green,red'"));
    white.emplace_back(nm, w);
    green.emplace_back(nm, g);
    red.emplace_back(nm, r);
  }
  if (white.size() < 2) throw Error(located(spectra_path, 0, "no spectral samples"));
  box.white = band_means(white);
  box.green = band_means(green);
  box.red = band_means(red);
  return box;
}

PatchSet cornell_patches(const CornellBox& box, double grid, std::vector<AreaEmitter>& emitters) {
  PatchSet set;
  for (std::uint32_t si = 0; si < box.surfaces.size(); ++si) {
    const auto& s = box.surfaces[si];
    const model::Rgb rho = s.material == "white"   ? box.white
                           : s.material == "green" ? box.green
                           : s.material == "red"   ? box.red
                                                   : box.light_reflectance;
    // Split a non-planar quad into two planar triangles.
    std::vector<std::vector<model::Vec3>> pieces{s.vertices};
    if (s.vertices.size() == 4) {
      const model::Vec3 n = polygon_normal(s.vertices);
      const model::Vec3 centre = (s.vertices[0] + s.vertices[1] + s.vertices[2] + s.vertices[3]) / 4.0;
      double off = 0.0;
      for (const auto& v : s.vertices) off = std::max(off, std::abs(glm::dot(v - centre, n)));
      if (off > kPlanarTolerance)
        pieces = {{s.vertices[0], s.vertices[1], s.vertices[2]},
                  {s.vertices[0], s.vertices[2], s.vertices[3]}};
    }
    for (const auto& piece : pieces) {
      model::Polygon poly;
      poly.vertices = piece;
      const PolygonMesh mesh = mesh_polygon(poly, grid);
      const auto base = static_cast<std::uint32_t>(set.vertices.size());
      set.vertices.insert(set.vertices.end(), mesh.vertices.begin(), mesh.vertices.end());
      for (std::size_t i = 0; i + 2 < mesh.triangles.size(); i += 3) {
        if (!set.add(base + mesh.triangles[i], base + mesh.triangles[i + 1], base + mesh.triangles[i + 2],
                     rho, si))
          continue;
        if (s.material == "emitter")
          emitters.push_back({static_cast<std::uint32_t>(set.patches.size() - 1), 0, box.emission});
      }
    }
  }
  return set;
}

}  // namespace walk::compiler
