#include "compiler/import/dxf_reader.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <map>
#include <numbers>
#include <set>

#include "compiler/import/dxf_document.hpp"
#include "compiler/import/dxf_geometry.hpp"
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
// Deepest INSERT nesting followed: real drawings nest a few levels; deeper means a block inserting itself.
constexpr int kMaxInsertDepth = 16;
// Most faces and wires one file may expand to through INSERT arrays: ten times the largest building model we
// know of, so a hostile file (a 32767 x 32767 array of nested arrays) fails with a message instead of
// exhausting memory.
constexpr std::size_t kMaxPrimitives = 20'000'000;

struct Context {
  glm::dmat4 world{1.0};
  bool mirrored = false;
  std::string layer = "0";  // layer of the innermost INSERT: entities on layer "0" in a block take it
  int color = 7;            // colour of the innermost INSERT: entities coloured BYBLOCK take it
  std::optional<int> true_color;
  int depth = 0;
};

class Builder {
 public:
  Builder(const DxfDocument& doc, const std::string& file, double scale, DxfStats& stats,
          std::vector<DxfWire>* wires, model::Model& model)
      : doc_(doc), file_(file), scale_(scale), stats_(stats), wires_(wires), model_(model) {}

  void entities(const std::vector<DxfEntity>& list, const Context& ctx) {
    for (const DxfEntity& e : list) entity(e, ctx);
  }

  // Counts what the drawing expands to through its INSERT arrays before expanding anything (each block's
  // count once), so a hostile file is refused in milliseconds, not after gigabytes of faces.
  void check_expansion(const std::vector<DxfEntity>& list) {
    std::map<std::string, double> counted;
    double total = 0.0;
    for (const DxfEntity& e : list) {
      total += expansion(e, counted, 0);
      if (total > double(kMaxPrimitives)) {
        char estimate[32];
        std::snprintf(estimate, sizeof estimate, "%.3g", total);
        throw Error(located(file_, e.line,
                            std::string("the drawing would expand to ") + estimate +
                                " faces and lines through its INSERT arrays (this INSERT and those before "
                                "it), more than " +
                                std::to_string(kMaxPrimitives),
                            "check the block's column/row counts (group codes 70/71) and nesting"));
      }
    }
  }

 private:
  // Primitives one entity expands to: 1, or an INSERT's columns x rows x its block's count. Saturates at
  // infinity; a nesting deeper than kMaxInsertDepth is left to the build, which names it.
  double expansion(const DxfEntity& e, std::map<std::string, double>& counted, int depth) {
    if (e.type != "INSERT") return 1.0;
    if (depth >= kMaxInsertDepth) return 1.0;
    const Fields f{e, file_};
    const double copies = double(std::max(1, f.integer(70, 1))) * double(std::max(1, f.integer(71, 1)));
    const std::string name = e.text(2, "");
    const auto block = doc_.blocks.find(name);
    if (block == doc_.blocks.end()) return copies;  // the build names the missing block
    auto it = counted.find(name);
    if (it == counted.end()) {
      // A block met again while it is being counted inserts itself: counted as one here, named by the build.
      if (!counting_.insert(name).second) return copies;
      double inside = 0.0;
      for (const DxfEntity& child : block->second.entities) inside += expansion(child, counted, depth + 1);
      counting_.erase(name);
      it = counted.emplace(name, inside).first;
    }
    return copies * it->second;
  }

  void entity(const DxfEntity& e, const Context& ctx) {
    const Fields f{e, file_};
    if (f.integer(67, 0) == 1) {  // paper space: layouts and title blocks, not the building
      ++stats_.frozen;
      return;
    }
    std::string layer = e.text(8, "0");
    if (layer == "0") layer = ctx.layer;
    const auto layer_it = doc_.layers.find(layer);
    if (layer_it != doc_.layers.end() && layer_it->second.frozen) {
      ++stats_.frozen;
      return;
    }
    int color = f.integer(62, 256);
    std::optional<int> true_color;
    if (e.find(420)) true_color = f.integer(420, 0) & 0xffffff;
    if (color == 0) {  // BYBLOCK
      color = ctx.color;
      if (!true_color) true_color = ctx.true_color;
    } else if (color == 256) {  // BYLAYER
      color = layer_it != doc_.layers.end() ? layer_it->second.color : 7;
      if (!true_color && layer_it != doc_.layers.end()) true_color = layer_it->second.true_color;
    }
    if (e.type == "INSERT") return insert(e, f, ctx, layer, color, true_color);

    DxfShape shape;
    dxf_entity_shape(e, file_, shape);
    if (!shape.known) {
      ++stats_.skipped[e.type];
      return;
    }
    ++stats_.read[e.type];
    stats_.degenerate += shape.degenerate;
    budget(shape.faces.size() + shape.wires.size(), e.line);
    const std::uint32_t group = model_.group_index(layer);
    const std::uint32_t material = true_color ? material_of(*true_color) : 0;
    for (auto& corners : shape.faces) face(corners, ctx, e, group, color, material, true_color.has_value());
    for (const auto& w : shape.wires) {
      ++stats_.wires;
      if (wires_)
        wires_->push_back({place(ctx, w[0]), place(ctx, w[1]), group, static_cast<std::uint32_t>(e.line)});
    }
  }

