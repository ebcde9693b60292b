// The event loop: prediction, processing, cells. See docs/granular_engine.md.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "contact_time.hpp"
#include "engine_impl.hpp"
#include "prefetch.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"

namespace granular {

using detail::EventType;
using detail::kNever;

namespace {

// An overlap deeper than this (in diameters) is not round-off: processing
// it counts as a recovery. Round-off overlaps are ~1e-15 per event.
constexpr double kRecoveryTolerance = 1e-9;
// Contact points this far past a segment end still count as hitting the
// segment, so that round-off cannot open a gap at the joint of two
// collinear or concave segments.
constexpr double kSegmentEndSlack = 1e-9;
// Interrupt polling period (events).
constexpr std::uint64_t kPollMask = 1023;
// Inelastic collapse: with a restitution near 0 a cluster of disks collides
// infinitely often in a finite time, so simulated time stops advancing and
// the run never ends. It is recognised from the event rate: every
// kCollapseWindow events, the events per disk per unit simulated time are
// compared with kCollapseEventRate. Healthy systems stay below ~1e4 (a
// dense gas at nu = 0.6, mean free path ~0.05 d, thermal speeds up to ~100
// sqrt(T/m) at Mach 50); a collapsing one exceeds any bound.
constexpr std::uint64_t kCollapseWindow = std::uint64_t{1} << 20;
constexpr double kCollapseEventRate = 1e7;
// Calendar look-ahead of the four prefetch stages, in calendar entries
// (stale ones included): each stage one or two events (~0.3 us each at
// N = 10^6) behind the previous one, so that the loads it builds on
// (~0.15 us from memory) have arrived. Distances from 4/2/1/1 to 24/12/6/3
// measure alike; these were best by a hair.
constexpr std::size_t kPrefetchRecords = 8;
constexpr std::size_t kPrefetchPartner = 4;
constexpr std::size_t kPrefetchNeighbours = 2;
constexpr std::size_t kPrefetchMore = 1;
// Systems whose particle arrays outgrow this many bytes get the full
// look-ahead (stages two to four); smaller ones live in cache, where those
// stages cost more work than the misses they hide (measured crossover on
// the benchmark host: ~2e5 disks, 24 MB; docs/bench_granular_engine.md).
constexpr double kFullLookAheadBytes = 32.0 * (1 << 20);
// Pending event times sampled to estimate the event rate of a new calendar.
constexpr std::size_t kRateSample = 4096;
// Slots are renumbered in Morton (Z) order of their cells every this many
// collisions per disk, so that a neighbourhood sits in nearby memory: the
// large-N rate is bound by cache and TLB misses. Small systems fit in cache
// and keep their numbering.
constexpr double kReorderCollisionsPerDisk = 10.0;
constexpr std::size_t kReorderMinDisks = 4096;

std::uint64_t spread_bits(std::uint32_t v) {
  std::uint64_t x = v;
  x = (x | (x << 16)) & 0x0000FFFF0000FFFFULL;
  x = (x | (x << 8)) & 0x00FF00FF00FF00FFULL;
  x = (x | (x << 4)) & 0x0F0F0F0F0F0F0F0FULL;
  x = (x | (x << 2)) & 0x3333333333333333ULL;
  x = (x | (x << 1)) & 0x5555555555555555ULL;
  return x;
}

// One axis of a neighbour lookup: the index one step outside is wrapped
// (with the periodic image's shift); false when that side is not periodic.
bool wrap_axis(int& v, int n, bool periodic, double length, double& shift) {
  shift = 0.0;
  if (v >= 0 && v < n) return true;
  if (v < 0) { v += n; shift = -length; } else { v -= n; shift = length; }
  return periodic;
}

}  // namespace

void Engine::Impl::advance(Particle& q) const {
  const double dt = now - q.t;
  if (dt == 0.0) return;
  const Vec2 g = cfg.gravity;
  q.x += q.vx * dt + 0.5 * g.x * dt * dt;
  q.y += q.vy * dt + 0.5 * g.y * dt * dt;
  q.vx += g.x * dt;
  q.vy += g.y * dt;
  q.t = now;
}

int Engine::Impl::cell_of(double x, double y) const {
  int cy = static_cast<int>(std::floor((y - cfg.ymin) / ch));
  cy = std::clamp(cy, 0, ncy - 1);
  if (drifting) {
    const auto k = static_cast<std::int64_t>(std::floor((x - cfg.xmin - drift * now) / cw));
    const std::int64_t m = k % ncx;
    return pack_cell(static_cast<int>(m < 0 ? m + ncx : m), cy);
  }
  int cx = static_cast<int>(std::floor((x - cfg.xmin) / cw));
  cx = std::clamp(cx, 0, ncx - 1);
  return pack_cell(cx, cy);
}

std::size_t Engine::Impl::wall_cell(double x, double y) const {
  const int cx = std::clamp(static_cast<int>(std::floor((x - cfg.xmin) * inv_wcw)), 0, wnx - 1);
  const int cy = std::clamp(static_cast<int>(std::floor((y - cfg.ymin) * inv_wch)), 0, wny - 1);
  return static_cast<std::size_t>(cy) * static_cast<std::size_t>(wnx) +
         static_cast<std::size_t>(cx);
}

// The column whose number modulo ncx is cx, nearest to the point xi: the
// stored column may differ from floor(xi / cw) by round-off at a face.
// (Double arithmetic throughout: an integer division per event costs more
// than the rest; a remainder off by ncx from round-off is wrapped back.)
double Engine::Impl::column_of(double xi, int cx) const {
  const double n = static_cast<double>(ncx);
  const double k0 = std::floor(xi * inv_cw);
  double d = static_cast<double>(cx) - (k0 - n * std::floor(k0 * inv_ncx));
  if (2.0 * d > n)
    d -= n;
  else if (2.0 * d < -n)
    d += n;
  return k0 + d;
}

void Engine::Impl::cell_insert(std::int32_t i, int c) {
  p[i].cell = c;
  std::int32_t& h = head[head_index(c)];
  p[i].next = h;
  h = i;
}

void Engine::Impl::cell_remove(std::int32_t i, int c) {
  std::int32_t* link = &head[head_index(c)];
  while (*link != i) link = &p[*link].next;
  *link = p[i].next;
}

void Engine::Impl::schedule(std::int32_t i) {
  detail::Slot& si = s[i];
  const double t = si.key();
  ++si.qver;  // the previous entry of this slot is now stale
  if (t != kNever) cal.push({t, static_cast<std::uint32_t>(i), si.qver});
}

// The event loop reads the calendar a few entries ahead and asks for the
// memory those events will touch, in stages, each using what the previous
// stage brought in (a hint only: a stale entry costs nothing, and no result
// depends on it). The work is branch-free where the branch would follow the
// event kind, a coin toss the predictor would lose.
void Engine::Impl::prefetch_ahead() {
  using Entry = detail::Calendar::Entry;
  cal.each_ahead(0, kPrefetchRecords, [this](const Entry& e) { prefetch_records(e.slot); });
  if (!full_look_ahead) return;
  cal.each_ahead(1, kPrefetchPartner, [this](const Entry& e) { prefetch_stage2(e.slot); });
  cal.each_ahead(2, kPrefetchNeighbours, [this](const Entry& e) { prefetch_stage3(e.slot); });
  cal.each_ahead(3, kPrefetchMore, [this](const Entry& e) { prefetch_stage4(e.slot); });
}

// Stage one: the slot's records.
void Engine::Impl::prefetch_records(std::size_t i) const {
  detail::prefetch(&p[i]);
  detail::prefetch(&s[i]);
}

// The slot whose neighbourhood an event of slot i scans besides its own:
// the partner of a disk collision, i itself otherwise.
std::size_t Engine::Impl::scan_partner(std::size_t i) const {
  const detail::Slot& si = s[i];
  const bool disk = !si.crossing_first() && si.type == EventType::disk;
  return disk ? static_cast<std::uint32_t>(si.partner) : i;
}

// The cell whose 3 x 3 block the event of slot i scans: its own, or for a
// cell crossing the one it moves to (a superset of the row it scans).
int Engine::Impl::event_cell(std::size_t i) const {
  const detail::Slot& si = s[i];
  const int d = si.crossing_first() ? si.cell_dir : 4;
  const int cx = std::clamp(cell_x(p[i].cell) + (d == 1) - (d == 0), 0, ncx - 1);
  const int cy = std::clamp(cell_y(p[i].cell) + (d == 3) - (d == 2), 0, ncy - 1);
  return pack_cell(cx, cy);
}

// Heads of the four corner cells of the 3 x 3 block around `cell`, clamped
// at the domain's edges: the 4 x 4 tiles of heads they fall in hold the
// whole block (at a periodic edge the wrapped side is left to the demand
// load).
void Engine::Impl::prefetch_corner_heads(int cell) const {
  const int cx = cell_x(cell), cy = cell_y(cell);
  const std::uint32_t c0 = head_col(std::max(cx - 1, 0)), c1 = head_col(std::min(cx + 1, ncx - 1));
  const std::uint32_t r0 = head_row(std::max(cy - 1, 0)), r1 = head_row(std::min(cy + 1, ncy - 1));
  detail::prefetch(&head[r0 + c0]);
  detail::prefetch(&head[r0 + c1]);
  detail::prefetch(&head[r1 + c0]);
  detail::prefetch(&head[r1 + c1]);
}

// The first disk of each cell of the 3 x 3 block around `cell`; an empty
// cell asks for slot `self` (in cache) instead of taking a branch.
void Engine::Impl::prefetch_block_disks(int cell, std::size_t self) const {
  const auto n = static_cast<std::uint32_t>(p.size());
  const auto ask = [&](std::int32_t k) {
    detail::prefetch(&p[static_cast<std::uint32_t>(k) < n ? static_cast<std::size_t>(k) : self]);
  };
  const int cx = cell_x(cell), cy = cell_y(cell);
  if (cx > 0 && cy > 0 && cx + 1 < ncx && cy + 1 < ncy) {
    // Interior (nearly always): the nine head indices without block_of()'s
    // wrapping.
    const std::uint32_t c0 = head_col(cx - 1), c1 = head_col(cx), c2 = head_col(cx + 1);
    for (int dy = -1; dy <= 1; ++dy) {
      const std::uint32_t r = head_row(cy + dy);
      ask(head[r + c0]);
      ask(head[r + c1]);
      ask(head[r + c2]);
    }
    return;
  }
  Block b;
  block_of(cell, b);
  for (int m = 0; m < b.n; ++m) ask(head[b.head[m]]);
}

// Stage two: the partner's records (for an event without one, the slot's
// own again: in cache by now) and the heads of the block the event scans.
void Engine::Impl::prefetch_stage2(std::size_t i) const {
  const std::size_t j = scan_partner(i);
  detail::prefetch(&p[j]);
  detail::prefetch(&s[j]);
  prefetch_corner_heads(event_cell(i));
}

// Stage three: the partner's block heads and the first disks of the
// event's block.
void Engine::Impl::prefetch_stage3(std::size_t i) const {
  prefetch_corner_heads(p[scan_partner(i)].cell);
  prefetch_block_disks(event_cell(i), i);
}

// Stage four: the first disks of the partner's block. (Second disks of a
// cell, about one per block, were asked for too in a trial: the nine
// dependent reads cost more than that miss.)
void Engine::Impl::prefetch_stage4(std::size_t i) const {
  const std::size_t j = scan_partner(i);
  if (j != i) prefetch_block_disks(p[j].cell, i);
}

// Empties the calendar and schedules every live slot again, with the bucket
// width tuned to the event rate measured so far (or estimated from the
// pending events). Slots renumbered since are fine: entries are rebuilt.
void Engine::Impl::rebuild_calendar() {
  std::size_t live = 0;
  std::vector<double> ahead;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double t = s[i].key();
    if (!p[i].alive || t == kNever) continue;
    ++live;
    if (ahead.size() < kRateSample) ahead.push_back(t - now);
  }
  double rate = cal.measured_rate(now);
  if (!(rate > 0.0) && !ahead.empty()) {
    // Before any measurement: a slot's next event is typically the median
    // time ahead away.
    auto mid = ahead.begin() + static_cast<std::ptrdiff_t>(ahead.size() / 2);
    std::nth_element(ahead.begin(), mid, ahead.end());
    if (*mid > 0.0) rate = static_cast<double>(live) / *mid;
  }
  cal.reset(now, live, rate);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double t = s[i].key();
    if (!p[i].alive || t == kNever) continue;
    cal.push({t, static_cast<std::uint32_t>(i), s[i].qver});
  }
}

