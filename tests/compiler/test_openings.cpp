// Cutting doors, passages and windows out of their walls, on the real EnergyPlus house and small cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "compiler/geometry/openings.hpp"
#include "compiler/import/dxf_reader.hpp"
#include "test_openings_util.hpp"

namespace walk::compiler {
namespace test_openings {  // named, not anonymous: the suite compiles as unity batches

using model::Polygon;
using model::Role;
using model::Vec3;
using test::area_vector;
using test::centroid;
using test::inside_polygon;
using test::polygon_area;

const std::string kHouse = std::string(WALK_SHARED_DATA) + "/eplus-house-doors/house.dxf";
const std::string kOffice = std::string(WALK_SHARED_DATA) + "/eplus-medium-office/refbldg_medium_office.dxf";

bool contains(const std::string& s, const char* part) {
  return s.find(part) != std::string::npos;
}

// Roles as the scene config assigns them for EnergyPlus files; the north arrow (layer "1") is dropped.
model::Model load_with_roles(const std::string& path) {
  model::Model m = read_dxf(path);
  std::vector<Polygon> kept;
  for (auto& p : m.polygons) {
    if (m.groups[p.group] == "1") continue;
    if (p.color == 45 || contains(p.name, "_DOOR") || contains(p.name, "_HOLE"))
      p.role = Role::Opening;
    else if (contains(p.name, "_WIN") || p.color == 143)
      p.role = Role::Glass;
    kept.push_back(std::move(p));
  }
  m.polygons = std::move(kept);
  return m;
}

double opaque_area(const model::Model& m) {
  double area = 0.0;
  for (const auto& p : m.polygons) area += p.role == Role::Opaque ? polygon_area(p) : 0.0;
  return area;
}

bool same_face(const Polygon& a, const Polygon& b) {
  if (a.vertices.size() != b.vertices.size()) return false;
  for (const auto& v : a.vertices) {
    const bool found = std::any_of(b.vertices.begin(), b.vertices.end(),
                                   [&](const Vec3& w) { return glm::distance(v, w) < 1e-4; });
    if (!found) return false;
  }
  return true;
}

// Opaque faces of `m` parallel to `cutter`, holding its centre (projected) inside their boundary, and nearest
// to its plane: on it (within 2 mm) for doors and passages; up to 0.3 m away for windows, which the house
// export places 0.13 m behind their wall's plane.
std::size_t host_count(const model::Model& m, const Polygon& cutter) {
  const Vec3 c = centroid(cutter.vertices);
  const Vec3 nc = glm::normalize(area_vector(cutter.vertices));
  const double reach = cutter.role == Role::Glass ? 0.3 : 0.002;
  std::vector<double> distances;
  for (const auto& host : m.polygons) {
    if (host.role != Role::Opaque) continue;
    const Vec3 n = glm::normalize(area_vector(host.vertices));
    if (std::abs(std::abs(glm::dot(n, nc)) - 1.0) > 1e-6) continue;
    const double d = glm::dot(c - host.vertices[0], n);
    if (std::abs(d) <= reach && inside_polygon(host, c - d * n, 1e-9)) distances.push_back(std::abs(d));
  }
  if (distances.empty()) return 0;
  const double nearest = *std::min_element(distances.begin(), distances.end());
  return static_cast<std::size_t>(
      std::count_if(distances.begin(), distances.end(), [&](double d) { return d <= nearest + 0.002; }));
}

TEST(Openings, HouseDoorsHolesAndWindowsAreCut) {
  model::Model m = load_with_roles(kHouse);
  const double before = opaque_area(m);

  // Expected: each distinct door/hole/window (zone copies of one door count once) removes its area from
  // every coplanar wall copy that holds it.
  std::vector<const Polygon*> distinct;
  std::size_t openings = 0, glass = 0;
  for (const auto& p : m.polygons) {
    if (p.role == Role::Opaque) continue;
    (p.role == Role::Opening ? openings : glass) += 1;
    const bool seen =
        std::any_of(distinct.begin(), distinct.end(), [&](const Polygon* d) { return same_face(*d, p); });
    if (!seen) distinct.push_back(&p);
  }
  ASSERT_EQ(openings, 17u + 7u);
  ASSERT_EQ(glass, 25u);
  double expected_cut = 0.0;
  std::vector<std::string> hostless;
  for (const Polygon* c : distinct) {
    const std::size_t hosts = host_count(m, *c);
    if (hosts == 0) hostless.push_back(c->name);
    if (c->role == Role::Glass) {
      EXPECT_EQ(hosts, 1u) << c->name;  // all windows are in exterior walls or the roof
    }
    expected_cut += polygon_area(*c) * static_cast<double>(hosts);
  }
  EXPECT_TRUE(hostless.empty()) << hostless.size() << " without host, e.g. " << hostless.front();

  std::vector<Polygon> doors;
  for (const auto& p : m.polygons) {
    if (p.role == Role::Opening) doors.push_back(p);
  }

  const OpeningStats stats = cut_openings(m);
  EXPECT_EQ(stats.unmatched, 0u);
  EXPECT_EQ(stats.openings_cut, openings);
  EXPECT_EQ(stats.glass_cut, glass);
  EXPECT_EQ(stats.glass_inset, glass);  // every window in this export sits 0.13 m behind its wall or roof
  EXPECT_GT(stats.hosts_cut, 0u);

  const double after = opaque_area(m);
  EXPECT_NEAR(before - after, expected_cut, 1e-6 * expected_cut) << "before " << before << " after " << after;

  std::size_t glass_left = 0;
  for (const auto& p : m.polygons) {
    EXPECT_NE(p.role, Role::Opening) << p.name;
    glass_left += p.role == Role::Glass ? 1 : 0;
    // Cut walls keep the host's orientation: outer boundary counter-clockwise about the original normal.
    EXPECT_GT(polygon_area(p), 0.0) << p.name;
  }
  EXPECT_EQ(glass_left, glass);

  for (const auto& door : doors) {
    const Vec3 middle = centroid(door.vertices);
    for (const auto& p : m.polygons) {
      if (p.role == Role::Opaque) {
        EXPECT_FALSE(inside_polygon(p, middle, 0.002)) << door.name << " in " << p.name;
      }
    }
    // A point on the wall just beside the door (left or right of it, at mid height) is still wall.
    const Vec3 up{0.0, 0.0, 1.0};
    const Vec3 n = glm::normalize(area_vector(door.vertices));
    const Vec3 side = glm::normalize(glm::cross(up, n));
    double half_width = 0.0;
    for (const auto& v : door.vertices)
      half_width = std::max(half_width, std::abs(glm::dot(v - middle, side)));
    bool wall_beside = false;
    for (double sign : {-1.0, 1.0}) {
      const Vec3 beside = middle + side * (sign * (half_width + 0.05));
      for (const auto& p : m.polygons) {
        wall_beside = wall_beside || (p.role == Role::Opaque && inside_polygon(p, beside, 0.002));
      }
    }
    EXPECT_TRUE(wall_beside) << door.name;
  }
}

TEST(Openings, CutWallsKeepOrientationAndHoleWinding) {
  model::Model m = load_with_roles(kHouse);
  std::vector<Vec3> normal_by_line(100000, Vec3{0.0});
  for (const auto& p : m.polygons) normal_by_line[p.source_line] = glm::normalize(area_vector(p.vertices));
  (void)cut_openings(m);
  std::size_t with_holes = 0;
  for (const auto& p : m.polygons) {
    const Vec3 original = normal_by_line[p.source_line];
    EXPECT_GT(glm::dot(area_vector(p.vertices), original), 0.0) << p.name;
    for (const auto& hole : p.holes) EXPECT_LT(glm::dot(area_vector(hole), original), 0.0) << p.name;
    with_holes += p.holes.empty() ? 0 : 1;
  }
  EXPECT_GT(with_holes, 0u);
}

TEST(Openings, OfficeWindowsFindTheirWalls) {
  model::Model m = load_with_roles(kOffice);
  double window_area = 0.0;
  for (const auto& p : m.polygons) window_area += p.role == Role::Glass ? polygon_area(p) : 0.0;
  const double before = opaque_area(m);
  const OpeningStats stats = cut_openings(m);
  EXPECT_EQ(stats.glass_cut, 12u);
  EXPECT_EQ(stats.unmatched, 0u);
  EXPECT_EQ(stats.hosts_cut, 12u);
  EXPECT_EQ(stats.glass_inset, 0u);  // this export puts windows on the wall plane
  EXPECT_NEAR(before - opaque_area(m), window_area, 1e-6 * window_area);
}

Polygon rectangle(double x0, double z0, double x1, double z1, Role role) {
  Polygon p;  // in the plane y = 0, normal -y (counter-clockwise seen from -y)
  p.vertices = {{x0, 0.0, z0}, {x1, 0.0, z0}, {x1, 0.0, z1}, {x0, 0.0, z1}};
  p.role = role;
  return p;
}

TEST(Openings, DoorAtWallEdgeMakesNotchAndSplitWall) {
  model::Model m;
  m.polygons.push_back(rectangle(0, 0, 4, 3, Role::Opaque));
  m.polygons.push_back(rectangle(1, -1, 2, 4, Role::Opening));  // taller than the wall: splits it in two
  const OpeningStats stats = cut_openings(m);
  EXPECT_EQ(stats.openings_cut, 1u);
  ASSERT_EQ(m.polygons.size(), 2u);
  EXPECT_NEAR(polygon_area(m.polygons[0]) + polygon_area(m.polygons[1]), 12.0 - 3.0, 1e-9);
}

// The groups of the faces cut out of a wall are its doors' and windows' frames; a face that found no wall
// (here a pane standing free) names none.
TEST(Openings, FrameGroupsAreTheGroupsOfTheFacesCut) {
  model::Model m;
  m.groups = {"wall", "door 1", "window 1", "glass screen"};
  m.polygons.push_back(rectangle(0, 0, 6, 3, Role::Opaque));
  m.polygons.push_back(rectangle(1, 0, 2, 2, Role::Opening));
  m.polygons.back().group = 1;
  m.polygons.push_back(rectangle(3, 1, 5, 2, Role::Glass));
  m.polygons.back().group = 2;
  Polygon free_pane = rectangle(1, 1, 2, 2, Role::Glass);
  for (auto& v : free_pane.vertices) v.y += 1.0;  // a metre in front of the wall
  free_pane.group = 3;
  m.polygons.push_back(free_pane);
  const OpeningStats stats = cut_openings(m);
  EXPECT_EQ(stats.unmatched, 1u);
  EXPECT_EQ(stats.frame_groups, (std::vector<std::uint32_t>{1, 2}));
}

TEST(Openings, FarOrTiltedFacesAreNotCut) {
  model::Model m;
  m.polygons.push_back(rectangle(0, 0, 4, 3, Role::Opaque));
  Polygon off = rectangle(1, 1, 2, 2, Role::Opening);
  for (auto& v : off.vertices) v.y += 0.01;  // 10 mm in front of the wall: not on it
  m.polygons.push_back(off);
  Polygon touching = rectangle(4, 0, 5, 3, Role::Glass);  // shares only an edge
  m.polygons.push_back(touching);
  const OpeningStats stats = cut_openings(m);
  EXPECT_EQ(stats.unmatched, 2u);
  EXPECT_EQ(stats.hosts_cut, 0u);
  ASSERT_EQ(m.polygons.size(), 3u);
  EXPECT_EQ(m.polygons[0].vertices, rectangle(0, 0, 4, 3, Role::Opaque).vertices);  // untouched, bit for bit
}

// Cutters find their hosts through a grid of 2 m cells: a door across a cell boundary at negative
// coordinates, a window set back 0.25 m across the wall's plane (y = 0, a cell boundary), both on an 80 m
// wall spanning 40 cells, far from the origin; a wall in front of the window by more than its inset, and
// furniture beside the door (in the door's cells, not in its plane), take nothing.
TEST(Openings, CuttersFindTheirHostsAcrossGridCells) {
  for (const double offset : {0.0, -500.25}) {
    model::Model m;
    auto shifted = [&](Polygon p) {
      for (auto& v : p.vertices) v.x += offset;
      return p;
    };
    m.polygons.push_back(shifted(rectangle(-40, 0, 40, 3, Role::Opaque)));
    m.polygons.push_back(shifted(rectangle(-1, 0, 1, 2, Role::Opening)));
    Polygon window = shifted(rectangle(30.2, 1, 31.8, 2, Role::Glass));
    for (auto& v : window.vertices) v.y -= 0.25;  // set back, in the next cell across the wall's plane
    m.polygons.push_back(window);
    Polygon screen = shifted(rectangle(30, 0.5, 32, 2.5, Role::Opaque));
    for (auto& v : screen.vertices) v.y += 0.6;  // a wall 0.6 m in front of the window's wall
    m.polygons.push_back(screen);
    // A ground plane 200 km long, over more grid cells than hold cutters: still cut (a notch at the door).
    Polygon ground = shifted(rectangle(-100000, -1, 100000, 0.5, Role::Opaque));
    for (auto& v : ground.vertices) v.y = 0.0;
    m.polygons.push_back(ground);
    Polygon table = shifted(rectangle(1.5, 0, 2.5, 0.8, Role::Opaque));
    for (auto& v : table.vertices) v.y -= 0.4;
    m.polygons.push_back(table);
    const OpeningStats stats = cut_openings(m);
    EXPECT_EQ(stats.openings_cut, 1u) << offset;
    EXPECT_EQ(stats.glass_cut, 1u) << offset;
    EXPECT_EQ(stats.glass_inset, 1u) << offset;
    EXPECT_EQ(stats.hosts_cut, 2u) << "only the long wall and the ground: " << offset;
    EXPECT_EQ(stats.unmatched, 0u) << offset;
    double wall_area = 0.0;
    for (const auto& p : m.polygons)
      if (p.role == Role::Opaque && std::all_of(p.vertices.begin(), p.vertices.end(), [](const Vec3& v) {
            return v.y == 0.0 && v.z >= 0.0 && std::abs(v.x) < 1000.0;
          }))
        wall_area += polygon_area(p);
    EXPECT_NEAR(wall_area, 240.0 - 2.0 * 2.0 - 1.6 * 1.0, 1e-6) << offset;
  }
}

TEST(Openings, OppositeWindingCopiesCutBoth) {
  model::Model m;
  m.polygons.push_back(rectangle(0, 0, 4, 3, Role::Opaque));
  Polygon back = rectangle(0, 0, 4, 3, Role::Opaque);
  std::reverse(back.vertices.begin(), back.vertices.end());
  m.polygons.push_back(back);
  Polygon door = rectangle(1, 0.5, 2, 2.5, Role::Opening);
  m.polygons.push_back(door);
  std::reverse(door.vertices.begin(), door.vertices.end());
  m.polygons.push_back(door);
  const OpeningStats stats = cut_openings(m);
  EXPECT_EQ(stats.openings_cut, 2u);
  EXPECT_EQ(stats.hosts_cut, 2u);
  ASSERT_EQ(m.polygons.size(), 2u);
  for (const auto& p : m.polygons) {
    ASSERT_EQ(p.holes.size(), 1u);
    EXPECT_NEAR(polygon_area(p), 12.0 - 2.0, 1e-9);
  }
  EXPECT_LT(area_vector(m.polygons[0].vertices).y, 0.0);
  EXPECT_GT(area_vector(m.polygons[1].vertices).y, 0.0);
}

}  // namespace test_openings
}  // namespace walk::compiler
