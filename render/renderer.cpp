// The renderer: static buffers uploaded once, a draw list per cell built on first use, dimmer levels as
// uniforms. Everything is drawn into an FBO owned here; a window only ever receives a blit of it.
#include "render/renderer.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <tuple>
#include <utility>

#include "model/error.hpp"
#include "model/model.hpp"
#include "render/accumulator.hpp"
#include "render/albedo_maps.hpp"
#include "render/camera.hpp"
#include "render/cluster_layout.hpp"
#include "render/culling_policy.hpp"
#include "render/diagonals.hpp"
#include "render/display_light.hpp"
#include "render/draw_list.hpp"
#include "render/framebuffer.hpp"
#include "render/frustum.hpp"
#include "render/gl_check.hpp"
#include "render/jitter.hpp"
#include "render/light_mixer.hpp"
#include "render/occluders.hpp"
#include "render/portal_view.hpp"
#include "render/shader.hpp"
#include "render/subdivision.hpp"
#include "render/tonemap.hpp"
#include "render/unit_refinement.hpp"
#include "render/upscale.hpp"

namespace walk::render {

namespace {

// Texture units of the compact light form, the polygons' first entries and the dimmer levels (0: full
// light, 1: polygon light, 2 and 3: albedo maps).
constexpr int kCompactColourUnit = 4;
constexpr int kCompactCodeUnit = 5;
constexpr int kPolygonFirstUnit = 6;
constexpr int kLevelsUnit = 7;

// A texture buffer of `format` over a new buffer object holding `bytes` of `data` (at least 4 bytes, so an
// empty one is still a valid texture).
void upload_texture_buffer(GLuint& buffer, GLuint& texture, GLenum format, const void* data,
                           std::size_t bytes, GLenum usage = GL_STATIC_DRAW) {
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_TEXTURE_BUFFER, buffer);
  glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(std::max<std::size_t>(bytes, 4)), bytes ? data : nullptr, usage);
  glGenTextures(1, &texture);
  glBindTexture(GL_TEXTURE_BUFFER, texture);
  glTexBuffer(GL_TEXTURE_BUFFER, format, buffer);
}

// The scene shaders' sources, with the albedo-map code only when the bundle has maps.
std::string scene_source(const model::Bundle& bundle, const std::string& source, bool vertex_stage) {
  return bundle.textures().empty() ? source : with_albedo_maps(source, vertex_stage);
}

// Points the bound VAO's attributes at `vbo`'s VERT records (position, albedo, polygon) and, unless 0,
// at `light_ranges` (a_light_first, in VERT's numbering).
void point_scene_attributes(GLuint vbo, GLuint light_ranges) {
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(model::VertexRecord),
                        reinterpret_cast<const void*>(offsetof(model::VertexRecord, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(model::VertexRecord),
                        reinterpret_cast<const void*>(offsetof(model::VertexRecord, albedo)));
  // The polygon id selects the coarse (per-polygon) light.
  glEnableVertexAttribArray(2);
  glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, sizeof(model::VertexRecord),
                         reinterpret_cast<const void*>(offsetof(model::VertexRecord, polygon)));
  if (light_ranges != 0) {
    glBindBuffer(GL_ARRAY_BUFFER, light_ranges);
    glEnableVertexAttribArray(3);
    glVertexAttribIPointer(3, 2, GL_UNSIGNED_INT, sizeof(VertexLightRange), nullptr);
  }
}

}  // namespace

// The coarse form's index buffer, its own vertices (copies of VERT records in its numbering, see
// LaidOutForm::vertices) and the VAO over both. Its light is per polygon, so the shader reads no LGHT
// ranges from them.
struct CoarseBuffers {
  GLuint vao = 0, vbo = 0, ibo = 0;
  CoarseBuffers() = default;
  CoarseBuffers(const LaidOutForm& form, std::span<const model::VertexRecord> vertices) {
    glGenBuffers(1, &ibo);
    glBindBuffer(GL_COPY_WRITE_BUFFER, ibo);  // no VAO bound yet: a target that is not VAO state
    glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(form.indices.size() * sizeof(std::uint32_t)),
                 form.indices.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    std::vector<model::VertexRecord> copies;
    copies.reserve(form.vertices.size());
    for (const std::uint32_t v : form.vertices) copies.push_back(vertices[v]);
    glGenBuffers(1, &vbo);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(copies.size() * sizeof(model::VertexRecord)), copies.data(),
                 GL_STATIC_DRAW);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    point_scene_attributes(vbo, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);  // recorded in the VAO
    glBindVertexArray(0);
  }
  CoarseBuffers(CoarseBuffers&& o) noexcept { *this = std::move(o); }
  CoarseBuffers& operator=(CoarseBuffers&& o) noexcept {
    std::swap(vao, o.vao);
    std::swap(vbo, o.vbo);
    std::swap(ibo, o.ibo);
    return *this;
  }
  ~CoarseBuffers() {
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &vbo);
    glDeleteBuffers(1, &ibo);
  }
};

// A scene program and its uniforms' locations.
struct ScenePass {
  ScenePass(const char* name, const std::string& vertex_source, const std::string& fragment_source)
      : program(name, vertex_source.c_str(), fragment_source.c_str()),
        u_view_projection(program.uniform("u_view_projection")),
        u_light(program.uniform("u_light")),
        // Absent from a program the GLSL compiler could prove never reads them: not an error.
        u_levels(glGetUniformLocation(program.id(), "u_levels")),
        u_ambient(program.uniform("u_ambient")),
        u_inv_exposure(program.uniform("u_inv_exposure")),
        u_opacity(program.uniform("u_opacity")),
        u_polygon_light(glGetUniformLocation(program.id(), "u_polygon_light")),
        u_polygon_first(glGetUniformLocation(program.id(), "u_polygon_first")),
        u_compact_colour(glGetUniformLocation(program.id(), "u_compact_colour")),
        u_compact_code(glGetUniformLocation(program.id(), "u_compact_code")),
        u_patch_weight(program.uniform("u_patch_weight")),
        u_clip_plane(program.uniform("u_clip_plane")) {}
  ShaderProgram program;
  GLint u_view_projection, u_light, u_levels, u_ambient, u_inv_exposure, u_opacity, u_polygon_light,
      u_polygon_first, u_compact_colour, u_compact_code, u_patch_weight, u_clip_plane;
};