// Next crossing of a face of the particle's cell (state at `now`).
void Engine::Impl::predict_cell(std::int32_t i) {
  if (drifting) {
    predict_cell_drifting(i);
    return;
  }
  const Particle& q = p[i];
  detail::Slot& si = s[i];
  const int cx = cell_x(p[i].cell), cy = cell_y(p[i].cell);
  const double xlo = cfg.xmin + cx * cw, xhi = cfg.xmin + (cx + 1) * cw;
  const double ylo = cfg.ymin + cy * ch, yhi = cfg.ymin + (cy + 1) * ch;
  const Vec2 g = cfg.gravity;
  // Each face is a gap that closes: distance to it, its rate, half accel.
  const double t0 = detail::first_contact(q.x - xlo, q.vx, 0.5 * g.x);
  const double t1 = detail::first_contact(xhi - q.x, -q.vx, -0.5 * g.x);
  const double t2 = detail::first_contact(q.y - ylo, q.vy, 0.5 * g.y);
  const double t3 = detail::first_contact(yhi - q.y, -q.vy, -0.5 * g.y);
  double best = t0;
  std::uint8_t dir = 0;
  if (t1 < best) { best = t1; dir = 1; }
  if (t2 < best) { best = t2; dir = 2; }
  if (t3 < best) { best = t3; dir = 3; }
  si.cell_t = now + best;
  si.cell_dir = dir;
}

