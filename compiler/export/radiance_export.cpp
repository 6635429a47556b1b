#include "compiler/export/radiance_export.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <numbers>
#include <sstream>

#include "model/error.hpp"
#include "model/luminaire_shapes.hpp"

namespace walk::compiler {
namespace {

namespace fs = std::filesystem;

// Point lights become spheres this big (metres): small against any room, large enough for Radiance to find
// them with its source sampling.
constexpr double kPointLightRadius = 0.02;
// Clear float glass: Radiance's `glass` takes transmissivity (0.96 gives 88 % transmittance at normal
// incidence, the usual single pane).
constexpr double kGlassTransmissivity = 0.96;

void real_arguments(std::ostream& out, std::initializer_list<double> values) {
  out << "0\n0\n" << values.size();
  for (const double v : values) out << ' ' << v;
  out << '\n';
}

void sphere(std::ostream& out, const std::string& modifier, const std::string& name, const model::Vec3& at) {
  out << modifier << " sphere " << name << '\n';
  real_arguments(out, {at.x, at.y, at.z, kPointLightRadius});
}

}  // namespace

RadianceExportStats export_radiance(const model::Bundle& b, const std::string& folder) {
  RadianceExportStats stats;
  std::ostringstream out;
  out.precision(9);
  const auto& meta = b.meta();
  const model::Vec3 origin(meta.origin[0], meta.origin[1], meta.origin[2]);
  out << "# Walkthrough bundle " << b.path() << " as a Radiance scene, world metres, radiant W per channel.\n"
      << "# Illuminance at a point facing n:  oconv scene.rad > scene.oct\n"
      << "#   echo 'x y z nx ny nz' | rtrace -I -h -ab 6 -ad 4096 -aa 0.05 scene.oct |\n"
      << "#   rcalc -e '$1=179*(.2126*$1+.7152*$2+.0722*$3)'   (lux, as walk probe prints)\n\n";

  // Materials: one per bundle material and role, with the reflectance the solver used.
  const auto polygons = b.polygons();
  const auto vertices = b.vertices();
  std::vector<std::int8_t> written(b.materials().size() * 2, 0);
  auto material_name = [&](const model::PolygonRecord& p) {
    const bool glass = static_cast<model::Role>(p.role) == model::Role::Glass;
    const std::string name = (glass ? "glass_" : "mat_") + std::to_string(p.material);
    auto& done = written[p.material * 2 + (glass ? 1 : 0)];
    if (!done) {
      done = 1;
      ++stats.materials;
      const auto& m = b.materials()[p.material];
      out << "# " << b.string(m.name) << '\n';
      if (glass) {
        out << "void glass " << name << '\n';
        real_arguments(out, {kGlassTransmissivity, kGlassTransmissivity, kGlassTransmissivity});
      } else {
        out << "void plastic " << name << '\n';
        real_arguments(out, {m.reflectance[0], m.reflectance[1], m.reflectance[2], 0.0, 0.0});
      }
    }
    return name;
  };
  const auto idx = b.indices();
  for (std::size_t pi = 0; pi < polygons.size(); ++pi) {
    const auto& p = polygons[pi];
    const auto role = static_cast<model::Role>(p.role);
    if (role != model::Role::Opaque && role != model::Role::Glass) continue;  // panels follow as lights
    const std::string material = material_name(p);
    for (std::uint32_t k = p.first_index; k + 2 < p.first_index + p.index_count; k += 3) {
      out << material << " polygon t" << stats.polygons++ << "\n0\n0\n9";
      for (int c = 0; c < 3; ++c) {
        const auto& v = vertices[idx[k + c]];
        for (int a = 0; a < 3; ++a) out << ' ' << double(v.position[a]) + meta.origin[a];
      }
      out << '\n';
    }
  }

  // Luminaires at the solver's power: a panel's radiance is its exitance / pi, a sphere's power / (4 pi^2
  // r^2).
  const auto luminaires = model::load_luminaires(b);
  for (std::size_t i = 0; i < luminaires.size(); ++i) {
    const auto& l = luminaires[i];
    const std::string name = "lamp_" + std::to_string(i);
    out << "# " << l.name << " (circuit " << b.string(b.circuits()[l.circuit].name) << ")\n";
    if (l.kind == model::LuminaireKind::Area) {
      const double area = l.width * l.height;
      out << "void light " << name << '\n';
      real_arguments(out, {l.power.r / (std::numbers::pi * area), l.power.g / (std::numbers::pi * area),
                           l.power.b / (std::numbers::pi * area)});
      // Corners counter-clockwise about the normal: Radiance lights emit on the side the normal faces.
      const model::Vec3 n = glm::normalize(l.normal), u = glm::normalize(l.u_axis);
      const model::Vec3 v = glm::cross(n, u);
      const model::Vec3 c = l.position + origin;
      out << name << " polygon panel_" << i << "\n0\n0\n12";
      for (const auto& [su, sv] : {std::pair{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}) {
        const model::Vec3 q = c + u * (su * l.width) + v * (sv * l.height);
        out << ' ' << q.x << ' ' << q.y << ' ' << q.z;
      }
      out << '\n';
      ++stats.panels;
      continue;
    }
    const double shell = 4.0 * std::numbers::pi * std::numbers::pi * kPointLightRadius * kPointLightRadius;
    if (l.kind == model::LuminaireKind::Spot && l.cone < std::numbers::pi) {
      // Radiance's spotlight is a sharp cone (no cos^n falloff): the power spread over the cone it lights.
      const double cone_share = (1.0 - std::cos(l.cone)) / 2.0;
      const model::Vec3 axis = glm::normalize(l.normal);
      out << "void spotlight " << name << "\n0\n0\n7 " << l.power.r / (shell * cone_share) << ' '
          << l.power.g / (shell * cone_share) << ' ' << l.power.b / (shell * cone_share) << ' '
          << 2.0 * l.cone * 180.0 / std::numbers::pi << ' ' << axis.x << ' ' << axis.y << ' ' << axis.z
          << '\n';
    } else {
      if (l.kind == model::LuminaireKind::Photometric) {
        ++stats.fixtures_approximated;
        out << "# measured fixture written as an isotropic source of its flux; convert its table with "
               "ies2rad\n";
      }
      out << "void light " << name << '\n';
      real_arguments(out, {l.power.r / shell, l.power.g / shell, l.power.b / shell});
    }
    sphere(out, name, "source_" + std::to_string(i), l.position + origin);
    ++stats.spheres;
  }

  // Whole or not at all: written beside, then renamed over.
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw Error("walk export radiance: cannot make folder " + folder + ": " + ec.message());
  const fs::path path = fs::path(folder) / "scene.rad", part = fs::path(folder) / "scene.rad.part";
  {
    std::ofstream file(part, std::ios::binary);
    file << out.str();
    if (!file.flush())
      throw Error("walk export radiance: cannot write " + part.string() + " (disk full or read-only?)");
  }
  fs::rename(part, path, ec);
  if (ec) {
    fs::remove(part, ec);
    throw Error("walk export radiance: cannot write " + path.string() + ": " + ec.message());
  }
  return stats;
}

}  // namespace walk::compiler
