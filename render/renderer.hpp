#pragma once
// Draws a bundle: static buffers uploaded once, the PVS of the eye's cell, circuits mixed by dimmer levels in
// the vertex shader (a dimmer change shows in the next frame with no re-upload). Needs a current GL context.
#include <cstdint>
#include <glm/vec3.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "model/bundle.hpp"
#include "render/display_light.hpp"
#include "render/draw_list.hpp"
#include "render/governor.hpp"
#include "render/gpu_timer.hpp"
#include "render/refine_schedule.hpp"

namespace walk::render {

// A camera in the bundle's local coordinates (metres, z up).
// A fixed physical screen in the same coordinates: the picture is the view through this rectangle from the
// eye (head-coupled, off-axis perspective; Kooima 2008). Three corners; the fourth completes the rectangle.
struct ScreenRect {
  glm::dvec3 lower_left{0.0}, lower_right{0.0}, upper_left{0.0};
  bool operator==(const ScreenRect&) const = default;
};

struct View {
  glm::dvec3 eye{0.0};
  glm::dvec3 forward{1.0, 0.0, 0.0};
  glm::dvec3 up{0.0, 0.0, 1.0};
  double fov_y_degrees = 60.0;
  double near_plane = 0.05;
  double far_plane = 500.0;
  // Set: the projection is the off-axis frustum from eye through the screen; forward, up and fov_y_degrees
  // are then not used for it (forward still tells which way the walker faces).
  std::optional<ScreenRect> screen;
};

// Top row first, RGBA8.
struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
  [[nodiscard]] const std::uint8_t* pixel(int x, int y) const {
    return &rgba[(std::size_t(y) * width + x) * 4];
  }
};

enum class WindowBuffer { Back, BackLeft, BackRight };
struct PresentRegion {
  int x = 0, y = 0;  // lower-left corner in the window, pixels
  WindowBuffer buffer = WindowBuffer::Back;
};

// How one draw() call draws; the defaults are the full-quality single frame.
struct DrawOptions {
  float patch_weight = 1.0f;  // 0: flat polygon light (PLGT, the coarse display), 1: per-vertex patches
  float jitter_x = 0.0f;      // sub-pixel offset of the image, pixels (anti-aliasing samples)
  float jitter_y = 0.0f;
  float resolution = 1.0f;  // below 1: drawn at this fraction of the size and scaled up (moving, Reduced)
  bool diagonals = false;   // quads split along the diagonals last chosen by colour (refine() chooses them)
  // Above 0 (with flat light): each cluster at its coarsest level of detail whose error projects under this
  // many pixels of the full-size frame. 0: every triangle.
  float lod_pixels = 0.0f;
};

struct FrameStats {
  static constexpr std::uint32_t kNoCell =
      0xffffffffu;  // no cells, or the eye is outside all of them: all drawn
  std::uint32_t cell = 0;
  std::uint32_t polygons_drawn = 0;
  std::uint32_t triangles_drawn = 0;     // at the level of detail drawn
  std::uint32_t draw_ranges = 0;         // glMultiDrawElements entries after merging neighbouring clusters
  std::uint32_t cells_seen = 0;          // cells reached through portals (0: portal culling did not run)
  std::uint32_t triangles_occluded = 0;  // left out by occlusion culling (after the PVS, frustum, portals)
  std::uint64_t frames_drawn =
      0;  // frames this renderer has drawn (draw() calls and refine() steps that drew)
  RefineStage stage = RefineStage::Moving;          // what the last refine() step did (Idle: drew nothing)
  MovingLevel moving_level = MovingLevel::Patches;  // the level of the last moving refine() step
  float patch_weight = 1.0f;                        // of the last frame drawn
  float resolution = 1.0f;             // of the last frame drawn (0.5 at the Reduced moving level)
  int samples = 1;                     // samples accumulated in the picture now shown
  std::uint32_t quads_flipped = 0;     // quads split differently from the bundle at the last diagonal choice
  std::uint32_t quads_subdivided = 0;  // quads drawn as bilinear sub-quads at the last choice
  std::uint32_t subdivision_triangles = 0;  // sub-quad triangles made at the last choice
  // Of those, drawn by the last frame: the sub-quads of the units its list draws (0 while moving).
  std::uint32_t subdivision_triangles_drawn = 0;
  double gpu_ms = -1.0;  // GPU time of the newest frame timed by queries (it lags a frame or two); -1: none
  // Frames refine() drew off the record to warm each moving level at a new frame size (not in frames_drawn).
  std::uint64_t warm_up_frames = 0;
};