// Drifting grid: the column's faces move at `drift`, so the gaps close at
// the disk's speed relative to the grid. (The rectangle's x faces, fixed,
// are in the slot's timer: scan_surfaces().)
void Engine::Impl::predict_cell_drifting(std::int32_t i) {
  const Particle& q = p[i];
  detail::Slot& si = s[i];
  const int cy = cell_y(q.cell);
  const double xi = q.x - cfg.xmin - drift * now;
  const double k = column_of(xi, cell_x(q.cell));
  const double xlo = k * cw, xhi = (k + 1.0) * cw;
  const double ylo = cfg.ymin + cy * ch, yhi = cfg.ymin + (cy + 1) * ch;
  const Vec2 g = cfg.gravity;
  if (g.x == 0.0 && g.y == 0.0) {
    // Straight flight (the stream's usual case): only the face each
    // component moves towards can be reached, as first_contact() finds
    // with more work; a gap closed by round-off gives 0 as there.
    const double vr = q.vx - drift;
    const double tx =
        std::max(0.0, vr > 0.0 ? (xhi - xi) / vr : vr < 0.0 ? (xlo - xi) / vr : kNever);
    const double ty = std::max(
        0.0, q.vy > 0.0 ? (yhi - q.y) / q.vy : q.vy < 0.0 ? (ylo - q.y) / q.vy : kNever);
    const bool along_x = tx <= ty;  // ties as in the general case: x faces first
    si.cell_t = now + (along_x ? tx : ty);
    si.cell_dir = along_x ? (vr > 0.0 ? detail::FACE_RIGHT : detail::FACE_LEFT)
                          : (q.vy > 0.0 ? detail::FACE_TOP : detail::FACE_BOTTOM);
    return;
  }
  const double t0 = detail::first_contact(xi - xlo, q.vx - drift, 0.5 * g.x);
  const double t1 = detail::first_contact(xhi - xi, drift - q.vx, -0.5 * g.x);
  const double t2 = detail::first_contact(q.y - ylo, q.vy, 0.5 * g.y);
  const double t3 = detail::first_contact(yhi - q.y, -q.vy, -0.5 * g.y);
  double best = t0;
  std::uint8_t dir = detail::FACE_LEFT;
  if (t1 < best) {
    best = t1;
    dir = detail::FACE_RIGHT;
  }
  if (t2 < best) {
    best = t2;
    dir = detail::FACE_BOTTOM;
  }
  if (t3 < best) {
    best = t3;
    dir = detail::FACE_TOP;
  }
  si.cell_t = now + best;
  si.cell_dir = dir;
}