  struct Fields {
    const DxfEntity& e;
    const std::string& file;
    [[nodiscard]] double num(int code, double fallback) const {
      const DxfPair* p = e.find(code);
      return p ? dxf_number(*p, file) : fallback;
    }
    [[nodiscard]] int integer(int code, int fallback) const {
      const DxfPair* p = e.find(code);
      return p ? dxf_integer(*p, file) : fallback;
    }
  };

  void budget(std::size_t more, std::size_t line) {
    primitives_ += more;
    if (primitives_ > kMaxPrimitives)
      throw Error(located(file_, line,
                          "the drawing expands to more than " + std::to_string(kMaxPrimitives) +
                              " faces and lines through its INSERT arrays",
                          "check the block's column/row counts (group codes 70/71) and nesting"));
  }

  [[nodiscard]] Vec3 place(const Context& ctx, const Vec3& p) const {
    return Vec3(ctx.world * glm::dvec4(p, 1.0)) * scale_;
  }

  std::uint32_t material_of(int rgb) {
    char name[16];
    std::snprintf(name, sizeof name, "rgb:%06X", rgb);
    for (std::size_t i = 0; i < model_.materials.size(); ++i)
      if (model_.materials[i].name == name) return static_cast<std::uint32_t>(i);
    if (model_.materials.empty()) model_.materials.push_back({"default", {0.5, 0.5, 0.5}});
    model_.materials.push_back(
        {name, {((rgb >> 16) & 255) / 255.0, ((rgb >> 8) & 255) / 255.0, (rgb & 255) / 255.0}});
    return static_cast<std::uint32_t>(model_.materials.size() - 1);
  }

  void face(const std::vector<Vec3>& corners, const Context& ctx, const DxfEntity& e, std::uint32_t group,
            int color, std::uint32_t material, bool true_color) {
    std::vector<Vec3> vertices;
    for (const Vec3& c : corners) {
      const Vec3 p = place(ctx, c);
      if (!vertices.empty() && glm::distance(vertices.back(), p) <= kSameCornerTolerance) continue;
      vertices.push_back(p);
    }
    while (vertices.size() > 1 && glm::distance(vertices.back(), vertices.front()) <= kSameCornerTolerance)
      vertices.pop_back();
    Vec3 twice_area{0.0};
    for (std::size_t i = 1; i + 1 < vertices.size(); ++i)
      twice_area += glm::cross(vertices[i] - vertices[0], vertices[i + 1] - vertices[0]);
    if (vertices.size() < 3 || !(0.5 * glm::length(twice_area) >= kMinFaceArea)) {
      ++stats_.degenerate;
      return;
    }
    // A mirroring transform turns counter-clockwise into clockwise: reverse to keep the face's side.
    if (ctx.mirrored) std::reverse(vertices.begin(), vertices.end());
    model::Polygon polygon;
    if (vertices.size() == 3) ++stats_.triangles;
    polygon.vertices = std::move(vertices);
    polygon.group = group;
    polygon.color = color;
    polygon.material = material;
    polygon.name = e.comment;
    polygon.source_line = static_cast<std::uint32_t>(e.line);
    model_.polygons.push_back(std::move(polygon));
    ++stats_.faces;
    if (true_color) ++stats_.true_colours;
  }

