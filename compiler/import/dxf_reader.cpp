#include "compiler/import/dxf_reader.hpp"

#include <array>
#include <cmath>
#include <fstream>
#include <glm/geometric.hpp>
#include <optional>

#include "compiler/import/dxf_tokenizer.hpp"
#include "model/error.hpp"

namespace walk::compiler {
namespace {

using model::Vec3;

// Corners closer than this (metres, after unit scaling) are the same corner. EnergyPlus prints 5 decimals
// (10 micrometres), so this only merges corners written identically, i.e. a triangle's repeated 4th corner.
constexpr double kSameCornerTolerance = 1e-6;
// A face with less area than this (square metres) is a degenerate sliver (e.g. collinear corners).
constexpr double kMinFaceArea = 1e-12;

// One 3DFACE being read: which of the 12 coordinate codes were seen.
struct FaceEntity {
  std::size_t line = 0;  // line of its `0` code
  std::string layer = "0";
  int color = 0;
  std::string name;
  std::array<Vec3, 4> corners{};
  std::array<std::array<bool, 3>, 4> seen{};
};

std::string face_where(const FaceEntity& face) {
  return face.name.empty() ? std::string("3DFACE") : "3DFACE \"" + face.name + "\"";
}

// Appends the face as a polygon, or returns false when it is degenerate.
bool add_face(const FaceEntity& face, const std::string& file, model::Model& model, DxfStats& stats) {
  const char* axes = "xyz";
  bool has_fourth = true;
  for (int c = 0; c < 4; ++c) {
    int count = 0;
    for (int a = 0; a < 3; ++a) count += face.seen[c][a] ? 1 : 0;
    if (count == 3) continue;
    if (c == 3 && count == 0) {  // a 3-corner 3DFACE: tolerated, read as a triangle
      has_fourth = false;
      continue;
    }
    std::string missing;
    for (int a = 0; a < 3; ++a) {
      if (!face.seen[c][a])
        missing += std::string(missing.empty() ? "" : ", ") + axes[a] + " (group code " +
                   std::to_string(10 * (a + 1) + c) + ")";
    }
    throw Error(located(
        file, face.line, face_where(face) + " is missing corner " + std::to_string(c + 1) + " " + missing,
        "every 3DFACE needs corners 10/20/30 to 13/23/33; re-export the drawing or delete this "
        "entity"));
  }
  std::vector<Vec3> vertices;
  const int corners = has_fourth ? 4 : 3;
  for (int c = 0; c < corners; ++c) {
    const Vec3& p = face.corners[c];
    if (!vertices.empty() && glm::distance(vertices.back(), p) <= kSameCornerTolerance) continue;
    vertices.push_back(p);
  }
  while (vertices.size() > 1 && glm::distance(vertices.back(), vertices.front()) <= kSameCornerTolerance) {
    vertices.pop_back();
  }
  if (vertices.size() < 3) return false;
  Vec3 twice_area{0.0};
  for (std::size_t i = 1; i + 1 < vertices.size(); ++i) {
    twice_area += glm::cross(vertices[i] - vertices[0], vertices[i + 1] - vertices[0]);
  }
  if (0.5 * glm::length(twice_area) < kMinFaceArea) return false;

  model::Polygon polygon;
  if (vertices.size() == 3) ++stats.triangles;
  polygon.vertices = std::move(vertices);
  polygon.group = model.group_index(face.layer);
  polygon.color = face.color;
  polygon.name = face.name;
  polygon.source_line = static_cast<std::uint32_t>(face.line);
  model.polygons.push_back(std::move(polygon));
  ++stats.faces;
  return true;
}

}  // namespace

model::Model read_dxf(const std::string& path, const DxfOptions& options) {
  return read_dxf(path, options, nullptr);
}

model::Model read_dxf(const std::string& path, const DxfOptions& options, DxfStats* stats_out) {
  if (!(options.unit_scale > 0.0) || !std::isfinite(options.unit_scale)) {
    throw Error(
        located(path, 0, "unit scale " + std::to_string(options.unit_scale) + " is not a positive number",
                "set the scene's unit scale to the metres per drawing unit, e.g. 0.001 for millimetres"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error(located(path, 0, "cannot open the DXF file",
                        "check the path in the scene config and that "
                        "the file exists and is readable"));
  }
  DxfTokenizer tokens(in, path);
  model::Model model;
  DxfStats stats;

  std::string section;  // name of the current SECTION, empty outside one
  bool expect_section_name = false;
  bool saw_eof = false;
  std::string comment;             // last 999 comment: EnergyPlus names each surface in one before its entity
  std::optional<FaceEntity> face;  // the 3DFACE being read, if any
  std::size_t entity_line = 0;     // line of the `0` code of the entity being read (any type)
  std::string entity_type;

  const auto finish_entity = [&] {
    if (face) {
      if (!add_face(*face, path, model, stats)) ++stats.degenerate;
      face.reset();
    }
    entity_type.clear();
  };

  DxfPair pair;
  while (tokens.next(pair)) {
    if (pair.code == 999) {
      comment = pair.value;
      continue;
    }
    if (pair.code == 0) {
      finish_entity();
      entity_line = pair.code_line;
      if (pair.value == "EOF") {
        saw_eof = true;
        break;
      }
      if (pair.value == "SECTION") {
        expect_section_name = true;
        continue;
      }
      if (pair.value == "ENDSEC") {
        section.clear();
        continue;
      }
      entity_type = pair.value;
      // Tables and block definitions are not drawn directly; entities outside any section are (hand-made
      // files).
      if (!section.empty() && section != "ENTITIES") continue;
      if (pair.value == "3DFACE") {
        face.emplace();
        face->line = pair.code_line;
        // Faces after the first of a TRIANGULATE3DFACE'd surface have no comment of their own and keep this
        // one.
        face->name = comment;
      } else {
        ++stats.skipped[pair.value];
      }
      continue;
    }
    if (expect_section_name && pair.code == 2) {
      section = pair.value;
      expect_section_name = false;
      continue;
    }
    if (!face) continue;
    if (pair.code == 8) {
      face->layer = pair.value;
    } else if (pair.code == 62) {
      face->color = tokens.integer(pair);
    } else if (pair.code >= 10 && pair.code <= 33 && pair.code % 10 <= 3) {
      const int axis = pair.code / 10 - 1;
      const int corner = pair.code % 10;
      face->corners[corner][axis] = tokens.number(pair) * options.unit_scale;
      face->seen[corner][axis] = true;
    }
  }
  stats.lines = tokens.lines_read();
  if (stats.lines == 0) {
    throw Error(located(path, 0, "the DXF file is empty", "copy or export the file again"));
  }
  if (!saw_eof) {
    const std::string inside =
        entity_type.empty() ? std::string()
                            : " inside the " + entity_type + " entity at line " + std::to_string(entity_line);
    throw Error(located(path, stats.lines,
                        "the DXF file ends without its \"0 EOF\" marker" + inside + ": it is truncated",
                        "copy or export the file again"));
  }
  if (model.polygons.empty()) {
    throw Error(
        located(path, 0,
                "the DXF file has no usable 3DFACE entities (" + std::to_string(stats.degenerate) +
                    " degenerate ones skipped)",
                "export the model's surfaces as 3DFACE, e.g. EnergyPlus Output:Surfaces:Drawing, DXF"));
  }
  if (model.materials.empty()) model.materials.push_back(model::Material{"default", {0.5, 0.5, 0.5}});
  if (stats_out) *stats_out = std::move(stats);
  return model;
}

}  // namespace walk::compiler