// Drifting grid: the slot's timer joins its next cell event.
void Engine::Impl::join_timer(std::int32_t i) {
  detail::Slot& si = s[i];
  if (timer_t[i] < si.cell_t) {
    si.cell_t = timer_t[i];
    si.cell_dir = si.timer_dir;
  }
}

bool Engine::Impl::neighbour_cell(int cx, int cy, int& cell, double& shx, double& shy) const {
  if (!wrap_axis(cx, ncx, wrap_x, wrap_lx, shx) || !wrap_axis(cy, ncy, periodic_y, ly, shy))
    return false;
  cell = pack_cell(cx, cy);
  return true;
}

void Engine::Impl::block_of(int cell, Block& b) const {
  // Columns and rows of the block (wrapped on periodic sides), each as its
  // share of the tiled head index.
  std::uint32_t col[3], row[3];
  double sx[3], sy[3];
  bool okx[3], oky[3];
  const int cx = cell_x(cell), cy = cell_y(cell);
  for (int d = 0; d < 3; ++d) {
    int x = cx + d - 1, y = cy + d - 1;
    okx[d] = wrap_axis(x, ncx, wrap_x, wrap_lx, sx[d]);
    oky[d] = wrap_axis(y, ncy, periodic_y, ly, sy[d]);
    col[d] = head_col(x);
    row[d] = head_row(y);
  }
  int n = 0;
  for (int dy = 0; dy < 3; ++dy) {
    if (!oky[dy]) continue;
    for (int dx = 0; dx < 3; ++dx) {
      if (!okx[dx]) continue;
      b.head[n] = row[dy] + col[dx];
      b.shx[n] = sx[dx];
      b.shy[n] = sy[dy];
      ++n;
    }
  }
  b.n = n;
}

void Engine::Impl::scan_cell_for(std::int32_t i, int cx, int cy, double rx, double ry, double vx,
                                 double vy, double rad_i) {
  int cell = 0;
  double shx = 0.0, shy = 0.0;
  if (!neighbour_cell(cx, cy, cell, shx, shy)) return;
  scan_list(i, head[head_index(cell)], shx, shy, rx, ry, vx, vy, rad_i);
}

void Engine::Impl::scan_list(std::int32_t i, std::int32_t first, double shx, double shy, double rx,
                             double ry, double vx, double vy, double rad_i) {
  detail::Slot& si = s[i];
  const Vec2 g = cfg.gravity;
  const bool accel = g.x != 0.0 || g.y != 0.0;
  const bool mono = ns == 1;
  for (std::int32_t k = first; k >= 0; k = p[k].next) {
    if (k == i) continue;
    const Particle& o = p[k];
    const double dt = now - o.t;
    double ox = o.x + o.vx * dt + shx, oy = o.y + o.vy * dt + shy;
    double ovx = o.vx, ovy = o.vy;
    if (accel) {
      ox += 0.5 * g.x * dt * dt;
      oy += 0.5 * g.y * dt * dt;
      ovx += g.x * dt;
      ovy += g.y * dt;
    }
    const double sig = mono ? 2.0 * rad_i : rad_i + radius[o.species];
    const double tc = detail::disk_contact(rx - ox, ry - oy, vx - ovx, vy - ovy, sig * sig);
    if (now + tc < si.coll_t) {
      si.coll_t = now + tc;
      si.type = EventType::disk;
      si.partner = k;
      si.pcount = o.count;
    }
  }
}

// Walls and vertices a disk may touch: those of its cell (fixed grid), or
// (drifting grid) those of the fixed grid's cell it is in, which lists all
// it could reach before travelling that cell's clearance; the look-up is
// then repeated at that horizon (WALL_RECHECK) unless the disk reaches an
// x face of the rectangle first. The drifting grid keeps both in the
// slot's timer, which joins cell_t: call after predict_cell().
void Engine::Impl::scan_surfaces(std::int32_t i, int c, double rx, double ry, double vx,
                                 double vy) {
  if (!drifting) {
    scan_walls_for(i, linear_cell(c), rx, ry, vx, vy);
    return;
  }
  const Vec2 g = cfg.gravity;
  const double t_left = detail::first_contact(rx - cfg.xmin, vx, 0.5 * g.x);
  const double t_right = detail::first_contact(cfg.xmax - rx, -vx, -0.5 * g.x);
  double timer = t_left;
  std::uint8_t dir = detail::EXIT_LEFT;
  if (t_right < timer) {
    timer = t_right;
    dir = detail::EXIT_RIGHT;
  }
  if (surfaces.empty()) {  // nothing to look up: only the exits
    timer_t[i] = now + timer;
    s[i].timer_dir = dir;
    join_timer(i);
    return;
  }
  const std::size_t lc = wall_cell(rx, ry);
  const double clear = static_cast<double>(surfaces[lc].clear);
  if (clear != kNever) {
    // The path travelled in dt is at most |v| dt + |g| dt^2 / 2.
    const double speed = std::sqrt(vx * vx + vy * vy);
    const double accel = std::sqrt(g.x * g.x + g.y * g.y);
    const double dt = 2.0 * clear / (speed + std::sqrt(speed * speed + 2.0 * accel * clear));
    if (dt < timer) {
      timer = dt;
      dir = detail::WALL_RECHECK;
    }
  }
  detail::Slot& si = s[i];
  timer_t[i] = now + timer;
  si.timer_dir = dir;
  // Beyond the timer the walls are looked up again: the horizon of the
  // look-up's predictions (the quartic of a vertex under gravity).
  const double cell_t = si.cell_t;
  si.cell_t = timer_t[i];
  scan_walls_for(i, lc, rx, ry, vx, vy);
  si.cell_t = cell_t;
  join_timer(i);
}