class Renderer {
 public:
  // Uploads the bundle's buffers into the current context, which must stay current for every call and for
  // the destructor. The bundle must outlive the renderer. Throws walk::Error for more than kMaxCircuits
  // circuits (65,536).
  // `light_form`: each circuit in the form the compiler chose (compact where within its limit), or all full.
  explicit Renderer(const model::Bundle& bundle, DisplayLightForm light_form = DisplayLightForm::AsCompiled);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // One level per circuit, clamped to 0..1 (NaN reads as 0); missing entries keep their previous level.
  void set_dimmers(std::span<const float> levels);
  [[nodiscard]] std::span<const float> dimmers() const;
  // On by default: each zone's copy of a double wall faces into its own zone. The bundle's PVS assumes it
  // (polygons turned away from a whole cell are left out), so turning it off also draws every polygon.
  void set_backface_culling(bool enabled);
  // Radiosity (W/m2 per channel) shown as white, instead of the bundle's exposure; std::nullopt (or a value
  // that is not positive) hands it back to the bundle. The kiosk's [display] white_luminance sets it.
  void set_exposure(std::optional<float> white_radiosity);
  // Blit each frame to the default framebuffer (a window); off by default. Use Backend::has_window().
  void set_present_to_window(bool enabled);
  // Where in the window a frame goes: its lower-left corner, and for quad-buffered stereo the eye's back
  // buffer. Several renderers share one window this way (stereo eyes, screens of one spanning output).
  void set_present_region(const PresentRegion& region);
  // Blits the last frame to its region again: after a swap, a region whose renderer did not draw would show
  // whatever the back buffer held.
  void present_again() const;
  // Glass polygons are blended over what is behind them with this opacity (0..1, default 0.25), in display
  // (sRGB) values: glass blocks walking, not seeing.
  // The paper's floor plan for navigation: a view from above of everything at or below the viewer's storey,
  // with the viewer as a red arrow, drawn over the top-right corner (`fraction` of the frame's height).
  void set_map_overlay(bool enabled, float fraction = 0.35f);
  void set_glass_opacity(float opacity);
  [[nodiscard]] float glass_opacity() const;
  // Off: every polygon is drawn whatever the eye's cell (for comparison and benchmarks). On by default.
  void set_pvs_culling(bool enabled);
  // On by default: also drop the PVS's clusters whose box is wholly outside the view frustum (one box test
  // per cluster per frame). Off: the cell's whole PVS is drawn.
  void set_frustum_culling(bool enabled);
  // On by default, with the PVS: narrow the view through the cells' portals each frame (Luebke & Georges
  // 1995) and draw only the clusters the eye's chains of portals show. Bundles without portals draw the PVS.
  void set_portal_culling(bool enabled);
  // On by default: a cell whose portal walk hides little rests from it for a while (culling_policy.hpp). Off:
  // every frame walks (the pixel tests, which must exercise the walk in every view).
  void set_adaptive_portal_culling(bool enabled);
  // On by default: each view rasterises the nearest large walls, floors and ceilings in view into a small
  // software depth buffer and leaves out the clusters they hide (occlusion_buffer.hpp: conservative, the
  // same picture). Off: what the PVS, the frustum and the portals leave is drawn.
  void set_occlusion_culling(bool enabled);
  // On by default: a cell where occlusion culling hides little rests from it for a while
  // (culling_policy.hpp). Off: every view is culled (the pixel tests).
  void set_adaptive_occlusion_culling(bool enabled);
  // How the Reduced level's half-size frame is scaled up to the full size: nullopt (the default) on the CPU
  // where GL rasterises on the CPU too (llvmpipe at 1280x720: 1.5 ms against a GL_LINEAR blit's 5-7 ms;
  // upscale.hpp), else by the blit; true or false forces one. At an even frame size the two differ by at most
  // 1 in a channel.
  void set_cpu_upscale(std::optional<bool> enabled);
  // On by default: opaque clusters are drawn nearest first (by their boxes' distance from the eye), so the
  // depth test, which llvmpipe makes before shading, spares the fragments they hide; clusters adjacent in
  // the buffer go as runs of up to `run_triangles` (0: each on its own). Off: the compiler's order, whose
  // neighbouring clusters merge into fewer draw ranges. Either way the same picture.
  void set_nearest_first(bool enabled, std::uint32_t run_triangles = kNearestFirstRunTriangles);
  // On by default: a moving level with a pixel budget leaves out clusters whose whole box spans no more than
  // it (cluster_layout.hpp too_small_to_draw), as a level of detail within the budget may move a surface
  // that far. Full-detail frames draw everything either way.
  void set_detail_elision(bool enabled);
  // On by default: the coarse form's polygons share vertices where their corners coincide, each triangle
  // ending on a vertex of its own polygon for its flat light (cluster_layout.hpp). Off: each polygon's
  // vertices its own, as VERT has them (for the A/B in walk bench render). The same picture either way.
  void set_shared_coarse_vertices(bool enabled);
  void draw(const View& view, int width, int height);
  void draw(const View& view, int width, int height, const DrawOptions& options);

  // Adaptive refinement, the kiosk's per-frame call: a moving view is drawn at the level the frame-rate
  // governor picks for the eye's cell; a still view is refined step by step (patches blended in, then
  // jittered samples accumulated); once converged, nothing is drawn until the view, size, dimmers or settings
  // change. Returns whether it drew. Times moving frames and accumulation steps for the governor as
  // set_frame_timing says.
  bool refine(const View& view, int width, int height);
  // Auto (the default): GL timer queries on hardware drivers, glFinish and the CPU clock on software
  // rasterizers (render/gpu_timer.hpp says why). Queries falls back to Finish where the driver's counter
  // has no bits.
  void set_frame_timing(FrameTiming timing);
  [[nodiscard]] bool timing_by_queries() const;  // what refine() uses in the current context
  void set_refine_settings(const RefineSettings& settings);
  // Frame rate the governor holds (default 60).
  void set_target_rate(double hz);
  // Pins the moving level instead of letting the governor choose; std::nullopt hands it back.
  void set_moving_level(std::optional<MovingLevel> level);
  [[nodiscard]] const FrameGovernor& governor() const;
  [[nodiscard]] Image read_pixels(int width, int height) const;
  [[nodiscard]] const FrameStats& last_stats() const;
  // The stage the next refine() takes if nothing changes (Diagonals again while clusters wait for theirs).
  [[nodiscard]] RefineStage schedule_stage() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Throws walk::Error naming the path when it cannot be written.
void write_png(const std::string& path, const Image& image);

}  // namespace walk::render