struct Renderer::Impl {
  const model::Bundle& bundle;
  ScenePass full_pass{"scene", scene_source(bundle, kLightMixerVertexShader, true),
                      scene_source(bundle, kTonemapFragmentShader, false)};
  // With albedo maps, the flat moving levels draw through a program without them: sampling maps costs
  // llvmpipe 7-15 ms a 1280x720 frame (Sibenik), more than any level saves. Empty without maps.
  std::optional<ScenePass> flat_pass;
  // The coarse form's: flat light from each triangle's provoking vertex, over vertices shared between
  // polygons (render/cluster_layout.hpp); never with maps. Empty without a coarse form.
  std::optional<ScenePass> coarse_pass;
  ScenePass* pass = &full_pass;           // this frame's
  std::optional<AlbedoMaps> albedo_maps;  // only when the bundle has them
  // Subdivided quads carry their mixed radiosity per vertex: made on first use, like the accumulator.
  std::optional<ShaderProgram> shaded_program;
  GLuint shaded_vao = 0, shaded_vbo = 0;
  GLsizei shaded_vertices = 0;
  // Per unit, its subdivided triangles' run in the shaded buffer (in vertices): a frame draws the runs of
  // the units its list draws, so still frames pay for the sub-quads in view, not the model's.
  std::vector<IndexRange> shaded_runs;
  // What the shaded buffer was gathered for: a slice frame of the same sight, with no unit unmade since,
  // uploads only the sub-quads it made (each slice re-uploading the whole sight's cost L up to 5.5 MB a
  // frame). The buffer has room for shaded_capacity vertices.
  std::vector<std::uint32_t> shaded_sight;
  std::uint64_t shaded_unmade = 0;
  GLsizei shaded_capacity = 0;
  std::vector<GLint> shaded_firsts;
  std::vector<GLsizei> shaded_counts;
  // The coarse form with vertices shared between polygons, and (made on first use, for the A/B of
  // set_shared_coarse_vertices) with vertices of each polygon's own.
  CoarseBuffers coarse, own_coarse;
  bool shared_coarse_vertices = true;
  [[nodiscard]] GLuint coarse_vao() const { return shared_coarse_vertices ? coarse.vao : own_coarse.vao; }
  GLuint vao = 0, vbo = 0, ibo = 0, refined_vao = 0, refined_ibo = 0, light_buffer = 0, light_texture = 0,
         polygon_buffer = 0, polygon_texture = 0, polygon_first_buffer = 0, polygon_first_texture = 0,
         compact_colour_buffer = 0, compact_colour_texture = 0, compact_code_buffer = 0,
         compact_code_texture = 0, light_range_vbo = 0, levels_buffer = 0, levels_texture = 0;
  DisplayLight display_light;
  std::vector<float> shader_levels;    // this frame's, as u_levels takes them (DisplayLight::shader_levels)
  std::vector<float> uploaded_levels;  // what levels_buffer holds: a frame uploads only a change
  // Both index forms laid out cluster by cluster (fine INDX; coarse CIDX, drawn with flat polygon light
  // while moving, empty when the bundle has none), and each cell's PVS as units of that layout.
  ClusterLayout layout;
  std::vector<std::optional<std::vector<std::uint32_t>>> cell_units;  // made on first visit
  std::vector<std::uint32_t> every_unit;
  std::vector<std::uint32_t> near_units;  // this frame's, when sight starts in more than the eye's cell
  // The units the last frame's list was made from (its cell's PVS, the near cells' or every unit): what a
  // still view may draw, and so what its diagonals and sub-quads are made for.
  const std::vector<std::uint32_t>* sight_units = &every_unit;
  // The view the near cells and the portal walk were made for (frame_list() reuses them for the same one).
  std::uint32_t seen_cell = FrameStats::kNoCell;
  glm::mat4 seen_matrix{0.0f};
  bool seen_portals = false;
  bool near_all = false;  // sight starts in a cell off the walk: everything is drawn
  bool walked = false;    // the portals were walked for it
  CullingPolicy portal_policy{bundle.cells().size()};
  CullingPolicy occlusion_policy{bundle.cells().size()};
  bool adaptive_occlusion = true;
  bool occluded = false;  // the last view was culled by occlusion
  bool adaptive_portals = true;
  std::uint32_t cells_seen = 0;  // reached by that walk
  Framebuffer framebuffer;
  Framebuffer reduced_framebuffer;  // the Reduced moving level draws here, then scales up
  // Scaling up on the CPU (upscale.hpp): set_cpu_upscale's choice, else where GL rasterises on the CPU too.
  std::optional<bool> cpu_upscale;
  bool software = false;  // software_rasterizer(), asked once
  std::vector<std::uint8_t> reduced_pixels, upscaled_pixels;
  void upscale_on_cpu(const Framebuffer& source, int width, int height, int full_width, int full_height);

  std::vector<float> levels;
  std::optional<float> exposure_override;  // set_exposure: radiosity shown as white, instead of META's
  // Radiosity (W/m2) shown as white: the kiosk's override, else the bundle's, else 1.
  float exposure() const {
    const float e = exposure_override.value_or(bundle.meta().exposure);
    return e > 0.0f ? e : 1.0f;
  }
  DrawList list;  // this frame's
  bool culling = true;
  float glass_opacity = 0.25f;
  bool present_to_window = false;
  PresentRegion present_region;
  bool pvs_culling = true;
  bool frustum_culling = true;
  bool nearest_first = true;
  std::uint32_t run_triangles = kNearestFirstRunTriangles;
  bool detail_elision = true;  // LodChoice::leave_out_small
  bool portal_culling = true;
  std::optional<PortalView> portal_view;  // when the bundle has portals
  // Occlusion culling: the occluders found at load time, and the last view they were rasterised for.
  bool occlusion_culling = true;
  OccluderSet occluders;
  OcclusionCulling occlusion;
  // The last view's units (frame_list): what it may draw, and what the portals and the occlusion buffer
  // left out of that, with what they were made for.
  std::vector<std::uint32_t> view_units, behind_portals, occluded_units;
  struct ViewKey {
    std::uint32_t cell = FrameStats::kNoCell;
    glm::mat4 matrix{0.0f};
    const std::vector<std::uint32_t>* units = nullptr;
    const PortalView* portals = nullptr;
    bool frustum = false, back_faces = false, occlusion = false;
    int width = 0, height = 0;
    bool operator==(const ViewKey&) const = default;
  };
  std::optional<ViewKey> view_key;  // unset: no view yet
  bool map_overlay = false;
  float map_fraction = 0.35f;
  GLuint marker_vao = 0, marker_vbo = 0;
  FrameStats stats;

  // Adaptive refinement state: what the picture now shown was made from.
  std::optional<Accumulator> accumulator;  // made on first use: plain draw() callers never pay for it
  RefineSchedule schedule;
  FrameGovernor governor;
  std::optional<MovingLevel> pinned_level;
  MovingLevel moving_level = MovingLevel::Patches;
  FrameTiming frame_timing = FrameTiming::Auto;
  std::optional<bool> by_queries;     // frame_timing resolved in the current context, on first use
  std::optional<GpuTimer> gpu_timer;  // only when timing by queries
  bool use_queries();
  void learn_from_timer();
  std::vector<JitterSample> jitter = jitter_pattern(schedule.settings().aa_samples);
  std::optional<View> shown_view;
  int shown_width = 0, shown_height = 0;
  std::vector<float> shown_levels;
  std::optional<UnitRefinement> refinement;    // made with the layout: its polygons by unit, once
  std::vector<std::uint32_t> refined_indices;  // INDX with colour-chosen diagonals
  bool restart = true;  // settings changed or draw() overwrote the picture: start again as if moved

  Impl(const model::Bundle& b, DisplayLightForm form) : bundle(b), display_light(b, form) {}
  ~Impl() {
    glDeleteTextures(1, &compact_colour_texture);
    glDeleteBuffers(1, &compact_colour_buffer);
    glDeleteTextures(1, &compact_code_texture);
    glDeleteBuffers(1, &compact_code_buffer);
    glDeleteTextures(1, &polygon_texture);
    glDeleteBuffers(1, &polygon_buffer);
    glDeleteTextures(1, &polygon_first_texture);
    glDeleteBuffers(1, &polygon_first_buffer);
    glDeleteBuffers(1, &light_range_vbo);
    glDeleteTextures(1, &light_texture);
    glDeleteBuffers(1, &light_buffer);
    glDeleteTextures(1, &levels_texture);
    glDeleteBuffers(1, &levels_buffer);
    glDeleteBuffers(1, &ibo);
    glDeleteBuffers(1, &refined_ibo);
    glDeleteBuffers(1, &shaded_vbo);
    glDeleteVertexArrays(1, &shaded_vao);
    glDeleteBuffers(1, &marker_vbo);
    glDeleteVertexArrays(1, &marker_vao);
    glDeleteVertexArrays(1, &refined_vao);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
  }

  // The units `cell` may see (every unit without cells or outside them all).
  const std::vector<std::uint32_t>& units_for(std::uint32_t cell) {
    if (cell >= cell_units.size()) return every_unit;
    auto& slot = cell_units[cell];
    if (!slot) {
      const auto& c = bundle.cells()[cell];
      slot = units_of(layout, bundle.pvs().subspan(c.pvs_first, c.pvs_count));
    }
    return *slot;
  }
  // The units of every cell in `cells`; every unit when one is off the walk (an eye there draws all).
  const std::vector<std::uint32_t>& union_of_pvs(std::span<const std::uint32_t> cells) {
    near_units.clear();
    for (const std::uint32_t c : cells) {
      if (bundle.cells()[c].flags & model::kCellOutside) return every_unit;
      const auto& u = units_for(c);
      near_units.insert(near_units.end(), u.begin(), u.end());
    }
    std::sort(near_units.begin(), near_units.end());
    near_units.erase(std::unique(near_units.begin(), near_units.end()), near_units.end());
    return near_units;
  }
  // The cell's units, less those outside the frustum when one is given (frames go through frame_list,
  // which adds the near cells and the portal walk; the map overlay draws every unit through this).
  DrawList list_for(std::uint32_t cell, bool coarse, const Frustum* frustum, const LodChoice* lod = nullptr) {
    return cluster_draw_list(layout, coarse ? layout.coarse : layout.fine, units_for(cell), frustum, lod);
  }