void Engine::Impl::scan_walls_for(std::int32_t i, std::size_t lc, double rx, double ry, double vx,
                                  double vy) {
  detail::Slot& si = s[i];
  const double rad = radius[p[i].species];
  const Vec2 g = cfg.gravity;
  if (surfaces.empty()) return;
  const detail::SurfaceCell& here = surfaces[lc];
  const detail::SurfaceCell& next = surfaces[lc + 1];
  {
    for (std::int32_t k = here.walls; k < next.walls; ++k) {
      const std::int32_t w = wall_list[k];
      const detail::WallGeom& wg = walls[w];
      const double ax = rx - wg.a.x, ay = ry - wg.a.y;
      const double d0 = ax * wg.n.x + ay * wg.n.y;
      if (d0 <= 0.0) continue;  // behind a one-sided wall: never touches it
      const double vn = vx * wg.n.x + vy * wg.n.y;
      const double gn = g.x * wg.n.x + g.y * wg.n.y;
      const double dt = detail::first_contact(d0 - rad, vn, 0.5 * gn);
      if (!(now + dt < si.coll_t)) continue;
      const double along = ax * wg.t.x + ay * wg.t.y + (vx * wg.t.x + vy * wg.t.y) * dt +
                        0.5 * (g.x * wg.t.x + g.y * wg.t.y) * dt * dt;
      // Contact beyond the segment's ends: the end vertex (convex) or the
      // next segment (concave) takes it.
      if (along < -kSegmentEndSlack || along > wg.length + kSegmentEndSlack) continue;
      si.coll_t = now + dt;
      si.type = EventType::wall;
      si.partner = w;
    }
  }
  {
    const bool accel = g.x != 0.0 || g.y != 0.0;
    for (std::int32_t k = here.vertices; k < next.vertices; ++k) {
      const std::int32_t v = vertex_list[k];
      const Vec2 vp = cfg.vertices[v].p;
      const double dt =
          accel ? detail::vertex_contact_accelerated(rx - vp.x, ry - vp.y, vx, vy, g.x, g.y, rad,
                                                     si.cell_t - now)
                : detail::disk_contact(rx - vp.x, ry - vp.y, vx, vy, rad * rad);
      if (now + dt < si.coll_t) {
        si.coll_t = now + dt;
        si.type = EventType::vertex;
        si.partner = v;
      }
    }
  }
}

// Full prediction for slot i: cell crossing plus every possible partner.
void Engine::Impl::predict(std::int32_t i) {
  Particle& q = p[i];
  advance(q);
  detail::Slot& si = s[i];
  si.coll_t = kNever;
  si.type = EventType::none;
  predict_cell(i);
  const double rad = radius[q.species];
  // Two passes: read the nine list heads and start loading their first
  // disks, then scan; for large systems the loads overlap instead of
  // following one another.
  Block b;
  block_of(p[i].cell, b);
  std::int32_t first[9];
  for (int k = 0; k < b.n; ++k) {
    first[k] = head[b.head[k]];
    if (first[k] >= 0) detail::prefetch(&p[first[k]]);
  }
  for (int k = 0; k < b.n; ++k) scan_list(i, first[k], b.shx[k], b.shy[k], q.x, q.y, q.vx, q.vy, rad);
  scan_surfaces(i, p[i].cell, q.x, q.y, q.vx, q.vy);
}

void Engine::Impl::process(std::int32_t i) {
  detail::Slot& si = s[i];
  if (si.crossing_first()) {
    cross_cell(i);
    return;
  }
  switch (si.type) {
    case EventType::disk: {
      const std::int32_t j = si.partner;
      if (!p[j].alive || p[j].count != si.pcount) {
        // The partner changed course since the prediction: predict again.
        ++repredictions;
        predict(i);
        schedule(i);
        return;
      }
      collide_disks(i, j);
      return;
    }
    case EventType::wall: {
      Particle& q = p[i];
      advance(q);
      const detail::WallGeom& wg = walls[si.partner];
      const double d0 = (q.x - wg.a.x) * wg.n.x + (q.y - wg.a.y) * wg.n.y;
      const double e = wg.e >= 0.0 ? wg.e : e_wall[q.species];
      collide_surface(i, wg.n, e, radius[q.species] - d0);
      return;
    }
    case EventType::vertex: {
      Particle& q = p[i];
      advance(q);
      const Vertex& v = cfg.vertices[si.partner];
      const double rx = q.x - v.p.x, ry = q.y - v.p.y;
      const double dist = std::sqrt(rx * rx + ry * ry);
      const double e = v.restitution >= 0.0 ? v.restitution : e_vertex[q.species];
      collide_surface(i, Vec2{rx / dist, ry / dist}, e, radius[q.species] - dist);
      return;
    }
    case EventType::none:
      predict(i);
      schedule(i);
      return;
  }
}

