#pragma once
// A generated office tower of axial polygons for the ray-casting benchmark and tests: floors of rooms on a
// grid, each room with a tiled floor and ceiling, two walls (thick boxes with a door gap) and desks.
// The default makes 20 floors x 80 rooms x 74 quads = 118,400 axial polygons (236,800 triangles).
#include <vector>

#include "compiler/raycast/triangle_bvh.hpp"

namespace walk::bench {

struct TowerOptions {
  int floors = 20;
  int rooms_x = 10, rooms_y = 8;
  double room_x = 4.0, room_y = 5.0, storey = 3.6;  // metres
  double wall = 0.15, door = 1.0, ceiling = 3.0;
  int tiles = 4;  // floor and ceiling tiles per side
  int desks = 3;
};

class TowerBuilder {
 public:
  std::vector<compiler::Triangle> triangles;
  std::uint32_t polygons = 0;

  // Quad p0 p1 p2 p3, counter-clockwise about its front normal.
  void quad(const model::Vec3& p0, const model::Vec3& p1, const model::Vec3& p2, const model::Vec3& p3) {
    triangles.push_back({p0, p1, p2, polygons});
    triangles.push_back({p0, p2, p3, polygons});
    ++polygons;
  }
  // Closed box, fronts outward.
  void box(const model::Vec3& l, const model::Vec3& h) {
    quad({l.x, l.y, l.z}, {l.x, h.y, l.z}, {h.x, h.y, l.z}, {h.x, l.y, l.z});  // bottom, -z
    quad({l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z});  // top, +z
    quad({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z});  // -y
    quad({l.x, h.y, l.z}, {l.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, l.z});  // +y
    quad({l.x, l.y, l.z}, {l.x, l.y, h.z}, {l.x, h.y, h.z}, {l.x, h.y, l.z});  // -x
    quad({h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z}, {h.x, l.y, h.z});  // +x
  }
};

inline std::vector<compiler::Triangle> office_tower(const TowerOptions& o = {},
                                                    std::size_t* polygons = nullptr) {
  TowerBuilder b;
  for (int f = 0; f < o.floors; ++f) {
    const double z0 = f * o.storey;
    for (int i = 0; i < o.rooms_x; ++i) {
      for (int j = 0; j < o.rooms_y; ++j) {
        const double x0 = i * o.room_x, y0 = j * o.room_y, x1 = x0 + o.room_x, y1 = y0 + o.room_y;
        const double tx = o.room_x / o.tiles, ty = o.room_y / o.tiles;
        for (int a = 0; a < o.tiles; ++a) {
          for (int c = 0; c < o.tiles; ++c) {
            const double u0 = x0 + a * tx, u1 = u0 + tx, v0 = y0 + c * ty, v1 = v0 + ty;
            b.quad({u0, v0, z0}, {u1, v0, z0}, {u1, v1, z0}, {u0, v1, z0});  // floor, up
            const double zc = z0 + o.ceiling;
            b.quad({u0, v0, zc}, {u0, v1, zc}, {u1, v1, zc}, {u1, v0, zc});  // ceiling, down
          }
        }
        // Wall on the room's +x side (door gap in the middle) and on its +y side.
        const double w = o.wall / 2, zt = z0 + o.ceiling;
        const double my = (y0 + y1) / 2, mx = (x0 + x1) / 2;
        b.box({x1 - w, y0, z0}, {x1 + w, my - o.door / 2, zt});
        b.box({x1 - w, my + o.door / 2, z0}, {x1 + w, y1, zt});
        b.box({x0, y1 - w, z0}, {mx - o.door / 2, y1 + w, zt});
        b.box({mx + o.door / 2, y1 - w, z0}, {x1, y1 + w, zt});
        for (int d = 0; d < o.desks; ++d) {
          const double dx = x0 + 0.4 + d * 1.2, dy = y0 + 0.5;
          b.box({dx, dy, z0 + 0.72}, {dx + 1.0, dy + 0.7, z0 + 0.75});
        }
      }
    }
  }
  if (polygons) *polygons = b.polygons;
  return std::move(b.triangles);
}

}  // namespace walk::bench
