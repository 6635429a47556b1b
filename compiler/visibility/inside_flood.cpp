#include "compiler/visibility/inside_flood.hpp"

#include <algorithm>

#include "compiler/partition/axial_cover.hpp"

namespace walk::compiler {
namespace {

model::Vec3 centre_of(const Winding& w) {
  model::Vec3 c{0.0};
  for (const auto& p : w) c += p;
  return w.empty() ? c : c / double(w.size());
}

// Can a person pass the portal? Its outline's box is at least kFloodMinWidth across both ways in its plane.
bool walkable(const Portal& p) {
  const int u = u_axis(p.axis), v = v_axis(p.axis);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (const auto& q : p.hull)
    for (int k = 0; k < 2; ++k) {
      lo[k] = std::min(lo[k], q[k == 0 ? u : v]);
      hi[k] = std::max(hi[k], q[k == 0 ? u : v]);
    }
  return hi[0] - lo[0] >= kFloodMinWidth && hi[1] - lo[1] >= kFloodMinWidth;
}

}  // namespace

void flood_portals(const PortalGraph& g, std::vector<char>& reached, std::vector<std::uint32_t> queue,
                   const std::function<bool(const Portal&)>& passes,
                   const std::function<void(std::uint32_t, std::uint32_t, std::uint32_t)>& entered) {
  for (std::size_t h = 0; h < queue.size(); ++h) {
    const std::uint32_t c = queue[h];
    for (const auto id : g.cell_portals[c]) {
      const Portal& p = g.portals[id];
      if (!passes(p)) continue;
      const std::uint32_t d = p.back == c ? p.front : p.back;
      if (reached[d]) continue;
      reached[d] = 1;
      if (entered) entered(d, id, c);
      queue.push_back(d);
    }
  }
}

InsideFlood flood_inside(const Partition& part, const PortalGraph& g, std::span<const model::Vec3> seeds,
                         const std::function<std::uint32_t(const model::Vec3&)>& locate_seed,
                         bool over_regions, const std::function<bool(const Leak&)>& confirm) {
  InsideFlood f;
  const std::size_t n = part.cells.size();
  f.seeds = seeds.size();
  if (seeds.empty()) {
    f.inside.assign(n, 1);
    return f;
  }
  f.inside.assign(n, 0);
  // Breadth first, so each leak's path is a shortest one in portals.
  std::vector<std::uint32_t> via(n, kOutside);  // portal the flood came in through
  std::vector<std::uint32_t> seed_of(n, 0);
  std::vector<std::uint32_t> queue;
  for (std::size_t s = 0; s < seeds.size(); ++s) {
    const std::uint32_t c = locate_seed ? locate_seed(seeds[s]) : locate(part.nodes, seeds[s]);
    if (c >= n || f.inside[c]) continue;
    f.inside[c] = 1;
    seed_of[c] = static_cast<std::uint32_t>(s);
    queue.push_back(c);
  }
  flood_portals(
      g, f.inside, std::move(queue),
      [&](const Portal& p) {
        return !p.glazed && walkable(p) && (!over_regions || (p.forward && p.backward));
      },
      [&](std::uint32_t d, std::uint32_t portal, std::uint32_t from) {
        via[d] = portal;
        seed_of[d] = seed_of[from];
      });
  for (const Leak& leak : g.leaks) {
    if (!f.inside[leak.cell]) continue;
    if (confirm && !confirm(leak)) {
      ++f.unconfirmed;
      continue;
    }
    LeakPath path;
    path.area = leak.area;
    path.points.push_back(leak.where);
    for (std::uint32_t c = leak.cell; via[c] != kOutside;) {
      const Portal& p = g.portals[via[c]];
      path.points.push_back(centre_of(p.hull));
      c = p.back == c ? p.front : p.back;
    }
    path.points.push_back(seeds[seed_of[leak.cell]]);
    std::reverse(path.points.begin(), path.points.end());
    f.leaks.push_back(std::move(path));
  }
  std::sort(f.leaks.begin(), f.leaks.end(),
            [](const LeakPath& a, const LeakPath& b) { return a.area > b.area; });
  if (over_regions) {
    // A head leans where feet cannot go: the regions next to the walk through a portal too narrow to pass
    // (a niche, a gap beside a pillar; glazed or not, as sight passes glass) are on it too, when sight
    // passes into them (not through the back of a wall into a pocket the solids leave). Regions reach the
    // void only through such gaps when solids leave one, so one step, not a flood.
    const std::vector<char> walked = f.inside;
    for (const Portal& p : g.portals)
      if ((walked[p.back] && p.forward) || (walked[p.front] && p.backward))
        f.inside[p.back] = f.inside[p.front] = 1;
  }
  return f;
}

}  // namespace walk::compiler