  // The eye's cell decides what is drawn; without cells (or outside them all) everything is.
  [[nodiscard]] std::uint32_t cell_of(const View& view) const {
    if (bundle.cells().empty()) return FrameStats::kNoCell;
    const double eye[3] = {view.eye.x, view.eye.y, view.eye.z};
    const std::uint32_t cell = bundle.locate_cell(eye);
    if (cell >= bundle.cells().size()) return FrameStats::kNoCell;
    // Off the walk (only the outside reaches it): no PVS there, everything is drawn.
    return bundle.cells()[cell].flags & model::kCellOutside ? FrameStats::kNoCell : cell;
  }
  // The compiler leaves out of each cell's PVS the polygons turned away from all of it, which only a
  // renderer culling back faces may skip: with culling off, every polygon is drawn.
  [[nodiscard]] std::uint32_t list_cell(std::uint32_t cell) const {
    return pvs_culling && culling ? cell : FrameStats::kNoCell;
  }
  // A frame's list from the list cell `cell`: its PVS clusters, less those outside the frustum of
  // `view_projection_matrix` when frustum culling is on, each at its coarsest level within `lod_pixels` of
  // the full-size frame (flat light only: a level's vertices carry their own polygon's light), nearest
  // first unless that is off or `counts_only` (the governor's triangle counts, which no order changes).
  DrawList frame_list(std::uint32_t cell, const View& view, const glm::mat4& view_projection_matrix,
                      int full_width, int full_height, bool coarse, float lod_pixels,
                      bool counts_only = false) {
    const Frustum frustum(view_projection_matrix);
    const LodChoice lod{glm::vec3(view.eye), float(double(full_height) / vertical_field_of_view(view)),
                        coarse ? lod_pixels : 0.0f, detail_elision};
    const std::vector<std::uint32_t>* units = &units_for(cell);
    const PortalView* portals = nullptr;
    if (cell < bundle.cells().size()) {
      // The governor asks for each level's list of the same view: the walk is made once a view.
      const bool same_view = seen_cell == cell && seen_matrix == view_projection_matrix &&
                             seen_portals == (portal_culling && portal_view.has_value());
      if (!same_view) {
        const glm::vec3 eye(view.eye);
        near_units.clear();
        const auto starts =
            near_cells(bundle.nodes(), bundle.cells().size(), cell, eye, view_projection_matrix);
        near_all = false;
        if (starts.size() > 1) near_all = &union_of_pvs(starts) == &every_unit;
        cells_seen = 0;
        walked =
            portal_culling && portal_view && !near_all && (!adaptive_portals || portal_policy.applies(cell));
        if (walked) {
          portal_view->look_from(starts, eye, view_projection_matrix);
          cells_seen = portal_view->sees_everything() ? 0u : std::uint32_t(portal_view->cells_reached());
        }
        seen_cell = cell;
        seen_matrix = view_projection_matrix;
        seen_portals = portal_culling && portal_view.has_value();
      }
      if (near_all)
        units = &every_unit;
      else if (!near_units.empty())
        units = &near_units;
      if (walked) portals = &*portal_view;
    } else {
      cells_seen = 0;
      walked = false;
      seen_cell = FrameStats::kNoCell;
    }
    sight_units = units;
    const ViewKey key{cell,    view_projection_matrix, units,      portals,    frustum_culling,
                      culling, occlusion_culling,      full_width, full_height};
    if (view_key != key) {
      // What this view may draw, the same at every level: the units in the frustum that the portals show,
      // less those the nearest walls hide. Each level's list is then made from it with no test per unit.
      view_units.clear();
      behind_portals.clear();
      occluded_units.clear();
      for (const std::uint32_t u : *units) {
        if (u >= layout.units() || layout.drawn[u] == 0) continue;
        if (frustum_culling && !frustum.touches(layout.boxes[u])) continue;
        (portals && !portals->shows(u) ? behind_portals : view_units).push_back(u);
      }
      occluded = occlusion_culling && !occluders.polygons.empty() &&
                 (!adaptive_occlusion || occlusion_policy.applies(cell));
      if (occluded) {
        occlusion.look(occluders, layout, view_units, glm::vec3(view.eye), view_projection_matrix, full_width,
                       full_height, culling);
        std::erase_if(view_units, [&](std::uint32_t u) {
          if (!occlusion.hides(u)) return false;
          occluded_units.push_back(u);
          return true;
        });
      }
      view_key = key;
    }
    const LaidOutForm& form = coarse ? layout.coarse : layout.fine;
    const LodChoice* lod_choice = lod.max_pixels > 0.0f ? &lod : nullptr;
    DrawList list = cluster_draw_list(layout, form, view_units, nullptr, lod_choice, nullptr,
                                      nearest_first && !counts_only ? &lod.eye : nullptr, run_triangles);
    if (!counts_only) {
      list.triangles_behind_portals = triangles_of(layout, form, behind_portals, lod_choice);
      list.triangles_occluded = triangles_of(layout, form, occluded_units, lod_choice);
    }
    return list;
  }
  // What each moving level would draw from `view`: the triangles of its draw list, for the governor.
  std::array<double, kMovingLevels> level_triangles(const View& view, int width, int height) {
    const std::uint32_t cell = list_cell(cell_of(view));
    const glm::mat4 view_projection_matrix = view_projection(view, double(width) / double(height));
    std::array<double, kMovingLevels> out{};
    for (int l = 0; l < kMovingLevels; ++l) {
      const bool coarse = !layout.coarse.empty() && MovingLevel(l) != MovingLevel::Patches;
      out[std::size_t(l)] = frame_list(cell, view, view_projection_matrix, width, height, coarse,
                                       moving_error_pixels(MovingLevel(l)), true)
                                .triangles;
    }
    return out;
  }
  void draw_scene(const View& view, int width, int height, const DrawOptions& options);
  void warm_up(const View& view, int width, int height);
  std::pair<int, int> warmed_size{0, 0};
  void present(int width, int height) const;
  // Returns the ms spent making diagonals and sub-quads (the rest of its work is the frame's drawing).
  double choose_diagonals(const View& view);
  void upload_sub_quads(std::span<const std::uint32_t> units, std::span<const std::uint32_t> made);
  void draw_map(const View& view, int width, int height);
  // Draws runs of `vao`'s ShadedVertex triangles with the shaded program.
  void draw_shaded(GLuint vao, std::span<const GLint> firsts, std::span<const GLsizei> counts,
                   const glm::mat4& view_projection);
  // Draws the sub-quads of the units in `list`; returns their triangles.
  std::uint32_t draw_subdivided(const DrawList& list, const glm::mat4& view_projection);
  void make_shaded_program();
  void use_pass(const ScenePass& pass, const glm::mat4& view_projection, float patch_weight);
};

namespace {

const char* const kShadedVertexShader = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_radiosity;
layout(location = 2) in uint a_polygon;
uniform mat4 u_view_projection;
out vec3 v_radiosity;
void main() {
  v_radiosity = a_radiosity;
  gl_Position = u_view_projection * vec4(a_position, 1.0);
#ifdef WALK_ALBEDO_MAPS
  albedo_map(a_polygon, a_position);
#endif
}
)glsl";

// A VAO over a buffer of ShadedVertex.
void make_shaded_vao(GLuint& vao, GLuint& vbo) {
  glGenVertexArrays(1, &vao);
  glGenBuffers(1, &vbo);
  glBindVertexArray(vao);
  glBindBuffer(GL_ARRAY_BUFFER, vbo);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(ShadedVertex),
                        reinterpret_cast<const void*>(offsetof(ShadedVertex, position)));
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(ShadedVertex),
                        reinterpret_cast<const void*>(offsetof(ShadedVertex, radiosity)));
  glEnableVertexAttribArray(2);
  glVertexAttribIPointer(2, 1, GL_UNSIGNED_INT, sizeof(ShadedVertex),
                         reinterpret_cast<const void*>(offsetof(ShadedVertex, polygon)));
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

// One glMultiDrawElements over a batch's ranges of the bound VAO's index buffer.
void draw_batch(const DrawBatch& batch) {
  if (batch.empty()) return;
  glMultiDrawElements(GL_TRIANGLES, batch.counts.data(), GL_UNSIGNED_INT,
                      reinterpret_cast<const void* const*>(batch.byte_offsets.data()),
                      GLsizei(batch.counts.size()));
}