void Engine::Impl::cross_cell(std::int32_t i) {
  ++crossings;
  Particle& q = p[i];
  advance(q);
  detail::Slot& si = s[i];
  const std::uint8_t dir = si.cell_dir;
  if (dir >= detail::EXIT_LEFT) {
    leave_or_recheck(i);
    return;
  }
  int cx = cell_x(p[i].cell), cy = cell_y(p[i].cell);
  int ncx2 = cx + (dir == 1) - (dir == 0);
  int ncy2 = cy + (dir == 3) - (dir == 2);
  if (drifting) ncx2 = ncx2 < 0 ? ncx - 1 : ncx2 >= ncx ? 0 : ncx2;  // columns numbered modulo ncx
  if (ncx2 < 0 || ncx2 >= ncx || ncy2 < 0 || ncy2 >= ncy) {
    const Face face = dir == 0 ? cfg.left : dir == 1 ? cfg.right : dir == 2 ? cfg.bottom : cfg.top;
    if (face == Face::open) {
      remove(i);
      return;
    }
    if (face == Face::periodic) {
      if (ncx2 < 0) { ncx2 += ncx; q.x += lx; }
      else if (ncx2 >= ncx) { ncx2 -= ncx; q.x -= lx; }
      else if (ncy2 < 0) { ncy2 += ncy; q.y += ly; }
      else { ncy2 -= ncy; q.y -= ly; }
    } else {
      // A closed face reached by a centre: a wall was tunnelled through.
      // Reflect the disk back in (specular) and count the recovery.
      ++st.recoveries;
      if (dir <= 1) q.vx = -q.vx; else q.vy = -q.vy;
      ++q.count;
      predict(i);
      schedule(i);
      return;
    }
  }
  const int c = pack_cell(ncx2, ncy2);
  cell_remove(i, p[i].cell);
  cell_insert(i, c);
  predict_cell(i);
  if (drifting) join_timer(i);  // the path, hence its walls and timer, is unchanged
  const bool stale = si.type == EventType::disk &&
                     (!p[si.partner].alive || p[si.partner].count != si.pcount);
  if (stale) {
    predict(i);
  } else {
    // Only the cells that just became adjacent can hold a new partner; the
    // stored prediction already covers the others.
    const double rad = radius[q.species];
    if (dir <= 1) {
      const int fx = ncx2 + (dir == 1 ? 1 : -1);
      for (int dy = -1; dy <= 1; ++dy) scan_cell_for(i, fx, ncy2 + dy, q.x, q.y, q.vx, q.vy, rad);
    } else {
      const int fy = ncy2 + (dir == 3 ? 1 : -1);
      for (int dx = -1; dx <= 1; ++dx) scan_cell_for(i, ncx2 + dx, fy, q.x, q.y, q.vx, q.vy, rad);
    }
    if (!drifting) scan_surfaces(i, c, q.x, q.y, q.vx, q.vy);
  }
  schedule(i);
}

// Drifting grid: a disk reaching an x face of the rectangle (open: it
// leaves; closed: a wall was tunnelled, recovered as at a cell face), or
// its wall look-up horizon (the cell is unchanged: the stored collision
// still holds, only the walls are looked up again).
void Engine::Impl::leave_or_recheck(std::int32_t i) {
  Particle& q = p[i];
  detail::Slot& si = s[i];
  if (si.cell_dir != detail::WALL_RECHECK) {
    const Face face = si.cell_dir == detail::EXIT_LEFT ? cfg.left : cfg.right;
    if (face == Face::open) {
      remove(i);
      return;
    }
    ++st.recoveries;
    q.vx = -q.vx;
    ++q.count;
    predict(i);
    schedule(i);
    return;
  }
  ++rechecks;
  --crossings;
  predict_cell(i);
  const bool stale =
      si.type == EventType::disk && (!p[si.partner].alive || p[si.partner].count != si.pcount);
  if (stale)
    predict(i);
  else
    scan_surfaces(i, q.cell, q.x, q.y, q.vx, q.vy);
  schedule(i);
}

void Engine::Impl::integrate_energy() {
  energy_integral += energy * (now - energy_since);
  energy_since = now;
}

