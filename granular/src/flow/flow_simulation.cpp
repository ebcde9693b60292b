// Open-boundary supersonic stream on top of the engine.
//
// Boundaries (docs/granular_engine.md): the simulated rectangle is exactly
// the domain. Disks whose centre crosses x = xmin (back-flow), x = xmax,
// y = ymax (and y = ymin unless symmetric) leave the system (open faces of
// the engine's cell grid). The free stream enters through x = xmin and
// through the free-stream sides y = ymax (and y = ymin unless symmetric) as a
// Poisson stream of insertions at the exact one-way Maxwellian flux
// n <v_n>_+ per unit length, each disk drawn from the flux-weighted
// distribution and placed on the boundary line at a uniform random point;
// an insertion that would overlap a disk or a wall is retried at another
// point at the same instant, so the rate is kept exactly.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/engine_impl.hpp"
#include "engine/rng.hpp"
#include "granular/hard_disk.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"

namespace granular {

namespace {

// Positions tried for one insertion before it is given up (counted).
constexpr int kInsertTries = 64;
// Positions tried for one prefill disk before it is given up.
constexpr int kPrefillTries = 64;
// Automatic engine cells (FlowConfig::cell = 0): this many per mean free
// path of the inflow gas. Larger cells mean fewer crossings and more disks
// per prediction; on the wedge M3/10 (nu = 0.1, free path 4.7 d) cells of
// 1.5-2 d were fastest (docs/bench_granular_flow.md).
constexpr double kCellsPerFreePath = 3.0;

// Velocities above U + kFluxCutoff * sqrt(T) are always accepted by the
// flux-weighted rejection sampler (their weight error is ~exp(-kFluxCutoff^2/2)).
constexpr double kFluxCutoff = 8.0;

double normal_cdf(double x) { return 0.5 * std::erfc(-x / std::numbers::sqrt2); }
double normal_pdf(double x) { return std::exp(-0.5 * x * x) / std::sqrt(2.0 * std::numbers::pi); }

struct Segment {
  Vec2 a, b, n;
  Vec2 na, nb;  // pseudo-normals at a and b (sum of adjacent normals)
};

}  // namespace

struct FlowSimulation::Impl {
  FlowConfig cfg;
  Engine engine;
  detail::Rng rng;
  std::vector<Segment> body;
  double n_density = 0.0, sd = 1.0;
  double rate_left = 0.0, rate_top = 0.0, rate_bottom = 0.0, rate_total = 0.0;
  double next_insert = 0.0;
  double inflow_boost = 0.0;  // see the constructor
  std::uint64_t insert_failures = 0;

  Impl(const FlowConfig& c, EngineConfig ec) : cfg(c), engine(std::move(ec)), rng(c.seed) {}

  // Signed distance to the body surface (negative inside), via the nearest
  // feature and the pseudo-normal at chain joints.
  double body_distance(Vec2 q) const {
    double best = std::numeric_limits<double>::infinity();
    double sign = 1.0;
    for (const Segment& sg : body) {
      const Vec2 ab = sg.b - sg.a;
      const double t = std::clamp(dot(q - sg.a, ab) / norm2(ab), 0.0, 1.0);
      const Vec2 foot = sg.a + t * ab;
      const double d = norm(q - foot);
      if (d < best) {
        best = d;
        const Vec2 nn = t <= 0.0 ? sg.na : t >= 1.0 ? sg.nb : sg.n;
        sign = dot(q - foot, nn) >= 0.0 ? 1.0 : -1.0;
      }
    }
    return sign * best;
  }

  bool place(Vec2 r, Vec2 v) {
    if (!body.empty() && body_distance(r) < cfg.radius) return false;
    return engine.try_add(r, v, 0);
  }

  double flux_weighted_normal_speed(double mean) {
    // p(u) ~ u exp(-(u - mean)^2 / 2 sd^2), u > 0: rejection from the
    // truncated normal with acceptance u / u_max.
    const double umax = std::max(mean, 0.0) + kFluxCutoff * sd;
    while (true) {
      const double u = mean + sd * rng.normal();
      if (u <= 0.0) continue;
      if (u >= umax || rng.uniform() * umax < u) return u;
    }
  }