bool same_view(const View& a, const View& b) {
  return a.eye == b.eye && a.forward == b.forward && a.up == b.up && a.fov_y_degrees == b.fov_y_degrees &&
         a.near_plane == b.near_plane && a.far_plane == b.far_plane && a.screen == b.screen;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Renderer::Renderer(const model::Bundle& bundle, DisplayLightForm light_form)
    : impl_(std::make_unique<Impl>(bundle, light_form)) {
  auto& r = *impl_;
  r.software = software_rasterizer();
  const auto vertices = bundle.vertices();
  const std::size_t circuits = bundle.circuits().size();
  GLint max_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
  if (circuits > std::size_t(kMaxCircuits))
    throw Error("bundle '" + bundle.path() + "' has " + std::to_string(circuits) +
                " circuits; the renderer mixes at most " + std::to_string(kMaxCircuits) +
                " (merge circuits that are always dimmed together)");
  const std::size_t entries =
      std::max(r.display_light.full_entries().size(), r.display_light.compact_entries().size());
  if (entries > std::size_t(max_texels))
    throw Error("bundle '" + bundle.path() + "': " + std::to_string(entries) +
                " (vertex, circuit) light entries exceed this GL's texture buffer limit of " +
                std::to_string(max_texels) + "; compile with fewer circuits or a coarser mesh");

  if (!bundle.textures().empty())
    r.flat_pass.emplace("scene without maps", kLightMixerVertexShader, kTonemapFragmentShader);

  r.levels.resize(circuits);
  for (std::size_t c = 0; c < circuits; ++c)
    r.levels[c] = std::clamp(bundle.circuits()[c].default_level, 0.0f, 1.0f);
  r.layout = lay_out_clusters(layout_input(bundle));
  if (!r.layout.coarse.empty())
    r.coarse_pass.emplace("coarse scene", with_flat_light(kLightMixerVertexShader),
                          with_flat_light(kTonemapFragmentShader));
  r.every_unit = all_units(r.layout);
  r.refinement.emplace(RefinementInput{r.layout.fine.polygons, r.layout.unit_of_polygon, r.layout.units(),
                                       vertices, r.layout.fine.indices});
  r.cell_units.resize(bundle.cells().size());
  if (!bundle.portals().empty())
    r.portal_view.emplace(bundle.portals(), bundle.nodes(), bundle.cells().size(), r.layout.boxes);
  r.occluders = find_occluders(r.layout, vertices);
  const auto& indices = r.layout.fine.indices;

  // Static geometry: the VERT records are uploaded as they are (stride 40) and never touched again. A second
  // VAO shares them with the refined index buffer (same layout as INDX, diagonals chosen by colour).
  glGenBuffers(1, &r.vbo);
  glBindBuffer(GL_ARRAY_BUFFER, r.vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(vertices.size_bytes()), vertices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &r.ibo);
  glBindBuffer(GL_COPY_WRITE_BUFFER,
               r.ibo);  // no VAO bound yet: upload through a target that is not VAO state
  const GLsizeiptr index_bytes = GLsizeiptr(indices.size() * sizeof(std::uint32_t));
  glBufferData(GL_COPY_WRITE_BUFFER, index_bytes, indices.data(), GL_STATIC_DRAW);
  glGenBuffers(1, &r.refined_ibo);
  glBindBuffer(GL_COPY_WRITE_BUFFER, r.refined_ibo);
  glBufferData(GL_COPY_WRITE_BUFFER, index_bytes, indices.data(), GL_DYNAMIC_DRAW);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  // Where each vertex's light entries start (a_light_first), beside VERT in the same numbering.
  const auto& ranges = r.display_light.ranges();
  glGenBuffers(1, &r.light_range_vbo);
  glBindBuffer(GL_ARRAY_BUFFER, r.light_range_vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(ranges.size() * sizeof(VertexLightRange)), ranges.data(),
               GL_STATIC_DRAW);
  for (auto [vao, ibo] : {std::pair{&r.vao, r.ibo}, std::pair{&r.refined_vao, r.refined_ibo}}) {
    glGenVertexArrays(1, vao);
    glBindVertexArray(*vao);
    point_scene_attributes(r.vbo, r.light_range_vbo);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ibo);  // recorded in the VAO
    glBindVertexArray(0);
  }
  if (!r.layout.coarse.empty()) r.coarse = CoarseBuffers(r.layout.coarse, vertices);

  // Each vertex's light entries of the circuits shown full and of those shown compact, and the compact
  // form's colours; an empty buffer object still makes a valid texture.
  {
    const auto& full = r.display_light.full_entries();
    upload_texture_buffer(r.light_buffer, r.light_texture, GL_RGBA32F, full.data(),
                          full.size() * sizeof(FullLightEntry));
    const auto& codes = r.display_light.compact_entries();
    const bool compact = !r.display_light.compact_circuits().empty();
    const auto colours = bundle.compact_colour();
    upload_texture_buffer(r.compact_code_buffer, r.compact_code_texture, GL_R32UI, codes.data(),
                          codes.size() * sizeof(CompactLightEntry));
    upload_texture_buffer(r.compact_colour_buffer, r.compact_colour_texture, GL_RGBA8,
                          compact ? colours.data() : nullptr, compact ? colours.size_bytes() : 0);
  }
  {
    const auto& entries = r.display_light.polygon_entries();
    const auto& first = r.display_light.polygon_first();
    upload_texture_buffer(r.polygon_buffer, r.polygon_texture, GL_RGBA32F, entries.data(),
                          entries.size() * sizeof(FullLightEntry));
    upload_texture_buffer(r.polygon_first_buffer, r.polygon_first_texture, GL_R32UI, first.data(),
                          first.size() * sizeof(std::uint32_t));
  }
  // The dimmer levels, one float a circuit: written by the first frame and again whenever they change.
  upload_texture_buffer(r.levels_buffer, r.levels_texture, GL_R32F, nullptr, circuits * sizeof(float),
                        GL_DYNAMIC_DRAW);
  glBindTexture(GL_TEXTURE_BUFFER, 0);
  glBindBuffer(GL_TEXTURE_BUFFER, 0);
  if (!bundle.textures().empty()) {
    r.albedo_maps.emplace(bundle);
    glUseProgram(r.full_pass.program.id());
    AlbedoMaps::point_samplers(r.full_pass.program.id());
    glUseProgram(0);
  }
  check_gl("uploading the bundle's buffers");
}

Renderer::~Renderer() = default;

void Renderer::set_dimmers(std::span<const float> levels) {
  auto& own = impl_->levels;
  for (std::size_t c = 0; c < std::min(levels.size(), own.size()); ++c)
    own[c] = std::isnan(levels[c]) ? 0.0f : std::clamp(levels[c], 0.0f, 1.0f);
}
// refine() compares the levels with those of the picture shown, so a setter never forces a redraw itself.

std::span<const float> Renderer::dimmers() const {
  return impl_->levels;
}
void Renderer::set_exposure(std::optional<float> white_radiosity) {
  if (white_radiosity && !(*white_radiosity > 0.0f && std::isfinite(*white_radiosity)))
    white_radiosity.reset();
  if (impl_->exposure_override != white_radiosity) impl_->restart = true;
  impl_->exposure_override = white_radiosity;
}
void Renderer::set_backface_culling(bool enabled) {
  if (impl_->culling != enabled) impl_->restart = true;
  impl_->culling = enabled;
}
void Renderer::set_map_overlay(bool enabled, float fraction) {
  fraction = std::isfinite(fraction) ? std::clamp(fraction, 0.05f, 1.0f) : 0.35f;
  if (impl_->map_overlay != enabled || impl_->map_fraction != fraction) impl_->restart = true;
  impl_->map_overlay = enabled;
  impl_->map_fraction = fraction;
}
void Renderer::set_portal_culling(bool enabled) {
  if (impl_->portal_culling != enabled) impl_->restart = true;
  impl_->portal_culling = enabled;
}

void Renderer::set_cpu_upscale(std::optional<bool> enabled) {
  impl_->cpu_upscale = enabled;
}
void Renderer::set_occlusion_culling(bool enabled) {
  impl_->occlusion_culling = enabled;
  impl_->view_key.reset();
}

void Renderer::set_adaptive_occlusion_culling(bool enabled) {
  impl_->adaptive_occlusion = enabled;
  impl_->view_key.reset();  // decide afresh for the next view
}

void Renderer::set_adaptive_portal_culling(bool enabled) {
  impl_->adaptive_portals = enabled;
  impl_->seen_cell = FrameStats::kNoCell;  // decide afresh for the next view
}

void Renderer::set_nearest_first(bool enabled, std::uint32_t run_triangles) {
  impl_->nearest_first = enabled;
  impl_->run_triangles = run_triangles;
}

void Renderer::set_detail_elision(bool enabled) {
  impl_->detail_elision = enabled;
}