void Engine::Impl::collide_disks(std::int32_t i, std::int32_t j) {
  Particle& a = p[i];
  Particle& b = p[j];
  advance(a);
  advance(b);
  double dx = a.x - b.x, dy = a.y - b.y;
  // Minimum image: a contact distance is below a third of a periodic side.
  if (periodic_x) { if (dx > 0.5 * lx) dx -= lx; else if (dx < -0.5 * lx) dx += lx; }
  if (periodic_y) { if (dy > 0.5 * ly) dy -= ly; else if (dy < -0.5 * ly) dy += ly; }
  const double dist = std::sqrt(dx * dx + dy * dy);
  const double sig = radius[a.species] + radius[b.species];
  const double overlap = sig - dist;
  st.max_overlap = std::max(st.max_overlap, overlap);
  if (overlap > kRecoveryTolerance) ++st.recoveries;
  const double nx = dx / dist, ny = dy / dist;
  const double vn = (a.vx - b.vx) * nx + (a.vy - b.vy) * ny;
  if (vn < 0.0) {
    double e = e_disk[a.species * ns + b.species];
    if (now - p[i].last_coll < cfg.tc || now - p[j].last_coll < cfg.tc) e = 1.0;
    if (-vn < cfg.elastic_below) e = 1.0;
    const double ma = mass[a.species], mb = mass[b.species];
    const double jimp = (1.0 + e) * vn * (ma * mb / (ma + mb));  // < 0
    if (e != 1.0) integrate_energy();
    const double e_before = 0.5 * (ma * (a.vx * a.vx + a.vy * a.vy) + mb * (b.vx * b.vx + b.vy * b.vy));
    a.vx -= jimp / ma * nx;
    a.vy -= jimp / ma * ny;
    b.vx += jimp / mb * nx;
    b.vy += jimp / mb * ny;
    if (e != 1.0) {
      energy += 0.5 * (ma * (a.vx * a.vx + a.vy * a.vy) + mb * (b.vx * b.vx + b.vy * b.vy)) - e_before;
    }
    virial -= jimp * dist;
    ++a.count;
    ++b.count;
    p[i].last_coll = now;
    p[j].last_coll = now;
    ++st.collisions;
    ++st.disk_collisions;
  }
  predict(i);
  predict(j);
  schedule(i);
  schedule(j);
}

void Engine::Impl::collide_surface(std::int32_t i, Vec2 n, double e, double overlap) {
  Particle& q = p[i];
  st.max_overlap = std::max(st.max_overlap, overlap);
  if (overlap > kRecoveryTolerance) ++st.recoveries;
  const double vn = q.vx * n.x + q.vy * n.y;
  if (vn < 0.0) {
    if (now - p[i].last_coll < cfg.tc) e = 1.0;
    const double m = mass[q.species];
    if (e != 1.0) {
      integrate_energy();
      energy -= 0.5 * m * (1.0 - e * e) * vn * vn;
    }
    q.vx -= (1.0 + e) * vn * n.x;
    q.vy -= (1.0 + e) * vn * n.y;
    ++q.count;
    p[i].last_coll = now;
    ++st.collisions;
    ++st.wall_collisions;
  }
  predict(i);
  schedule(i);
}

void Engine::Impl::remove(std::int32_t i) {
  Particle& q = p[i];
  integrate_energy();
  energy -= 0.5 * mass[q.species] * (q.vx * q.vx + q.vy * q.vy);
  cell_remove(i, p[i].cell);
  q.alive = 0;
  ++q.count;  // every prediction naming this slot is now stale
  s[i].coll_t = kNever;
  s[i].cell_t = kNever;
  s[i].type = EventType::none;
  ++s[i].qver;  // its calendar entry is stale
  free_slots.push_back(i);
  ++st.removed;
}

void Engine::Impl::choose_look_ahead() {
  const double footprint = static_cast<double>(
      p.size() * (sizeof(Particle) + sizeof(detail::Slot)) + head.size() * sizeof(std::int32_t));
  full_look_ahead = cfg.look_ahead == LookAhead::full ||
                    (cfg.look_ahead == LookAhead::automatic && footprint > kFullLookAheadBytes);
}

bool Engine::Impl::reorder() {
  const std::size_t n = p.size();
  std::size_t alive = 0;
  for (const Particle& q : p) alive += q.alive ? 1 : 0;
  next_reorder = st.collisions + static_cast<std::uint64_t>(kReorderCollisionsPerDisk * static_cast<double>(alive));
  choose_look_ahead();
  if (alive < kReorderMinDisks) return false;
  std::vector<std::pair<std::uint64_t, std::int32_t>> order(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Particle& q = p[i];
    const std::uint64_t key =
        q.alive ? (spread_bits(static_cast<std::uint32_t>(cell_x(q.cell))) |
                   (spread_bits(static_cast<std::uint32_t>(cell_y(q.cell))) << 1))
                : ~std::uint64_t{0};
    order[i] = {key, static_cast<std::int32_t>(i)};
  }
  std::sort(order.begin(), order.end());
  std::vector<std::int32_t> new_index(n);
  for (std::size_t k = 0; k < n; ++k) new_index[static_cast<std::size_t>(order[k].second)] = static_cast<std::int32_t>(k);
  // Apply the permutation in place (cycle by cycle): a copy of the arrays
  // would double the peak memory of a large system.
  for (std::size_t k = 0; k < n; ++k)
    if (s[k].type == EventType::disk) s[k].partner = new_index[static_cast<std::size_t>(s[k].partner)];
  if (drifting) {  // 8 bytes a slot: a copy costs little
    std::vector<double> moved(n);
    for (std::size_t k = 0; k < n; ++k) moved[static_cast<std::size_t>(new_index[k])] = timer_t[k];
    timer_t.swap(moved);
  }
  for (std::size_t start = 0; start < n; ++start) {
    // new_index[k] < 0 marks a slot already placed.
    if (new_index[start] < 0 || static_cast<std::size_t>(new_index[start]) == start) continue;
    Particle pt = p[start];
    detail::Slot st_slot = s[start];
    std::size_t from = start;
    while (true) {
      const auto to = static_cast<std::size_t>(new_index[from]);
      new_index[from] = -1;
      if (to == start) {
        p[to] = pt;
        s[to] = st_slot;
        break;
      }
      std::swap(pt, p[to]);
      std::swap(st_slot, s[to]);
      from = to;
    }
  }
  std::fill(head.begin(), head.end(), -1);
  free_slots.clear();
  for (std::size_t k = n; k-- > 0;) {
    if (p[k].alive) cell_insert(static_cast<std::int32_t>(k), p[k].cell);
    else free_slots.push_back(static_cast<std::int32_t>(k));
  }
  rebuild_calendar();
  return true;
}

