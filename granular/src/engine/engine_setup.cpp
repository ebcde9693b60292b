// Engine construction: validation, species tables, cell grid, wall and
// vertex registration, adding disks.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "contact_time.hpp"
#include "engine_impl.hpp"
#include "scene/errors.hpp"

namespace granular {

namespace {

// A disk may touch another or a wall to this depth (diameters) when added:
// explicit configurations are written with finite decimals.
constexpr double kAddOverlapTolerance = 1e-12;
// Cells register walls and vertices this much beyond the largest radius, so
// that round-off in the cell geometry cannot drop a contact.
constexpr double kRegistrationSlack = 1e-9;
// Drifting grid: columns beyond those the rectangle spans (it meets at
// most wnx + 1 of them at a time), so that the columns on its two sides,
// numbered modulo ncx, are never adjacent.
constexpr int kSpareColumns = 3;
// Drifting grid: relative margin of the columns over the largest diameter
// (covers the round-off of xi up to drift * t ~ 1e9 diameters).
constexpr double kDriftCellMargin = 1e-6;
// Drifting grid: a disk near a wall or vertex looks up the fixed grid's
// items again after travelling this far (diameters). Larger: fewer
// look-ups, longer lists.
constexpr double kWallLookAhead = 8.0;
// Drifting grid: side of the fixed look-up grid's cells (diameters, at
// least the cell side). Larger: a smaller table (fewer cache misses per
// look-up: 16 bytes a cell), longer lists near the walls.
constexpr double kSurfaceCell = 6.0;

double point_rect_distance(Vec2 q, double x0, double y0, double x1, double y1) {
  const double dx = std::max({x0 - q.x, 0.0, q.x - x1});
  const double dy = std::max({y0 - q.y, 0.0, q.y - y1});
  return std::hypot(dx, dy);
}

double point_segment_distance(Vec2 q, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double l2 = norm2(ab);
  double t = l2 > 0.0 ? dot(q - a, ab) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return norm(q - (a + t * ab));
}

// Liang-Barsky: does segment ab meet the rectangle?
bool segment_hits_rect(Vec2 a, Vec2 b, double x0, double y0, double x1, double y1) {
  double t0 = 0.0, t1 = 1.0;
  const double d[2] = {b.x - a.x, b.y - a.y};
  const double lo[2] = {x0 - a.x, y0 - a.y};
  const double hi[2] = {x1 - a.x, y1 - a.y};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0.0) {
      if (lo[k] > 0.0 || hi[k] < 0.0) return false;
      continue;
    }
    double ta = lo[k] / d[k], tb = hi[k] / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

double segment_rect_distance(Vec2 a, Vec2 b, double x0, double y0, double x1, double y1) {
  if (segment_hits_rect(a, b, x0, y0, x1, y1)) return 0.0;
  double d = std::min(point_rect_distance(a, x0, y0, x1, y1), point_rect_distance(b, x0, y0, x1, y1));
  for (const Vec2 c : {Vec2{x0, y0}, Vec2{x1, y0}, Vec2{x0, y1}, Vec2{x1, y1}})
    d = std::min(d, point_segment_distance(c, a, b));
  return d;
}

[[noreturn]] void bad(const std::string& msg) { throw scene::InputError("granular engine: " + msg); }

}  // namespace

void Engine::Impl::init(EngineConfig c) {
  cfg = std::move(c);
  if (!(cfg.xmax > cfg.xmin) || !(cfg.ymax > cfg.ymin)) bad("empty simulation rectangle");
  if (!std::isfinite(cfg.xmax - cfg.xmin) || !std::isfinite(cfg.ymax - cfg.ymin))
    bad("the simulation rectangle must be finite");
  if (cfg.species.empty()) bad("no species");
  ns = cfg.species.size();
  if (ns > 65535) bad("too many species");
  for (const Species& sp : cfg.species) {
    if (!(sp.radius > 0.0) || !(sp.mass > 0.0)) bad("species radius and mass must be positive");
    if (!(sp.restitution_wall >= 0.0 && sp.restitution_wall <= 1.0) ||
        !(sp.restitution_vertex >= 0.0 && sp.restitution_vertex <= 1.0))
      bad("restitution must lie in [0, 1]");
    radius.push_back(sp.radius);
    mass.push_back(sp.mass);
    e_wall.push_back(sp.restitution_wall);
    e_vertex.push_back(sp.restitution_vertex);
    max_diameter = std::max(max_diameter, 2.0 * sp.radius);
  }
  max_diameter = 0.0;
  for (double r : radius) max_diameter = std::max(max_diameter, 2.0 * r);
  if (cfg.restitution.empty()) {
    e_disk.assign(ns * ns, 1.0);
  } else {
    if (cfg.restitution.size() != ns * ns) bad("restitution matrix must be species x species");
    e_disk = cfg.restitution;
    for (std::size_t a = 0; a < ns; ++a)
      for (std::size_t b = 0; b < ns; ++b)
        if (e_disk[a * ns + b] != e_disk[b * ns + a]) bad("restitution matrix must be symmetric");
  }
  for (double e : e_disk)
    if (!(e >= 0.0 && e <= 1.0)) bad("restitution must lie in [0, 1]");
  if (!(cfg.tc >= 0.0)) bad("tc must be >= 0");
  if ((cfg.left == Face::periodic) != (cfg.right == Face::periodic) ||
      (cfg.bottom == Face::periodic) != (cfg.top == Face::periodic))
    bad("periodic faces come in pairs");
  periodic_x = cfg.left == Face::periodic;
  periodic_y = cfg.bottom == Face::periodic;
  if ((periodic_x && cfg.gravity.x != 0.0) || (periodic_y && cfg.gravity.y != 0.0)) {
    // Allowed: a periodic axis with a force along it is a forced flow.
  }
  lx = cfg.xmax - cfg.xmin;
  ly = cfg.ymax - cfg.ymin;
  drifting = cfg.grid_speed != 0.0;
  drift = cfg.grid_speed;
  if (!std::isfinite(drift)) bad("grid_speed must be finite");
  if (drifting && periodic_x) bad("a drifting cell grid (grid_speed) needs non-periodic x faces");
  // A drifting column's faces are at k w in xi = x - xmin - drift t, whose
  // round-off grows with t (~1e-12 d at drift t ~ 1e4): columns a hair
  // wider than a diameter keep every touching pair in adjacent columns.
  const double cell =
      std::max(max_diameter * (drifting ? 1.0 + kDriftCellMargin : 1.0), cfg.min_cell);
  // Checked as doubles, before the counts are cast to int.
  const double cells_x = std::floor(lx / cell) + (drifting ? kSpareColumns : 0),
               cells_y = std::floor(ly / cell);
  if (std::max(cells_x, cells_y) > kMaxCellsPerSide) {
    char count[32];
    std::snprintf(count, sizeof count, "%.0f", std::max(cells_x, cells_y));
    bad(std::string("the domain is ") + count +
        " cells (largest disk diameters) along a side; at most " +
        std::to_string(kMaxCellsPerSide) + " are supported: use larger disks or a smaller domain");
  }
  ncx = std::max(1, static_cast<int>(cells_x));
  ncy = std::max(1, static_cast<int>(cells_y));
  if ((periodic_x && ncx < 3) || (periodic_y && ncy < 3))
    bad("a periodic side must be at least 3 largest diameters long");
  const int columns = drifting ? ncx - kSpareColumns : ncx;  // spanning the rectangle
  cw = lx / columns;
  ch = ly / ncy;
  // The fixed look-up grid of walls and vertices: the cell grid itself, or
  // for a drifting grid coarse cells whose records stay in cache.
  wnx =
      drifting ? std::max(1, static_cast<int>(std::floor(lx / std::max(cell, kSurfaceCell)))) : ncx;
  wny =
      drifting ? std::max(1, static_cast<int>(std::floor(ly / std::max(cell, kSurfaceCell)))) : ncy;
  inv_wcw = wnx / lx;
  inv_wch = wny / ly;
  inv_cw = 1.0 / cw;
  inv_ncx = 1.0 / ncx;
  wrap_x = periodic_x || drifting;
  wrap_lx = periodic_x ? lx : 0.0;
  tiles_x = (static_cast<std::uint32_t>(ncx) + kTile - 1) / kTile;
  const std::uint32_t tiles_y = (static_cast<std::uint32_t>(ncy) + kTile - 1) / kTile;
  head.assign(static_cast<std::size_t>(tiles_x) * tiles_y * kTile * kTile, -1);

  for (const Wall& w : cfg.walls) {
    const Vec2 d = w.b - w.a;
    const double len = norm(d);
    if (!(len > 0.0)) bad("zero-length wall");
    if (w.restitution > 1.0) bad("wall restitution must lie in [0, 1]");
    const Vec2 t = d / len;
    walls.push_back({w.a, perp(t), t, len, w.restitution});
  }
  for (const Vertex& v : cfg.vertices)
    if (v.restitution > 1.0) bad("vertex restitution must lie in [0, 1]");
  register_surfaces();
}

// Walls and vertices, registered in every cell of the fixed grid a disk
// centre in which could touch them (fixed cell grid), or could touch them
// before travelling the cell's wall_clear (drifting grid).
void Engine::Impl::register_surfaces() {
  const std::size_t ncell = static_cast<std::size_t>(wnx) * static_cast<std::size_t>(wny);
  const double wcw = lx / wnx, wch = ly / wny;
  const double radius_max = 0.5 * max_diameter;
  const auto cell_rect = [&](std::size_t c, double& x0, double& y0, double& x1, double& y1) {
    const auto cx = static_cast<double>(c % static_cast<std::size_t>(wnx));
    const auto cy = static_cast<double>(c / static_cast<std::size_t>(wnx));
    x0 = cfg.xmin + cx * wcw;
    x1 = cfg.xmin + (cx + 1) * wcw;
    y0 = cfg.ymin + cy * wch;
    y1 = cfg.ymin + (cy + 1) * wch;
  };
  const auto wall_distance = [&](std::size_t k, double x0, double y0, double x1, double y1) {
    return segment_rect_distance(cfg.walls[k].a, cfg.walls[k].b, x0, y0, x1, y1);
  };
  const auto vertex_distance = [&](std::size_t k, double x0, double y0, double x1, double y1) {
    return point_rect_distance(cfg.vertices[k].p, x0, y0, x1, y1);
  };
  // Reach from each cell: the largest radius (fixed grid), plus the
  // distance a disk may travel before it must look again (drifting grid):
  // at least kWallLookAhead, and in cells far from every item the whole
  // clearance, so that a disk in the open stream rarely looks at all.
  std::vector<double> reach(ncell, radius_max + kRegistrationSlack);
  surfaces.clear();
  if (cfg.walls.empty() && cfg.vertices.empty()) return;
  surfaces.assign(ncell + 1, detail::SurfaceCell{});
  if (drifting) {
    for (std::size_t c = 0; c < ncell; ++c) {
      double x0, y0, x1, y1;
      cell_rect(c, x0, y0, x1, y1);
      double nearest = detail::kNever;
      for (std::size_t k = 0; k < cfg.walls.size(); ++k)
        nearest = std::min(nearest, wall_distance(k, x0, y0, x1, y1));
      for (std::size_t k = 0; k < cfg.vertices.size(); ++k)
        nearest = std::min(nearest, vertex_distance(k, x0, y0, x1, y1));
      // The nearest item itself lies beyond the reach unless within kWallLookAhead.
      const double clear =
          std::max(kWallLookAhead, nearest - radius_max - 2.0 * kRegistrationSlack);
      float stored = static_cast<float>(clear);
      if (static_cast<double>(stored) > clear)
        stored = std::nextafter(stored, 0.0f);  // never beyond
      surfaces[c].clear = stored;
      reach[c] = radius_max + static_cast<double>(stored) + kRegistrationSlack;
    }
  }
  const auto register_all = [&](auto&& dist, std::size_t count,
                                std::int32_t detail::SurfaceCell::*first,
                                std::vector<std::int32_t>& list) {
    list.clear();
    for (std::size_t c = 0; c < ncell; ++c) {
      surfaces[c].*first = static_cast<std::int32_t>(list.size());
      double x0, y0, x1, y1;
      cell_rect(c, x0, y0, x1, y1);
      for (std::size_t k = 0; k < count; ++k)
        if (dist(k, x0, y0, x1, y1) <= reach[c]) list.push_back(static_cast<std::int32_t>(k));
    }
    surfaces[ncell].*first = static_cast<std::int32_t>(list.size());
  };
  register_all(wall_distance, cfg.walls.size(), &detail::SurfaceCell::walls, wall_list);
  register_all(vertex_distance, cfg.vertices.size(), &detail::SurfaceCell::vertices, vertex_list);
}

// Does a disk of `species` at r overlap (deeper than tol) any disk, wall or
// vertex, or lie outside a closed face?
bool Engine::Impl::overlaps(Vec2 r, int species, double tol, std::int32_t skip) const {
  const double rad = radius[static_cast<std::size_t>(species)];
  if (!(r.x >= cfg.xmin && r.x <= cfg.xmax && r.y >= cfg.ymin && r.y <= cfg.ymax)) return true;
  const int c = cell_of(r.x, r.y);
  const Vec2 g = cfg.gravity;
  Block b;
  block_of(c, b);
  for (int m = 0; m < b.n; ++m) {
    for (std::int32_t k = head[b.head[m]]; k >= 0; k = p[k].next) {
      if (k == skip) continue;
      const Particle& o = p[k];
      const double dt = now - o.t;
      const double ox = o.x + o.vx * dt + 0.5 * g.x * dt * dt + b.shx[m];
      const double oy = o.y + o.vy * dt + 0.5 * g.y * dt * dt + b.shy[m];
      const double sig = rad + radius[o.species] - tol;
      if ((r.x - ox) * (r.x - ox) + (r.y - oy) * (r.y - oy) < sig * sig) return true;
    }
  }
  if (surfaces.empty()) return false;
  const std::size_t lc = drifting ? wall_cell(r.x, r.y) : linear_cell(c);
  for (std::int32_t k = surfaces[lc].walls; k < surfaces[lc + 1].walls; ++k) {
    const Wall& w = cfg.walls[wall_list[k]];
    if (point_segment_distance(r, w.a, w.b) < rad - tol) return true;
  }
  for (std::int32_t k = surfaces[lc].vertices; k < surfaces[lc + 1].vertices; ++k)
    if (norm(r - cfg.vertices[vertex_list[k]].p) < rad - tol) return true;
  return false;
}

std::int32_t Engine::Impl::add_slot(Vec2 r, Vec2 v, int species) {
  std::int32_t i;
  std::uint32_t count = 0;
  if (!free_slots.empty()) {
    i = free_slots.back();
    free_slots.pop_back();
    count = p[i].count + 1;  // stale predictions naming the slot stay stale
  } else {
    i = static_cast<std::int32_t>(p.size());
    p.push_back({});
    s.push_back({});
    if (drifting) timer_t.push_back(detail::kNever);
  }
  p[i] = Particle{r.x, r.y, v.x, v.y, now, -detail::kNever, count, -1, 0,
                  static_cast<std::uint16_t>(species), 1};
  // The version carries over, so that calendar entries of the slot's
  // previous occupant stay stale.
  const std::uint32_t qver = s[i].qver + 1;
  s[i] = detail::Slot{detail::kNever, detail::kNever, -1, 0, detail::EventType::none, 0, 0, qver};
  cell_insert(i, cell_of(r.x, r.y));
  integrate_energy();
  energy += 0.5 * mass[static_cast<std::size_t>(species)] * norm2(v);
  if (started) {
    predict(i);
    schedule(i);
  }
  return i;
}

Engine::Engine(EngineConfig cfg) : impl_(std::make_unique<Impl>()) { impl_->init(std::move(cfg)); }
Engine::~Engine() = default;
Engine::Engine(Engine&&) noexcept = default;
Engine& Engine::operator=(Engine&&) noexcept = default;

namespace {

// Slot of the new disk, or -1 when it would overlap.
std::int32_t add_checked(Engine::Impl& m, Vec2 r, Vec2 v, int species) {
  if (species < 0 || static_cast<std::size_t>(species) >= m.ns) bad("unknown species");
  if (!std::isfinite(r.x) || !std::isfinite(r.y) || !std::isfinite(v.x) || !std::isfinite(v.y))
    bad("non-finite particle state");
  if (m.overlaps(r, species, kAddOverlapTolerance, -1)) return -1;
  ++m.st.inserted;
  return m.add_slot(r, v, species);
}

}  // namespace

bool Engine::try_add(Vec2 r, Vec2 v, int species) { return add_checked(*impl_, r, v, species) >= 0; }

std::size_t Engine::add(Vec2 r, Vec2 v, int species) {
  const std::int32_t i = add_checked(*impl_, r, v, species);
  if (i < 0) {
    std::ostringstream msg;
    msg.precision(17);
    msg << "particle at (" << r.x << ", " << r.y
        << ") overlaps another particle or a wall, or lies outside the box";
    bad(msg.str());
  }
  return static_cast<std::size_t>(i);
}

}  // namespace granular