void Renderer::set_shared_coarse_vertices(bool enabled) {
  Impl& r = *impl_;
  r.shared_coarse_vertices = enabled;
  if (enabled || r.layout.coarse.empty() || r.own_coarse.vao != 0) return;
  // The same ranges over the same triangles; only the vertices (and so each triangle's) differ.
  r.own_coarse = CoarseBuffers(lay_out_clusters(layout_input(r.bundle), CoarseVertices::OwnPerPolygon).coarse,
                               r.bundle.vertices());
}

void Renderer::set_frustum_culling(bool enabled) {
  if (impl_->frustum_culling != enabled) impl_->restart = true;
  impl_->frustum_culling = enabled;
}
void Renderer::set_pvs_culling(bool enabled) {
  if (impl_->pvs_culling != enabled) impl_->restart = true;
  impl_->pvs_culling = enabled;
}
void Renderer::set_refine_settings(const RefineSettings& settings) {
  impl_->schedule = RefineSchedule(settings);
  impl_->refinement->forget();  // every unit found and made again at the next stop
  impl_->jitter = jitter_pattern(impl_->schedule.settings().aa_samples);
  impl_->restart = true;
}
void Renderer::set_frame_timing(FrameTiming timing) {
  impl_->frame_timing = timing;
  impl_->by_queries.reset();
  impl_->gpu_timer.reset();
}
bool Renderer::timing_by_queries() const {
  return impl_->use_queries();
}
bool Renderer::Impl::use_queries() {
  if (!by_queries) {
    const bool wanted =
        frame_timing == FrameTiming::Queries || (frame_timing == FrameTiming::Auto && !software_rasterizer());
    by_queries = wanted && timer_queries_supported();
    if (*by_queries) gpu_timer.emplace();
  }
  return *by_queries;
}
// Frames whose queries have finished teach the governor, each for the cell and level it was drawn at. A frame
// holds the display for its CPU submission or its GPU time, whichever is longer.
void Renderer::Impl::learn_from_timer() {
  while (auto done = gpu_timer->ready()) {
    const auto& [frame, gpu] = *done;
    const double ms = std::max(frame.cpu_ms, gpu);
    if (frame.moving)
      governor.record_moving(frame.cell, MovingLevel(frame.level), ms, frame.triangles);
    else
      governor.record_sample(ms / double(frame.samples));
    stats.gpu_ms = gpu;
  }
}
void Renderer::set_target_rate(double hz) {
  impl_->governor = FrameGovernor(hz);
}
void Renderer::set_moving_level(std::optional<MovingLevel> level) {
  impl_->pinned_level = level;
}
const FrameGovernor& Renderer::governor() const {
  return impl_->governor;
}
void Renderer::set_present_to_window(bool enabled) {
  impl_->present_to_window = enabled;
}

void Renderer::set_present_region(const PresentRegion& region) {
  impl_->present_region = region;
}

void Renderer::present_again() const {
  if (impl_->framebuffer.width() > 0) impl_->present(impl_->framebuffer.width(), impl_->framebuffer.height());
}
void Renderer::set_glass_opacity(float opacity) {
  if (impl_->glass_opacity != std::clamp(opacity, 0.0f, 1.0f)) impl_->restart = true;
  impl_->glass_opacity = std::clamp(opacity, 0.0f, 1.0f);
}
float Renderer::glass_opacity() const {
  return impl_->glass_opacity;
}
const FrameStats& Renderer::last_stats() const {
  return impl_->stats;
}
RefineStage Renderer::schedule_stage() const {
  return impl_->schedule.stage();
}

void Renderer::draw(const View& view, int width, int height) {
  draw(view, width, height, DrawOptions{});
}

void Renderer::draw(const View& view, int width, int height, const DrawOptions& options) {
  auto& r = *impl_;
  r.draw_scene(view, width, height, options);
  r.present(width, height);
  r.restart = true;  // the refined picture, if any, was overwritten
  r.stats.samples = 1;
}

void Renderer::Impl::present(int width, int height) const {
  if (!present_to_window) return;
  const PresentRegion& at = present_region;
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer.id());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
  if (at.buffer != WindowBuffer::Back)
    glDrawBuffer(at.buffer == WindowBuffer::BackLeft ? GL_BACK_LEFT : GL_BACK_RIGHT);
  glBlitFramebuffer(0, 0, width, height, at.x, at.y, at.x + width, at.y + height, GL_COLOR_BUFFER_BIT,
                    GL_NEAREST);
  if (at.buffer != WindowBuffer::Back) glDrawBuffer(GL_BACK);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("presenting a frame");
}

void Renderer::Impl::draw_scene(const View& view, int width, int height, const DrawOptions& options) {
  auto& r = *this;
  glm::mat4 view_projection_matrix = view_projection(view, double(width) / double(height));
  if (options.jitter_x != 0.0f || options.jitter_y != 0.0f) {
    // A translation after projection moves the image by whole NDC units: 2 / size per pixel.
    const glm::mat4 shift = glm::translate(
        glm::mat4(1.0f),
        glm::vec3(2.0f * options.jitter_x / float(width), 2.0f * options.jitter_y / float(height), 0.0f));
    view_projection_matrix = shift * view_projection_matrix;
  }
  // Reduced: the same frame into a smaller target, scaled up below. Fill dominates llvmpipe's frame time.
  const int full_width = width, full_height = height;
  const bool reduced = options.resolution < 1.0f;
  if (reduced) {
    const float scale = std::max(0.1f, options.resolution);
    width = std::max(1, int(float(width) * scale));
    height = std::max(1, int(float(height) * scale));
  }
  Framebuffer& target = reduced ? r.reduced_framebuffer : r.framebuffer;
  target.ensure_size(width, height);

  const std::uint32_t cell = r.cell_of(view), list_cell = r.list_cell(cell);
  // Flat polygon light needs no diced vertices: the coarse form draws the same surfaces in far fewer
  // triangles.
  const bool coarse = options.patch_weight <= 0.0f && !options.diagonals && !r.layout.coarse.empty();
  r.list = r.frame_list(list_cell, view, view_projection_matrix, full_width, full_height, coarse,
                        options.lod_pixels);
  if (r.walked)
    r.portal_policy.record(list_cell, r.list.triangles_behind_portals, r.list.triangles);
  else if (r.portal_culling && r.portal_view)
    r.portal_policy.rested(list_cell);
  if (r.occluded)
    r.occlusion_policy.record(list_cell, r.list.triangles_occluded, r.list.triangles);
  else if (r.occlusion_culling)
    r.occlusion_policy.rested(list_cell);
  const DrawList& list = r.list;

  glBindFramebuffer(GL_FRAMEBUFFER, target.id());
  glViewport(0, 0, width, height);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  if (r.culling) {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
  } else {
    glDisable(GL_CULL_FACE);
  }

  std::uint32_t subdivided = 0;
  if (!list.opaque.empty() || !list.glass.empty()) {
    r.pass = coarse                                        ? &*r.coarse_pass
             : r.flat_pass && options.patch_weight <= 0.0f ? &*r.flat_pass
                                                           : &r.full_pass;
    const ScenePass& pass = *r.pass;
    r.use_pass(pass, view_projection_matrix, options.patch_weight);
    if (r.albedo_maps && r.pass == &r.full_pass) r.albedo_maps->bind();
    const GLuint scene_vao = options.diagonals ? r.refined_vao : coarse ? r.coarse_vao() : r.vao;
    glBindVertexArray(scene_vao);
    glUniform1f(pass.u_opacity, 1.0f);
    draw_batch(list.opaque);
    if (options.diagonals && r.shaded_vertices > 0) {
      // The subdivided quads, over their own quads (kept as a crack filler): pulled one depth step towards
      // the eye so they win wherever both cover a pixel. Only those of the clusters in this frame's list,
      // and only while still.
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(-1.0f, -1.0f);
      subdivided = r.draw_subdivided(list, view_projection_matrix);
      glDisable(GL_POLYGON_OFFSET_FILL);
      glBindVertexArray(scene_vao);
    }
    if (!list.glass.empty()) {
      // After everything opaque, depth-tested but not written, so glass behind glass still shows. Alpha
      // keeps 1 in the frame so read_pixels stays opaque.
      glUniform1f(pass.u_opacity, r.glass_opacity);
      glEnable(GL_BLEND);
      glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
      glDepthMask(GL_FALSE);
      draw_batch(list.glass);
      glDepthMask(GL_TRUE);
      glDisable(GL_BLEND);
    }
    if (r.map_overlay) r.draw_map(view, width, height);
    glBindVertexArray(0);
    for (const int unit : {kPolygonFirstUnit, kCompactCodeUnit, kCompactColourUnit, 1, 0}) {
      glActiveTexture(GLenum(GL_TEXTURE0 + unit));
      glBindTexture(GL_TEXTURE_BUFFER, 0);
    }
    if (r.albedo_maps) AlbedoMaps::unbind();
    glUseProgram(0);
  }
  if (reduced) {
    r.framebuffer.ensure_size(full_width, full_height);
    if (r.cpu_upscale.value_or(r.software)) {
      r.upscale_on_cpu(target, width, height, full_width, full_height);
    } else {
      glBindFramebuffer(GL_READ_FRAMEBUFFER, target.id());
      glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r.framebuffer.id());
      glBlitFramebuffer(0, 0, width, height, 0, 0, full_width, full_height, GL_COLOR_BUFFER_BIT, GL_LINEAR);
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  check_gl("drawing a frame");

  r.stats.cell = cell;
  r.stats.polygons_drawn = list.polygons;
  r.stats.triangles_drawn = list.triangles;
  r.stats.subdivision_triangles_drawn = subdivided;
  r.stats.draw_ranges = std::uint32_t(list.opaque.counts.size() + list.glass.counts.size());
  r.stats.triangles_occluded = list.triangles_occluded;
  r.stats.cells_seen = r.cells_seen;
  r.stats.patch_weight = std::clamp(options.patch_weight, 0.0f, 1.0f);
  r.stats.resolution = reduced ? std::max(0.1f, options.resolution) : 1.0f;
  ++r.stats.frames_drawn;
}

// Read back, scaled up by pixman, written into the frame's colour texture: both copies are memcpy-like in
// llvmpipe (0.1 and 0.5 ms at 1280x720), unlike a blit, which shades every full-size pixel.
void Renderer::Impl::upscale_on_cpu(const Framebuffer& source, int width, int height, int full_width,
                                    int full_height) {
  reduced_pixels.resize(4 * std::size_t(width) * std::size_t(height));
  upscaled_pixels.resize(4 * std::size_t(full_width) * std::size_t(full_height));
  // RGBA8 rows are whole words, so the default pack and unpack alignment of 4 leaves no padding.
  glBindFramebuffer(GL_READ_FRAMEBUFFER, source.id());
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, reduced_pixels.data());
  scale_bilinear(reduced_pixels, width, height, upscaled_pixels, full_width, full_height);
  glBindTexture(GL_TEXTURE_2D, framebuffer.colour_texture());
  glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, full_width, full_height, GL_RGBA, GL_UNSIGNED_BYTE,
                  upscaled_pixels.data());
  glBindTexture(GL_TEXTURE_2D, 0);
}