  void insert(const DxfEntity& e, const Fields& f, const Context& ctx, const std::string& layer, int color,
              std::optional<int> true_color) {
    const std::string name = e.text(2, "");
    const auto it = doc_.blocks.find(name);
    if (it == doc_.blocks.end())
      throw Error(located(file_, e.line,
                          "INSERT places block \"" + name + "\" that the BLOCKS section does not define",
                          "re-export the drawing with its blocks, or explode the INSERT"));
    if (ctx.depth >= kMaxInsertDepth)
      throw Error(located(file_, e.line,
                          "INSERT of \"" + name + "\" is nested more than " +
                              std::to_string(kMaxInsertDepth) +
                              " levels deep: a block that (indirectly) inserts itself",
                          "fix the block definitions in the drawing"));
    const DxfBlock& block = it->second;
    const DxfEntity base_holder{"BLOCK", block.line, {}, block.header, {}};
    const Fields bf{base_holder, file_};
    const Vec3 base(bf.num(10, 0.0), bf.num(20, 0.0), bf.num(30, 0.0));
    const Vec3 at(f.num(10, 0.0), f.num(20, 0.0), f.num(30, 0.0));
    const Vec3 scale(f.num(41, 1.0), f.num(42, 1.0), f.num(43, 1.0));
    const double rotation = f.num(50, 0.0) * std::numbers::pi / 180.0;
    const int columns = std::max(1, f.integer(70, 1)), rows = std::max(1, f.integer(71, 1));
    const double column_spacing = f.num(44, 0.0), row_spacing = f.num(45, 0.0);
    Vec3 normal(f.num(210, 0.0), f.num(220, 0.0), f.num(230, 1.0));
    if (!(glm::length(normal) > 0.0))
      throw Error(
          located(file_, e.line, "INSERT has a zero extrusion direction", "fix group codes 210/220/230"));
    const glm::dmat3 ocs = dxf_ocs(normal);
    const glm::dmat4 ocs4(glm::dvec4(ocs[0], 0.0), glm::dvec4(ocs[1], 0.0), glm::dvec4(ocs[2], 0.0),
                          glm::dvec4(0.0, 0.0, 0.0, 1.0));
    const double det = scale.x * scale.y * scale.z;
    budget(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows), e.line);
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < columns; ++c) {
        glm::dmat4 local = glm::translate(glm::dmat4(1.0), at);
        local = glm::rotate(local, rotation, Vec3(0.0, 0.0, 1.0));
        local = glm::translate(local, Vec3(c * column_spacing, r * row_spacing, 0.0));
        local = glm::scale(local, scale);
        local = glm::translate(local, -base);
        Context inner;
        inner.world = ctx.world * ocs4 * local;
        inner.mirrored = ctx.mirrored != (det < 0.0);
        inner.layer = layer;
        inner.color = color;
        inner.true_color = true_color;
        inner.depth = ctx.depth + 1;
        ++stats_.block_instances;
        if (det < 0.0) ++stats_.mirrored_instances;
        entities(block.entities, inner);
      }
    }
  }

  const DxfDocument& doc_;
  const std::string& file_;
  double scale_;
  DxfStats& stats_;
  std::vector<DxfWire>* wires_;
  model::Model& model_;
  std::size_t primitives_ = 0;
  std::set<std::string> counting_;  // blocks whose expansion is being counted
};

}  // namespace

std::optional<double> insunits_metres(int code) {
  switch (code) {
    case 1:
      return 0.0254;
    case 2:
      return 0.3048;
    case 3:
      return 1609.344;
    case 4:
      return 0.001;
    case 5:
      return 0.01;
    case 6:
      return 1.0;
    case 7:
      return 1000.0;
    case 8:
      return 2.54e-8;
    case 9:
      return 2.54e-5;
    case 10:
      return 0.9144;
    case 11:
      return 1e-10;
    case 12:
      return 1e-9;
    case 13:
      return 1e-6;
    case 14:
      return 0.1;
    case 15:
      return 10.0;
    case 16:
      return 100.0;
    default:
      return std::nullopt;
  }
}

model::Model read_dxf(const std::string& path, const DxfOptions& options) {
  return read_dxf(path, options, nullptr);
}

model::Model read_dxf(const std::string& path, const DxfOptions& options, DxfStats* stats) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw Error(located(path, 0, "cannot open the DXF file",
                        "check the path in the scene config and that the file exists and is readable"));
  }
  return read_dxf(in, path, options, stats, nullptr);
}

model::Model read_dxf(std::istream& in, const std::string& file, const DxfOptions& options,
                      DxfStats* stats_out, std::vector<DxfWire>* wires) {
  if (!(options.unit_scale > 0.0) || !std::isfinite(options.unit_scale)) {
    throw Error(
        located(file, 0, "unit scale " + std::to_string(options.unit_scale) + " is not a positive number",
                "set the scene's unit scale to the metres per drawing unit, e.g. 0.001 for millimetres"));
  }
  const DxfDocument doc = read_dxf_document(in, file);
  DxfStats stats;
  stats.lines = doc.lines;
  stats.insunits = doc.insunits;
  double scale = options.unit_scale;
  if (options.use_insunits && doc.insunits && *doc.insunits != 0) {
    const auto metres = insunits_metres(*doc.insunits);
    if (!metres)
      throw Error(located(file, doc.insunits_line,
                          "$INSUNITS " + std::to_string(*doc.insunits) + " is not a unit we know",
                          "set `units` in the scene's [model] table to say what the drawing unit is"));
    scale = *metres;
  }
  stats.unit_scale = scale;
  model::Model model;
  Builder builder(doc, file, scale, stats, wires, model);
  builder.check_expansion(doc.entities);
  builder.entities(doc.entities, Context{});
  if (model.polygons.empty() && !wires) {
    throw Error(
        located(file, 0,
                "the DXF file has no usable 3DFACE or other surface entities (" +
                    std::to_string(stats.degenerate) + " degenerate ones skipped)",
                "export the model's surfaces as 3DFACE or meshes (e.g. EnergyPlus Output:Surfaces:Drawing, "
                "DXF), give lines a thickness, or import a 2D plan with format = \"plan\""));
  }
  if (model.materials.empty()) model.materials.push_back(model::Material{"default", {0.5, 0.5, 0.5}});
  if (stats_out) *stats_out = std::move(stats);
  return model;
}

}  // namespace walk::compiler