  void insert_one() {
    const double pick = rng.uniform() * rate_total;
    const FlowConfig& c = cfg;
    Vec2 v;
    int side;  // 0 left, 1 top, 2 bottom
    if (pick < rate_left) {
      side = 0;
      v = {flux_weighted_normal_speed(c.inflow_speed) + inflow_boost, sd * rng.normal()};
    } else if (pick < rate_left + rate_top) {
      side = 1;
      v = {c.inflow_speed + sd * rng.normal(), -flux_weighted_normal_speed(0.0)};
    } else {
      side = 2;
      v = {c.inflow_speed + sd * rng.normal(), flux_weighted_normal_speed(0.0)};
    }
    for (int k = 0; k < kInsertTries; ++k) {
      const double u = rng.uniform();
      const Vec2 r = side == 0 ? Vec2{c.xmin, c.ymin + u * (c.ymax - c.ymin)}
                   : side == 1 ? Vec2{c.xmin + u * (c.xmax - c.xmin), c.ymax}
                               : Vec2{c.xmin + u * (c.xmax - c.xmin), c.ymin};
      if (place(r, v)) return;
    }
    ++insert_failures;
  }

  void prefill() {
    const FlowConfig& c = cfg;
    const double area = (c.xmax - c.xmin) * (c.ymax - c.ymin);
    const auto count = static_cast<std::int64_t>(std::llround(n_density * area));
    for (std::int64_t k = 0; k < count; ++k) {
      const Vec2 v{c.inflow_speed + sd * rng.normal(), sd * rng.normal()};
      for (int tries = 0; tries < kPrefillTries; ++tries) {
        const Vec2 r{c.xmin + rng.uniform() * (c.xmax - c.xmin), c.ymin + rng.uniform() * (c.ymax - c.ymin)};
        // A point inside the body stands for the body's share of the area.
        if (!body.empty() && body_distance(r) < 0.0) break;
        if (place(r, v)) break;
      }
    }
  }
};

namespace {}  // namespace

double automatic_cell(const FlowConfig& c) {
  // Mean free path of hard disks in 2D: 1 / (sqrt(2) n d chi), with the
  // contact value chi = (Z - 1) / (2 nu).
  const double d = 2.0 * c.radius;
  const double n = c.packing_fraction / (std::numbers::pi * c.radius * c.radius);
  const double chi = (henderson_z(c.packing_fraction) - 1.0) / (2.0 * c.packing_fraction);
  const double free_path = 1.0 / (std::numbers::sqrt2 * n * d * chi);
  return std::max(d, free_path / kCellsPerFreePath);
}

namespace {

EngineConfig engine_config(const FlowConfig& c, std::vector<Segment>& body) {
  if (!(c.xmax > c.xmin && c.ymax > c.ymin)) throw scene::InputError("flow: empty domain");
  if (!(c.packing_fraction > 0.0 && c.packing_fraction < 0.6))
    throw scene::InputError("flow: inflow packing fraction must lie in (0, 0.6)");
  if (!(c.temperature > 0.0)) throw scene::InputError("flow: temperature must be positive");
  EngineConfig e;
  e.xmin = c.xmin; e.xmax = c.xmax; e.ymin = c.ymin; e.ymax = c.ymax;
  const bool mirror_sides = c.sides == FlowConfig::Sides::mirror;
  e.left = e.right = Face::open;
  e.top = mirror_sides ? Face::closed : Face::open;
  e.bottom = c.symmetric || mirror_sides ? Face::closed : Face::open;
  if (mirror_sides) {
    e.walls.push_back({{c.xmax, c.ymax}, {c.xmin, c.ymax}, 1.0});
    if (!c.symmetric) e.walls.push_back({{c.xmin, c.ymin}, {c.xmax, c.ymin}, 1.0});
  }
  e.species = {Species{c.radius, c.mass, c.restitution_wall, c.restitution_wall}};
  e.restitution = {c.restitution};
  e.gravity = c.gravity;
  e.tc = c.tc;
  e.elastic_below = c.elastic_below * std::sqrt(c.temperature / c.mass);
  e.min_cell = c.cell > 0.0 ? c.cell : automatic_cell(c);
  if (c.comoving_cells) e.grid_speed = c.inflow_speed;
  if (c.symmetric) e.walls.push_back({{c.xmin, c.ymin}, {c.xmax, c.ymin}, 1.0});  // mirror
  for (const auto& chain : c.body_chains) {
    if (chain.size() < 2) throw scene::InputError("flow: a body chain needs two points");
    const bool closed = chain.front() == chain.back() && chain.size() > 3;
    const std::size_t nseg = chain.size() - 1;
    const std::size_t first = body.size();
    for (std::size_t k = 0; k < nseg; ++k) {
      const Vec2 a = chain[k], b = chain[k + 1];
      if (!(norm(b - a) > 0.0)) throw scene::InputError("flow: repeated point in a body chain");
      e.walls.push_back({a, b, -1.0});
      const Vec2 n = perp(normalized(b - a));
      body.push_back({a, b, n, n, n});
    }
    for (std::size_t k = 0; k < nseg; ++k) {
      Segment& sg = body[first + k];
      const bool has_prev = k > 0 || closed, has_next = k + 1 < nseg || closed;
      if (has_prev) sg.na = sg.n + body[first + (k + nseg - 1) % nseg].n;
      if (has_next) sg.nb = sg.n + body[first + (k + 1) % nseg].n;
    }
    // Vertices: chain ends (open chains) and convex joints (right turns).
    for (std::size_t k = 0; k < chain.size(); ++k) {
      const bool end = k == 0 || k + 1 == chain.size();
      if (end && closed) {
        if (k + 1 == chain.size()) continue;  // same point as k = 0
        const Vec2 t1 = chain[nseg] - chain[nseg - 1], t2 = chain[1] - chain[0];
        if (cross(t1, t2) < 0.0) e.vertices.push_back({chain[0], -1.0});
        continue;
      }
      if (end || cross(chain[k] - chain[k - 1], chain[k + 1] - chain[k]) < 0.0)
        e.vertices.push_back({chain[k], -1.0});
    }
  }
  return e;
}

}  // namespace

FlowSimulation::FlowSimulation(const FlowConfig& cfg) {
  std::vector<Segment> body;
  EngineConfig ec = engine_config(cfg, body);
  impl_ = std::make_unique<Impl>(cfg, std::move(ec));
  Impl& m = *impl_;
  m.body = std::move(body);
  m.sd = std::sqrt(cfg.temperature / cfg.mass);
  m.n_density = cfg.packing_fraction / (std::numbers::pi * cfg.radius * cfg.radius);
  const double mach_ratio = cfg.inflow_speed / m.sd;
  const double flux_x = cfg.inflow_speed * normal_cdf(mach_ratio) + m.sd * normal_pdf(mach_ratio);
  const double flux_side = m.sd / std::sqrt(2.0 * std::numbers::pi);
  m.rate_left = m.n_density * flux_x * (cfg.ymax - cfg.ymin);
  const bool open_sides = cfg.sides == FlowConfig::Sides::open_flux;
  m.rate_top = open_sides ? m.n_density * flux_side * (cfg.xmax - cfg.xmin) : 0.0;
  m.rate_bottom = cfg.symmetric ? 0.0 : m.rate_top;
  m.rate_total = m.rate_left + m.rate_top + m.rate_bottom;
  // Inserted disks have no upstream partners, so the collisional part of
  // the free stream's pressure, p_c = n T (Z - 1), is missing at the inflow
  // and would decelerate the incoming gas by ~T (Z - 1) / U (2% at nu = 0.1,
  // U = 4). Inserting every disk faster by that amount restores the
  // momentum flux p_c and, to first order, the energy flux p_c U.
  const double nu = cfg.packing_fraction;
  const double z = henderson_z(nu);
  if (cfg.inflow_speed > 0.0) m.inflow_boost = cfg.temperature * (z - 1.0) / (cfg.mass * cfg.inflow_speed);
  if (cfg.prefill) m.prefill();
  m.next_insert = -std::log(m.rng.uniform_open0()) / m.rate_total;
}

FlowSimulation::~FlowSimulation() = default;
FlowSimulation::FlowSimulation(FlowSimulation&&) noexcept = default;
FlowSimulation& FlowSimulation::operator=(FlowSimulation&&) noexcept = default;

void FlowSimulation::run_until(double t) {
  Impl& m = *impl_;
  while (m.next_insert <= t) {
    m.engine.run_until(m.next_insert);
    if (scene::interrupted()) return;
    m.insert_one();
    m.next_insert += -std::log(m.rng.uniform_open0()) / m.rate_total;
  }
  m.engine.run_until(t);
}

double FlowSimulation::time() const { return impl_->engine.time(); }
Stats FlowSimulation::stats() const { return impl_->engine.stats(); }
const FlowConfig& FlowSimulation::config() const { return impl_->cfg; }
const Engine& FlowSimulation::engine() const { return impl_->engine; }

}  // namespace granular