void Renderer::Impl::make_shaded_program() {
  if (shaded_program) return;
  shaded_program.emplace("subdivided", scene_source(bundle, kShadedVertexShader, true).c_str(),
                         scene_source(bundle, kTonemapFragmentShader, false).c_str());
  if (!albedo_maps) return;
  // Set once, kept by the program: its samplers, and the maps at full weight, since subdivided quads are
  // drawn only in still frames, with the patches. The caller's program is restored.
  GLint caller = 0;
  glGetIntegerv(GL_CURRENT_PROGRAM, &caller);
  glUseProgram(shaded_program->id());
  AlbedoMaps::point_samplers(shaded_program->id());
  glUniform1f(glGetUniformLocation(shaded_program->id(), "u_patch_weight"), 1.0f);
  glUseProgram(GLuint(caller));
}

// Leaves the scene program bound, as the caller had it.
std::uint32_t Renderer::Impl::draw_subdivided(const DrawList& list, const glm::mat4& view_projection_matrix) {
  shaded_firsts.clear();
  shaded_counts.clear();
  for (const std::uint32_t u : list.units) {
    if (u >= shaded_runs.size() || shaded_runs[u].count == 0) continue;
    const IndexRange run = shaded_runs[u];
    if (!shaded_counts.empty() && GLuint(shaded_firsts.back() + shaded_counts.back()) == run.first)
      shaded_counts.back() += GLsizei(run.count);  // units in a row: one range
    else {
      shaded_firsts.push_back(GLint(run.first));
      shaded_counts.push_back(GLsizei(run.count));
    }
  }
  if (shaded_counts.empty()) return 0;
  draw_shaded(shaded_vao, shaded_firsts, shaded_counts, view_projection_matrix);
  return std::uint32_t(std::accumulate(shaded_counts.begin(), shaded_counts.end(), std::int64_t(0)) / 3);
}

// Leaves the scene program bound, as the caller had it.
void Renderer::Impl::draw_shaded(GLuint shaded_vao_id, std::span<const GLint> firsts,
                                 std::span<const GLsizei> counts, const glm::mat4& view_projection_matrix) {
  glUseProgram(shaded_program->id());
  glUniformMatrix4fv(shaded_program->uniform("u_view_projection"), 1, GL_FALSE,
                     &view_projection_matrix[0][0]);
  glUniform1f(shaded_program->uniform("u_inv_exposure"), 1.0f / exposure());
  glUniform1f(shaded_program->uniform("u_opacity"), 1.0f);
  if (albedo_maps) albedo_maps->bind();
  glBindVertexArray(shaded_vao_id);
  glMultiDrawArrays(GL_TRIANGLES, firsts.data(), counts.data(), GLsizei(counts.size()));
  glUseProgram(pass->program.id());
}

// Binds `pass` with this frame's uniforms and the light textures.
void Renderer::Impl::use_pass(const ScenePass& pass, const glm::mat4& view_projection, float patch_weight) {
  const auto& meta = bundle.meta();
  glUseProgram(pass.program.id());
  glUniformMatrix4fv(pass.u_view_projection, 1, GL_FALSE, &view_projection[0][0]);
  display_light.shader_levels(levels, shader_levels);
  if (shader_levels != uploaded_levels) {
    glBindBuffer(GL_TEXTURE_BUFFER, levels_buffer);
    glBufferSubData(GL_TEXTURE_BUFFER, 0, GLsizeiptr(shader_levels.size() * sizeof(float)),
                    shader_levels.data());
    glBindBuffer(GL_TEXTURE_BUFFER, 0);
    uploaded_levels = shader_levels;
  }
  glUniform1f(pass.u_ambient, meta.ambient);
  glUniform1f(pass.u_inv_exposure, 1.0f / exposure());
  glUniform1f(pass.u_patch_weight, std::clamp(patch_weight, 0.0f, 1.0f));
  glUniform4f(pass.u_clip_plane, 0.0f, 0.0f, 0.0f, 1.0f);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, light_texture);
  glUniform1i(pass.u_light, 0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_BUFFER, polygon_texture);
  if (pass.u_polygon_light >= 0) glUniform1i(pass.u_polygon_light, 1);
  glActiveTexture(GL_TEXTURE0 + kPolygonFirstUnit);
  glBindTexture(GL_TEXTURE_BUFFER, polygon_first_texture);
  if (pass.u_polygon_first >= 0) glUniform1i(pass.u_polygon_first, kPolygonFirstUnit);
  glActiveTexture(GL_TEXTURE0 + kCompactColourUnit);
  glBindTexture(GL_TEXTURE_BUFFER, compact_colour_texture);
  if (pass.u_compact_colour >= 0) glUniform1i(pass.u_compact_colour, kCompactColourUnit);
  glActiveTexture(GL_TEXTURE0 + kCompactCodeUnit);
  glBindTexture(GL_TEXTURE_BUFFER, compact_code_texture);
  if (pass.u_compact_code >= 0) glUniform1i(pass.u_compact_code, kCompactCodeUnit);
  glActiveTexture(GL_TEXTURE0 + kLevelsUnit);
  glBindTexture(GL_TEXTURE_BUFFER, levels_texture);
  if (pass.u_levels >= 0) glUniform1i(pass.u_levels, kLevelsUnit);
  glActiveTexture(GL_TEXTURE0);
}

