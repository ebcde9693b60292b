#include <algorithm>
#include <cmath>

#include "granular/flow_setup.hpp"

namespace granular {

namespace {

// Clipped pieces shorter than this (scene units, relative to the body) are
// dropped: they are touch points (a vertex on the symmetry plane), not walls.
constexpr double kMinPiece = 1e-12;

// Liang-Barsky: the part t in [t0, t1] of a + t (b - a) inside the closed
// rectangle; false when none.
bool clip(scene::Vec2 a, scene::Vec2 b, const scene::Domain& d, double& t0, double& t1) {
  t0 = 0.0;
  t1 = 1.0;
  const scene::Vec2 dd = b - a;
  const double p[4] = {-dd.x, dd.x, -dd.y, dd.y};
  const double q[4] = {a.x - d.xmin, d.xmax - a.x, a.y - d.ymin, d.ymax - a.y};
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0) return false;
      continue;
    }
    const double r = q[k] / p[k];
    if (p[k] < 0.0) t0 = std::max(t0, r);
    else t1 = std::min(t1, r);
  }
  return t1 > t0;
}

// A piece running along a face of the domain is not a wall: on the
// outflow/side faces disks leave anyway, on the symmetry plane the mirror
// already is one.
bool along_boundary(scene::Vec2 a, scene::Vec2 b, const scene::Domain& d) {
  return (a.x == d.xmin && b.x == d.xmin) || (a.x == d.xmax && b.x == d.xmax) ||
         (a.y == d.ymin && b.y == d.ymin) || (a.y == d.ymax && b.y == d.ymax);
}

}  // namespace

std::vector<std::vector<scene::Vec2>> body_chains(const scene::BodyGeometry& g, const scene::Domain& d) {
  // The outline is counter-clockwise (body on the left); the engine wants the
  // body on the right, so walk it backwards.
  std::vector<scene::Vec2> cw(g.polyline.rbegin(), g.polyline.rend());
  const std::size_t n = cw.size();
  auto inside = [&](scene::Vec2 p) { return p.x >= d.xmin && p.x <= d.xmax && p.y >= d.ymin && p.y <= d.ymax; };
  std::size_t start = n;
  for (std::size_t i = 0; i < n; ++i)
    if (!inside(cw[i])) {
      start = i;
      break;
    }
  if (start == n) {  // wholly inside: one closed loop
    std::vector<scene::Vec2> loop = cw;
    loop.push_back(cw.front());
    return {loop};
  }
  std::vector<std::vector<scene::Vec2>> chains;
  std::vector<scene::Vec2> cur;
  auto flush = [&]() {
    if (cur.size() >= 2) chains.push_back(cur);
    cur.clear();
  };
  for (std::size_t k = 0; k < n; ++k) {
    const scene::Vec2 a = cw[(start + k) % n], b = cw[(start + k + 1) % n];
    double t0 = 0, t1 = 0;
    if (!clip(a, b, d, t0, t1)) {
      flush();
      continue;
    }
    // Snap to the exact vertices where the piece is unclipped, so joints match.
    const scene::Vec2 pa = t0 > 0.0 ? a + t0 * (b - a) : a;
    const scene::Vec2 pb = t1 < 1.0 ? a + t1 * (b - a) : b;
    if (norm(pb - pa) < kMinPiece * g.length || along_boundary(pa, pb, d)) {
      flush();
      continue;
    }
    if (cur.empty() || !(cur.back() == pa)) {
      flush();
      cur.push_back(pa);
    }
    cur.push_back(pb);
    if (t1 < 1.0) flush();
  }
  flush();
  return chains;
}

}  // namespace granular
