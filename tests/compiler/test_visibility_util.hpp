#pragma once
// Small buildings for the visibility tests: axis-aligned quads turned into bundle records.
#include <array>
#include <cstdint>
#include <vector>

#include "compiler/visibility/compute_cells.hpp"
#include "compiler/visibility/verify_visibility.hpp"
#include "model/bundle.hpp"

namespace walk::compiler::testing {

struct MiniBuilding {
  model::BundleContents b;

  // A quad a-b-c-d (planar, convex) of the given role.
  std::uint32_t quad(model::Vec3 a, model::Vec3 bb, model::Vec3 c, model::Vec3 d,
                     model::Role role = model::Role::Opaque) {
    const auto first_vertex = static_cast<std::uint32_t>(b.vertices.size());
    for (const auto& p : {a, bb, c, d}) {
      model::VertexRecord v{};
      v.position[0] = float(p.x);
      v.position[1] = float(p.y);
      v.position[2] = float(p.z);
      v.polygon = static_cast<std::uint32_t>(b.polygons.size());
      b.vertices.push_back(v);
    }
    model::PolygonRecord poly{};
    poly.first_index = static_cast<std::uint32_t>(b.indices.size());
    poly.index_count = 6;
    poly.first_vertex = first_vertex;
    poly.vertex_count = 4;
    poly.role = static_cast<std::uint32_t>(role);
    for (const std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) b.indices.push_back(first_vertex + i);
    b.polygons.push_back(poly);
    return static_cast<std::uint32_t>(b.polygons.size() - 1);
  }

  // Axis-aligned rectangle in the plane `axis` = coord, spanning [u0,u1] x [v0,v1] of the other two axes
  // (u = (axis+1)%3, v = (axis+2)%3).
  // It faces +axis; `facing` -1 turns it round.
  std::uint32_t rect(int axis, double coord, double u0, double u1, double v0, double v1,
                     model::Role role = model::Role::Opaque, int facing = 1) {
    auto p = [&](double u, double v) {
      model::Vec3 q{0.0};
      q[axis] = coord;
      q[(axis + 1) % 3] = u;
      q[(axis + 2) % 3] = v;
      return q;
    };
    if (facing < 0) return quad(p(u0, v0), p(u0, v1), p(u1, v1), p(u1, v0), role);
    return quad(p(u0, v0), p(u1, v0), p(u1, v1), p(u0, v1), role);
  }

  // The six faces of a box room facing into it (a room as the renderer, culling back faces, shows it).
  void room_inward(model::Vec3 lo, model::Vec3 hi) {
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      rect(a, lo[a], lo[u], hi[u], lo[v], hi[v], model::Role::Opaque, 1);
      rect(a, hi[a], lo[u], hi[u], lo[v], hi[v], model::Role::Opaque, -1);
    }
  }

  // The shell of a 4 m wide, 3 m high row `len` long along x: floor, ceiling, end and side walls. Returns
  // the far end wall (x = len).
  std::uint32_t row_shell(double len) {
    rect(2, 0.0, 0, len, 0, 4);
    rect(2, 3.0, 0, len, 0, 4);
    rect(0, 0.0, 0, 4, 0, 3);
    const auto end = rect(0, len, 0, 4, 0, 3);
    rect(1, 0.0, 0, 3, 0, len);
    rect(1, 4.0, 0, 3, 0, len);
    return end;
  }

  // Rectangle with a rectangular hole (the hole must lie inside), as up to four rectangles around it.
  void rect_with_hole(int axis, double coord, double u0, double u1, double v0, double v1, double hu0,
                      double hu1, double hv0, double hv1, int facing = 1) {
    const auto opaque = model::Role::Opaque;
    if (hu0 > u0) rect(axis, coord, u0, hu0, v0, v1, opaque, facing);
    if (hu1 < u1) rect(axis, coord, hu1, u1, v0, v1, opaque, facing);
    if (hv0 > v0) rect(axis, coord, hu0, hu1, v0, hv0, opaque, facing);
    if (hv1 < v1) rect(axis, coord, hu0, hu1, hv1, v1, opaque, facing);
  }

  // The six faces of a closed box room.
  void room(model::Vec3 lo, model::Vec3 hi) {
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      rect(a, lo[a], lo[u], hi[u], lo[v], hi[v]);
      rect(a, hi[a], lo[u], hi[u], lo[v], hi[v]);
    }
  }
};

// Polygons the flow and the sampling need not be asked about: every test checks the PVS against ID images.
// The mini buildings' walls are single quads standing for solid walls, so by default they are judged as
// drawn from both sides (`cull_back_faces` false here and in the tests' judges); the tests of back-face
// culling build walls facing the way a renderer that culls them needs.
inline VisibilityConfig test_config(PvsMethod method = PvsMethod::Conservative,
                                    bool cull_back_faces = false) {
  VisibilityConfig c;
  c.cull_back_faces = cull_back_faces;
  c.method = method;
  c.threads = 1;
  c.sample_points = 8;
  c.rays_per_point = 64;
  // Seeing past back faces relies on the tie rule (of two back-to-back walls the one facing the ray wins),
  // which the axial caster keeps and the skeleton's BVH does not.
  c.ray_caster = cull_back_faces ? "axial" : "bvh";
  return c;
}

// Small images keep the suite fast; the hard cases are built so that a miss would cover many pixels.
inline VerifyOptions small_judge(bool cull_back_faces = false) {
  VerifyOptions o;
  o.cull_back_faces = cull_back_faces;
  o.viewpoints = 3;
  o.resolution = 48;
  o.dense = 2;
  o.dense_resolution = 24;
  o.ray_caster = test_config(PvsMethod::Conservative, cull_back_faces).ray_caster;  // see test_config
  o.threads = 1;
  return o;
}

// Every cell of `vis`, in order.
inline std::vector<std::uint32_t> all_cells(const VisibilityResult& vis) {
  std::vector<std::uint32_t> cells(vis.partition.cells.size());
  for (std::uint32_t c = 0; c < cells.size(); ++c) cells[c] = c;
  return cells;
}

// Pixels the PVS of each of `cells` misses, judged from inside each cell and from beside its portals.
inline std::uint64_t missed_pixels(const MiniBuilding& m, const VisibilityResult& vis,
                                   const std::vector<std::uint32_t>& cells, bool cull_back_faces = false) {
  const VisibilityJudge judge(m.b.vertices, m.b.indices, m.b.polygons, small_judge(cull_back_faces));
  std::uint64_t missed = 0;
  for (const auto c : cells) {
    const Box& box = vis.partition.cells[c];
    missed += judge.missed(judge.views(box, c, portal_viewpoints(vis.graph, box, c)), vis.polygon_pvs(c));
  }
  return missed;
}

}  // namespace walk::compiler::testing