// Called inside the scene pass (program, light textures and uniforms bound). Top-down orthographic view of
// the model's bounds in a square at the top-right corner, cut at 0.5 m above the eye so upper storeys and
// ceilings do not hide the floor plan; floors face up, so back-face culling keeps them.
void Renderer::Impl::draw_map(const View& view, int width, int height) {
  const auto& m = bundle.meta();
  const int side = std::max(16, int(float(height) * map_fraction));
  const int x0 = std::max(0, width - side - 8), y0 = std::max(0, height - side - 8);
  const glm::vec3 lo(m.bounds_min[0], m.bounds_min[1], m.bounds_min[2]);
  const glm::vec3 hi(m.bounds_max[0], m.bounds_max[1], m.bounds_max[2]);
  const glm::vec2 centre = 0.5f * (glm::vec2(lo) + glm::vec2(hi));
  const float half = 0.5f * std::max({hi.x - lo.x, hi.y - lo.y, 1.0f}) * 1.05f;
  const glm::mat4 projection = glm::ortho(-half, half, -half, half, 0.0f, hi.z - lo.z + 4.0f);
  const glm::mat4 look =
      glm::lookAt(glm::vec3(centre, hi.z + 2.0f), glm::vec3(centre, lo.z), glm::vec3(0, 1, 0));
  const glm::mat4 plan = projection * look;

  glEnable(GL_SCISSOR_TEST);
  glScissor(x0, y0, side, side);
  glViewport(x0, y0, side, side);
  glClearColor(0.05f, 0.05f, 0.08f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glEnable(GL_CLIP_DISTANCE0);
  // Flat polygon light, a plan and not a picture: the coarse form where the bundle has one.
  const bool coarse = !layout.coarse.empty();
  if (coarse) {
    pass = &*coarse_pass;
    use_pass(*pass, plan, 0.0f);
  }
  glUniformMatrix4fv(pass->u_view_projection, 1, GL_FALSE, &plan[0][0]);
  glUniform4f(pass->u_clip_plane, 0.0f, 0.0f, -1.0f, float(view.eye.z) + 0.5f);
  glUniform1f(pass->u_patch_weight, 0.0f);
  glUniform1f(pass->u_opacity, 1.0f);
  glBindVertexArray(coarse ? coarse_vao() : vao);
  draw_batch(list_for(FrameStats::kNoCell, coarse, nullptr).opaque);
  glDisable(GL_CLIP_DISTANCE0);
  glUniform4f(pass->u_clip_plane, 0.0f, 0.0f, 0.0f, 1.0f);

  // The viewer: a red arrow above everything, pointing where they look.
  make_shaded_program();
  if (!marker_vao) make_shaded_vao(marker_vao, marker_vbo);
  glm::vec2 f(view.forward.x, view.forward.y);
  f = glm::length(f) > 1e-6f ? glm::normalize(f) : glm::vec2(1, 0);
  const glm::vec2 side_dir(-f.y, f.x), eye(view.eye.x, view.eye.y);
  const float size = 0.06f * half, z = hi.z + 1.0f;
  const glm::vec3 red(exposure(), 0.0f, 0.0f);
  const ShadedVertex arrow[3] = {{glm::vec3(eye + f * size, z), red},
                                 {glm::vec3(eye - f * size * 0.6f + side_dir * size * 0.6f, z), red},
                                 {glm::vec3(eye - f * size * 0.6f - side_dir * size * 0.6f, z), red}};
  // The compile's largest leak (LEAK): a yellow line from a seed through portal centres to the opening,
  // under the arrow, so an integrator sees where the building is open (qbsp's .pts line).
  std::vector<ShadedVertex> marks(arrow, arrow + 3);
  const auto leak = bundle.leak_path();
  const glm::vec3 yellow = glm::vec3(red.x, red.x, 0.0f);
  const float line_half_width = 0.012f * half;
  for (std::size_t i = 0; i + 1 < leak.size(); ++i) {
    const glm::vec2 a(leak[i][0], leak[i][1]), b(leak[i + 1][0], leak[i + 1][1]);
    const glm::vec2 d = glm::length(b - a) > 1e-6f ? glm::normalize(b - a) : glm::vec2(1, 0);
    const glm::vec2 n = glm::vec2(-d.y, d.x) * line_half_width;
    const float lz = z - 0.5f;
    const glm::vec3 q[4] = {{a + n, lz}, {a - n, lz}, {b - n, lz}, {b + n, lz}};
    for (const int k : {0, 1, 2, 0, 2, 3}) marks.push_back({q[k], yellow});
  }
  glBindBuffer(GL_ARRAY_BUFFER, marker_vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(marks.size() * sizeof(ShadedVertex)), marks.data(),
               GL_DYNAMIC_DRAW);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glDisable(GL_CULL_FACE);  // whichever way the arrow winds from above
  const GLint first = 0;
  const GLsizei count = GLsizei(marks.size());
  draw_shaded(marker_vao, {&first, 1}, {&count, 1}, plan);
  glDisable(GL_SCISSOR_TEST);
  glViewport(0, 0, width, height);
}

// For the units the still view may draw (sight_units), each made once per mix (UnitRefinement), nearest
// first for as long a frame as leaves time to draw it (FrameGovernor::still_slice_ms, at most
// RefineSettings::diagonal_slice_ms); a vertex's colour is computed here exactly as
// the vertex shader mixes it.
double Renderer::Impl::choose_diagonals(const View& view) {
  const auto vertices = bundle.vertices();
  if (refined_indices.empty()) refined_indices = layout.fine.indices;
  const float ambient = bundle.meta().ambient;
  const auto colour_of = [&](std::uint32_t v) {
    const float* albedo = vertices[v].albedo;
    return ambient * glm::vec3(albedo[0], albedo[1], albedo[2]) + display_light.mixed(v, levels);
  };
  const auto& settings = schedule.settings();
  const std::span<const std::uint32_t> units = *sight_units;
  std::vector<std::pair<float, std::uint32_t>> by_distance;
  by_distance.reserve(units.size());
  for (const std::uint32_t u : units)
    if (u < layout.units()) by_distance.push_back({distance_to(glm::vec3(view.eye), layout.boxes[u]), u});
  std::sort(by_distance.begin(), by_distance.end());
  std::vector<std::uint32_t> nearest_first(by_distance.size());
  for (std::size_t i = 0; i < by_distance.size(); ++i) nearest_first[i] = by_distance[i].second;
  // The slice is the making's alone: the order above (every unit of a one-cell model such as Sibenik's) is
  // the frame's other work, measured with its drawing, so even the least slice makes more than one unit.
  const auto making_start = std::chrono::steady_clock::now();
  const UnitRefinement::Update update = refinement->update(
      nearest_first, {levels, settings.subdivision_error * exposure(), settings.subdivision_depth}, colour_of,
      refined_indices,
      [&, slice = governor.still_slice_ms(settings.diagonal_slice_ms), units_made = 0]() mutable {
        // Asked after each unit made: stop where the next, taken to cost what the units so far cost on
        // average, would end past the slice (a large cluster made after the slice ran out overran it by
        // several ms on L).
        const double spent = milliseconds_since(making_start);
        return settings.diagonal_slice_ms > 0.0 && spent + spent / double(++units_made) > slice;
      });
  const double making_ms = milliseconds_since(making_start);
  if (!update.finished) schedule.diagonals_unfinished();
  const std::vector<std::uint32_t>& made = update.made;
  const RefinementTotals totals = refinement->totals(units);
  stats.quads_flipped = totals.quads_flipped;
  stats.quads_subdivided = totals.quads_subdivided;
  stats.subdivision_triangles = totals.subdivision_triangles;

  // The replaced quads stay in the index buffer, under their sub-quads: where a sub-quad's edge midpoint
  // meets a neighbour that was not split (a T-junction), pixels that fall between the triangles in float
  // show the quad's own Gouraud colour instead of a crack to the background.
  upload_sub_quads(units, made);
  // The made units' ranges only, runs of units next to each other as one (through the copy target: the
  // element binding belongs to whichever VAO is bound).
  glBindBuffer(GL_COPY_WRITE_BUFFER, refined_ibo);
  std::vector<IndexRange> ranges;
  for (const std::uint32_t u : made)
    for (const IndexRange& r : {layout.fine.opaque[u], layout.fine.glass[u]}) {
      if (r.count == 0) continue;
      if (!ranges.empty() && ranges.back().first + ranges.back().count == r.first)
        ranges.back().count += r.count;
      else
        ranges.push_back(r);
    }
  for (const IndexRange& r : ranges)
    glBufferSubData(GL_COPY_WRITE_BUFFER, GLintptr(r.first * sizeof(std::uint32_t)),
                    GLsizeiptr(r.count * sizeof(std::uint32_t)), refined_indices.data() + r.first);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
  check_gl("uploading the chosen diagonals");
  return making_ms;
}

// The sub-quads of the sight's made units into the shaded buffer: after a gather of the same sight with no
// unit unmade since, only those of `made` are appended, where the buffer has room; otherwise the sight's all
// are gathered again into a buffer with room for as many more.
void Renderer::Impl::upload_sub_quads(std::span<const std::uint32_t> units,
                                      std::span<const std::uint32_t> made) {
  std::vector<ShadedVertex> triangles;
  if (shaded_unmade == refinement->unmade() && std::ranges::equal(units, shaded_sight)) {
    refinement->append(made, triangles, shaded_runs, std::uint32_t(shaded_vertices));
    if (triangles.empty()) return;
    if (GLsizeiptr(shaded_vertices) + GLsizeiptr(triangles.size()) <= GLsizeiptr(shaded_capacity)) {
      glBindBuffer(GL_ARRAY_BUFFER, shaded_vbo);
      glBufferSubData(GL_ARRAY_BUFFER, GLintptr(shaded_vertices) * GLintptr(sizeof(ShadedVertex)),
                      GLsizeiptr(triangles.size() * sizeof(ShadedVertex)), triangles.data());
      glBindBuffer(GL_ARRAY_BUFFER, 0);
      shaded_vertices += GLsizei(triangles.size());
      return;
    }
  }
  refinement->gather(units, triangles, shaded_runs);
  shaded_sight.assign(units.begin(), units.end());
  shaded_unmade = refinement->unmade();
  shaded_vertices = GLsizei(triangles.size());
  if (triangles.empty()) return;
  // The map view may have made the program already; the VAO is this step's own.
  make_shaded_program();
  if (!shaded_vao) make_shaded_vao(shaded_vao, shaded_vbo);
  shaded_capacity = GLsizei(std::min<std::size_t>(2 * triangles.size(), std::numeric_limits<GLsizei>::max()));
  glBindBuffer(GL_ARRAY_BUFFER, shaded_vbo);
  glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(shaded_capacity) * GLsizeiptr(sizeof(ShadedVertex)), nullptr,
               GL_DYNAMIC_DRAW);
  glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(triangles.size() * sizeof(ShadedVertex)), triangles.data());
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