void Engine::Impl::build_all() {
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p[i].alive) continue;
    predict(static_cast<std::int32_t>(i));
  }
  started = true;
  if (!reorder()) rebuild_calendar();
}

// ---------------------------------------------------------------- public

void Engine::reserve(std::size_t n) {
  impl_->p.reserve(n);
  impl_->s.reserve(n);
  if (impl_->drifting) impl_->timer_t.reserve(n);
}

void Engine::start() {
  if (!impl_->started) impl_->build_all();
}

void Engine::run_until(double t, std::uint64_t max_collisions) {
  Impl& m = *impl_;
  if (!m.started) m.build_all();
  const auto live = [&m](const detail::Calendar::Entry& e) { return m.live(e); };
  const auto time_of = [&m](std::uint32_t slot) { return m.s[slot].key(); };
  while (true) {
    const detail::Calendar::Entry* e = m.cal.top(live, time_of);
    if (!e || !(e->t <= t)) break;
    if (m.st.collisions >= max_collisions) return;
    if ((++m.events & kPollMask) == 0 && scene::interrupted()) return;
    if (m.events - m.window_events >= kCollapseWindow) m.check_collapse();
    const std::uint32_t i = e->slot;
    m.now = e->t;
    m.cal.pop();
    m.prefetch_ahead();
    m.process(static_cast<std::int32_t>(i));
    if (m.st.collisions >= m.next_reorder) m.reorder();
    else if (m.cal.wants_retune()) m.rebuild_calendar();
  }
  if (m.st.collisions >= max_collisions) return;
  if (t != kNever && t > m.now) m.now = t;
}

void Engine::Impl::check_collapse() {
  const double span = now - window_time;
  const double disks = static_cast<double>(std::max<std::size_t>(p.size(), 1));
  const double rate = static_cast<double>(events - window_events) / (disks * span);
  if (!(span > 0.0) || rate > kCollapseEventRate) {
    std::ostringstream os;
    os.precision(3);
    os << "inelastic collapse at t = " << now << ": " << (events - window_events) << " events in a simulated time of "
       << span << " (" << (span > 0.0 ? rate : std::numeric_limits<double>::infinity())
       << " per disk per unit time, limit " << kCollapseEventRate
       << "); raise granular.restitution or granular.tc (the TC model makes collisions within tc elastic)";
    throw scene::RunError(os.str());
  }
  window_events = events;
  window_time = now;
}

void Engine::run_collisions(std::uint64_t n) {
  run_until(kNever, impl_->st.collisions + n);
}

double Engine::time() const { return impl_->now; }

Stats Engine::stats() const {
  Stats out = impl_->st;
  out.time = impl_->now;
  double e = 0.0;
  std::size_t n = 0;
  for_each_particle_species([&](Vec2, Vec2 v, int sp) {
    e += 0.5 * impl_->mass[static_cast<std::size_t>(sp)] * norm2(v);
    ++n;
  });
  out.kinetic_energy = e;
  out.particles = n;
  return out;
}

Stats Engine::stats_light() const {
  Stats out = impl_->st;
  out.time = impl_->now;
  return out;
}

EventCounts Engine::event_counts() const {
  return {impl_->events, impl_->crossings, impl_->repredictions, impl_->rechecks};
}

Vec2 Engine::cell_size() const {
  return {impl_->cw, impl_->ch};
}

const EngineConfig& Engine::config() const { return impl_->cfg; }
std::span<const Particle> Engine::particles() const { return {impl_->p.data(), impl_->p.size()}; }

void Engine::reset_measurement() {
  Impl& m = *impl_;
  m.virial = 0.0;
  m.meas_start = m.now;
  m.energy_integral = 0.0;
  m.energy_since = m.now;
}

double Engine::virial_sum() const { return impl_->virial; }

double Engine::measurement_time() const { return impl_->now - impl_->meas_start; }

double Engine::energy_time_integral() const {
  return impl_->energy_integral + impl_->energy * (impl_->now - impl_->energy_since);
}

double Engine::bytes_per_particle() const {
  const Impl& m = *impl_;
  const double n = static_cast<double>(std::max<std::size_t>(m.p.size(), 1));
  const double bytes = static_cast<double>(m.p.capacity() * sizeof(Particle) +
                                           m.s.capacity() * sizeof(detail::Slot) +
                                           m.head.capacity() * sizeof(std::int32_t) +
                                           m.free_slots.capacity() * sizeof(std::int32_t) +
                                           m.timer_t.capacity() * sizeof(double)) +
                       m.cal.bytes();
  return bytes / n;
}

}  // namespace granular