// The first frame down a drawing path costs llvmpipe its JIT compile of that state: the half-resolution
// level's scaling blit (where it blits) 40-90 ms once, a level's first frame several ms more. Each moving
// level is drawn once, off the record, at a new frame size, so no moving frame shows the hitch and no cost
// model learns it (a 90 ms first half-resolution frame made M's governor shun that level).
void Renderer::Impl::warm_up(const View& view, int width, int height) {
  warmed_size = {width, height};
  const FrameStats kept_stats = stats;
  const CullingPolicy kept_portal_policy = portal_policy, kept_occlusion_policy = occlusion_policy;
  for (int l = 0; l < kMovingLevels; ++l) {
    const auto level = MovingLevel(l);
    draw_scene(view, width, height,
               DrawOptions{.patch_weight = level == MovingLevel::Patches ? 1.0f : 0.0f,
                           .resolution = level == MovingLevel::Reduced ? 0.5f : 1.0f,
                           .lod_pixels = moving_error_pixels(level)});
  }
  glFinish();
  stats = kept_stats;
  stats.warm_up_frames += kMovingLevels;
  portal_policy = kept_portal_policy;
  occlusion_policy = kept_occlusion_policy;
}

bool Renderer::refine(const View& view, int width, int height) {
  auto& r = *impl_;
  if (r.warmed_size != std::pair{width, height}) r.warm_up(view, width, height);
  const bool moved = r.restart || !r.shown_view || !same_view(*r.shown_view, view) ||
                     width != r.shown_width || height != r.shown_height;
  const bool relit = r.shown_levels != r.levels;
  if (moved) {
    // A pinned level needs no prediction: the governor is asked only to keep its per-cell state. The
    // levels' lists (and the portal walk, once a view) are this frame's too: up to 4 ms on E1M1, which a
    // budget judged without them would overrun.
    const auto prepare_start = std::chrono::steady_clock::now();
    std::array<double, kMovingLevels> triangles{};
    if (!r.pinned_level) triangles = r.level_triangles(view, width, height);
    const std::uint32_t cell = r.cell_of(view);
    r.moving_level = r.pinned_level.value_or(r.governor.choose_moving(
        cell, r.pinned_level ? std::span<const double>() : std::span<const double>(triangles),
        milliseconds_since(prepare_start)));
    r.schedule.view_changed(r.moving_level == MovingLevel::Patches ? 1.0f : 0.0f);
  } else if (relit) {
    r.schedule.light_changed();
  }
  r.shown_view = view;
  r.shown_width = width;
  r.shown_height = height;
  r.shown_levels = r.levels;
  r.restart = false;

  const auto start = std::chrono::steady_clock::now();
  RefineStep step = r.schedule.next();
  r.stats.stage = step.stage;
  if (!step.draws()) return false;  // converged: the picture shown is final, the CPU stays idle

  const double making_ms = step.stage == RefineStage::Diagonals ? r.choose_diagonals(view) : 0.0;
  if (step.stage != RefineStage::Accumulating) {
    const bool moving = step.stage == RefineStage::Moving;
    const float resolution = moving && r.moving_level == MovingLevel::Reduced ? 0.5f : 1.0f;
    const float lod_pixels = moving ? moving_error_pixels(r.moving_level) : 0.0f;
    const bool queries = moving && r.use_queries();
    if (queries) r.gpu_timer->begin();
    r.draw_scene(view, width, height,
                 DrawOptions{step.patch_weight, 0.0f, 0.0f, resolution, step.diagonals, lod_pixels});
    r.stats.samples = 1;
    if (moving) {
      r.stats.moving_level = r.moving_level;
      if (queries) {
        r.gpu_timer->end({true, r.stats.cell, std::uint8_t(r.moving_level), double(r.stats.triangles_drawn),
                          1, milliseconds_since(start)});
        r.learn_from_timer();
      } else {
        glFinish();
        r.governor.record_moving(r.stats.cell, r.moving_level, milliseconds_since(start),
                                 double(r.stats.triangles_drawn));
      }
    } else if (!r.use_queries()) {
      // The frame less its making of diagonals and sub-quads (their gathering, upload and the draw): what
      // the next refinement slice leaves time for (where the GPU is timed by queries, it draws fast enough
      // that the slice's cap holds).
      glFinish();
      r.governor.record_still_draw(milliseconds_since(start) - making_ms);
    }
  } else {
    if (!r.accumulator) r.accumulator.emplace();
    if (step.sample == 0) r.accumulator->reset(width, height);
    // As many samples as the governor says fit in one frame; the last one drawn ends this step.
    const int fixed = r.schedule.settings().samples_per_frame;
    const int budget = fixed > 0 ? fixed : r.governor.samples_per_frame();
    const bool queries = r.use_queries();
    if (queries) r.gpu_timer->begin();
    int drawn = 0;
    for (;;) {
      const JitterSample& j = r.jitter[std::size_t(step.sample) % r.jitter.size()];
      r.draw_scene(view, width, height, DrawOptions{1.0f, j.dx, j.dy, 1.0f, step.diagonals});
      r.accumulator->add(r.framebuffer.colour_texture(), j.weight);
      if (++drawn >= budget || r.schedule.stage() != RefineStage::Accumulating) break;
      step = r.schedule.next();
    }
    r.accumulator->resolve(r.framebuffer.id());
    if (queries) {
      r.gpu_timer->end({false, 0, 0, -1.0, drawn, milliseconds_since(start)});
      r.learn_from_timer();
    } else {
      glFinish();
      r.governor.record_sample(milliseconds_since(start) / double(drawn));
    }
    r.stats.samples = r.accumulator->samples();
    r.stats.stage = RefineStage::Accumulating;
  }
  r.present(width, height);
  return true;
}

Image Renderer::read_pixels(int width, int height) const {
  const auto& fb = impl_->framebuffer;
  if (width != fb.width() || height != fb.height())
    throw Error("read_pixels(" + std::to_string(width) + "x" + std::to_string(height) +
                ") after drawing at " + std::to_string(fb.width()) + "x" + std::to_string(fb.height()) +
                "; draw at the size you read");
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(std::size_t(width) * height * 4);
  std::vector<std::uint8_t> bottom_up(image.rgba.size());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fb.id());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check_gl("reading pixels");
  // GL's rows run bottom up; Image's run top down.
  const std::size_t row = std::size_t(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy_n(bottom_up.data() + std::size_t(height - 1 - y) * row, row,
                image.rgba.data() + std::size_t(y) * row);
  return image;
}

}  // namespace walk::render
