// Validation box scenes: lattice start, Maxwellian velocities, run, summary.
#include "granular/box_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "granular/box_setup.hpp"
#include "granular/engine.hpp"
#include "granular/particle_budget.hpp"
#include "rng.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"
#include "scene/units.hpp"

namespace granular {

namespace {

// particles and packing_fraction, when both given, must agree this well.
constexpr double kCountAgreement = 0.005;
// Collisions per particle when the scene sets neither collisions nor time.
constexpr double kDefaultCollisionsPerParticle = 100.0;
// Collisions between progress updates / interrupt checks.
constexpr std::uint64_t kChunk = 200000;
// Hexagonal close packing of disks: no box start can hold more.
constexpr double kClosePacking = 0.9069;

std::string where(const scene::Scene& s) {
  return (s.source_file.empty() ? std::string("<scene>") : s.source_file) + ": granular: ";
}

}  // namespace

BoxSetup resolve_box(const scene::Scene& s) {
  if (!s.box) throw scene::InputError(where(s) + "not a box scene (no box: section)");
  const scene::Box& b = *s.box;
  const scene::GranularParams& g = s.granular;
  BoxSetup out;
  out.width = b.width;
  out.height = b.height;
  out.periodic = b.periodic;
  const double area = b.width * b.height;
  if (g.particles && g.packing_fraction) {
    const double want = *g.packing_fraction * area / scene::kDiskArea;
    if (std::abs(want - static_cast<double>(*g.particles)) > kCountAgreement * want) {
      std::ostringstream m;
      m << where(s) << "particles (" << *g.particles << ") and packing_fraction (" << *g.packing_fraction
        << ") disagree: that packing fraction means " << std::llround(want) << " particles in this box";
      throw scene::InputError(m.str());
    }
    out.particles = *g.particles;
  } else if (g.particles) {
    out.particles = *g.particles;
  } else if (g.packing_fraction) {
    out.particles = std::llround(*g.packing_fraction * area / scene::kDiskArea);
  } else {
    throw scene::InputError(where(s) + "a box scene needs particles or packing_fraction");
  }
  if (out.particles < 1) throw scene::InputError(where(s) + "no particles in the box");
  check_particle_budget(static_cast<double>(out.particles), 1, where(s) + "key 'granular.particles': ");
  out.packing_fraction = static_cast<double>(out.particles) * scene::kDiskArea / area;
  if (!(out.packing_fraction < kClosePacking)) {
    std::ostringstream m;
    m << where(s) << "key 'granular.particles': " << out.particles << " disks in a " << b.width << " x " << b.height
      << " box give packing fraction " << out.packing_fraction << ", at or beyond close packing (" << kClosePacking
      << ")";
    throw scene::InputError(m.str());
  }
  out.restitution = g.restitution;
  out.restitution_wall = g.restitution_wall.value_or(g.restitution);
  out.tc = g.tc;
  out.gravity = g.gravity;
  out.seed = g.seed;
  return out;
}

Engine make_box_engine(const BoxSetup& b) {
  EngineConfig c;
  c.xmin = 0; c.xmax = b.width; c.ymin = 0; c.ymax = b.height;
  const Face f = b.periodic ? Face::periodic : Face::closed;
  c.left = c.right = c.bottom = c.top = f;
  c.species = {Species{0.5, 1.0, b.restitution_wall, b.restitution_wall}};
  c.restitution = {b.restitution};
  c.gravity = b.gravity;
  c.tc = b.tc;
  c.min_cell = b.min_cell;
  c.look_ahead = b.look_ahead;
  if (!b.periodic) {
    // Counter-clockwise: the inside is on the left of travel.
    const Vec2 p0{0, 0}, p1{b.width, 0}, p2{b.width, b.height}, p3{0, b.height};
    c.walls = {{p0, p1, -1.0}, {p1, p2, -1.0}, {p2, p3, -1.0}, {p3, p0, -1.0}};
  }
  Engine eng(std::move(c));
  eng.reserve(static_cast<std::size_t>(b.particles));
  // Square lattice of at least N sites, occupied at random; spacing must
  // exceed a diameter (packing fractions up to pi/4 * (1 - margin)).
  const auto n = static_cast<std::size_t>(b.particles);
  auto nx = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n) * b.width / b.height)));
  nx = std::max<std::size_t>(nx, 1);
  const std::size_t ny = (n + nx - 1) / nx;
  const double dx = b.width / static_cast<double>(nx), dy = b.height / static_cast<double>(ny);
  if (dx <= 1.0 || dy <= 1.0)
    throw scene::InputError("granular: box: packing fraction " + std::to_string(b.packing_fraction) +
                            " is too high for the lattice start (a square lattice of " +
                            std::to_string(nx) + " x " + std::to_string(ny) +
                            " sites in this box is closer than a diameter)");
  detail::Rng rng(b.seed);
  std::vector<std::size_t> sites(nx * ny);
  for (std::size_t k = 0; k < sites.size(); ++k) sites[k] = k;
  for (std::size_t k = 0; k < n; ++k) {  // partial Fisher-Yates
    const std::size_t j = k + static_cast<std::size_t>(rng.uniform() * static_cast<double>(sites.size() - k));
    std::swap(sites[k], sites[std::min(j, sites.size() - 1)]);
  }
  std::vector<Vec2> v(n);
  Vec2 mean{0, 0};
  for (auto& vi : v) {
    vi = {rng.normal(), rng.normal()};
    mean += vi;
  }
  mean = mean / static_cast<double>(n);
  double ke = 0.0;
  for (auto& vi : v) {
    vi -= mean;  // zero total momentum
    ke += 0.5 * norm2(vi);
  }
  // Exactly T = 1: E = N T in two dimensions (k = m = 1).
  const double scale = ke > 0.0 ? std::sqrt(static_cast<double>(n) / ke) : 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t site = sites[k];
    const Vec2 r{(static_cast<double>(site % nx) + 0.5) * dx, (static_cast<double>(site / nx) + 0.5) * dy};
    eng.add(r, scale * v[k]);
  }
  return eng;
}

namespace {

constexpr char kBoxMagic[8] = {'G', 'R', 'A', 'N', 'B', 'O', 'X', '1'};

// Run phase and the numbers a restarted run needs, stored before the engine.
struct BoxCheckpoint {
  std::int32_t phase = 0;  // 0: melting, 1: measuring
  double energy_initial = 0.0;
};

void write_checkpoint(const std::string& path, const BoxCheckpoint& c, const Engine& eng) {
  scene::write_stream_atomic(path, [&](std::ostream& os) {
    os.write(kBoxMagic, sizeof(kBoxMagic));
    os.write(reinterpret_cast<const char*>(&c.phase), sizeof(c.phase));
    os.write(reinterpret_cast<const char*>(&c.energy_initial), sizeof(c.energy_initial));
    eng.save(os);
  });
}

Engine read_checkpoint(const std::string& path, BoxCheckpoint& c) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw scene::InputError(path + ": cannot open checkpoint");
  char magic[sizeof(kBoxMagic)] = {};
  in.read(magic, sizeof(magic));
  in.read(reinterpret_cast<char*>(&c.phase), sizeof(c.phase));
  in.read(reinterpret_cast<char*>(&c.energy_initial), sizeof(c.energy_initial));
  if (!in || std::memcmp(magic, kBoxMagic, sizeof(kBoxMagic)) != 0)
    throw scene::InputError(path + ": not a granular box checkpoint");
  return Engine::load(in);
}

}  // namespace

nlohmann::json run_box_scene(const scene::Scene& s, const RunOptions& o) {
  const BoxSetup b = resolve_box(s);
  const scene::GranularParams& g = s.granular;
  BoxCheckpoint ck;
  Engine eng = o.restart.empty() ? make_box_engine(b) : read_checkpoint(o.restart, ck);
  eng.start();
  if (o.restart.empty()) ck.energy_initial = eng.stats().kinetic_energy;
  if (!o.restart.empty() && eng.stats().particles != static_cast<std::size_t>(b.particles))
    throw scene::InputError(o.restart + ": checkpoint does not match the scene's box (particle count)");
  const double n = static_cast<double>(b.particles);
  const bool by_time = g.time.has_value() && !g.collisions.has_value();
  const double total = by_time ? *g.time : g.collisions.value_or(kDefaultCollisionsPerParticle * n);
  const std::string ck_path = o.out_dir + "/checkpoint.bin";
  const auto ck_every = static_cast<std::uint64_t>(g.checkpoint_interval.value_or(0.0));
  std::uint64_t next_ck = ck_every ? (eng.stats_light().collisions / ck_every + 1) * ck_every : 0;
  if (ck_every) scene::make_dirs(o.out_dir);
  bool stopped = false;
  auto should_stop = [&] {
    stopped = stopped || scene::interrupted() ||
              (o.stop_after_collisions && eng.stats_light().collisions >= o.stop_after_collisions);
    return stopped;
  };
  // The first half melts the lattice; the equation of state and the
  // temperature are measured over the second half.
  const auto clock0 = std::chrono::steady_clock::now();
  scene::Progress progress("granular " + s.name, total, by_time ? "time" : "collisions");
  auto run_to = [&](double target) {
    while (!should_stop()) {
      const std::uint64_t coll = eng.stats_light().collisions;
      const double done = by_time ? eng.time() : static_cast<double>(coll);
      if (done >= target) break;
      // Chunks end at checkpoints and at stop_after_collisions; chunking
      // does not change the sequence of events.
      std::uint64_t chunk = kChunk;
      if (next_ck) chunk = std::min(chunk, next_ck - coll);
      if (o.stop_after_collisions > coll) chunk = std::min(chunk, o.stop_after_collisions - coll);
      if (by_time) {
        eng.run_until(std::min(target, eng.time() + std::max(target / 100.0, 1e-12)), coll + chunk);
      } else {
        const auto left = static_cast<std::uint64_t>(target - done);
        eng.run_collisions(std::min<std::uint64_t>(std::max<std::uint64_t>(left, 1), chunk));
      }
      const std::uint64_t now_coll = eng.stats_light().collisions;
      if (next_ck && now_coll >= next_ck) {
        write_checkpoint(ck_path, ck, eng);
        next_ck += ck_every;
      }
      progress.update(by_time ? eng.time() : static_cast<double>(now_coll));
    }
  };
  if (ck.phase == 0) {
    run_to(0.5 * total);
    if (!should_stop()) {
      eng.reset_measurement();
      ck.phase = 1;
    }
  }
  if (ck.phase == 1) run_to(total);
  if (ck_every) write_checkpoint(ck_path, ck, eng);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock0).count();
  progress.finish();
  const Stats s1 = eng.stats();
  nlohmann::json j;
  j["particles"] = s1.particles;
  j["collisions"] = s1.collisions;
  j["disk_collisions"] = s1.disk_collisions;
  j["wall_collisions"] = s1.wall_collisions;
  j["recoveries"] = s1.recoveries;
  j["wall_seconds"] = wall;
  j["collisions_per_second"] = wall > 0 ? static_cast<double>(s1.collisions) / wall : 0.0;
  j["energy_initial"] = ck.energy_initial;
  j["energy_final"] = s1.kinetic_energy;
  j["max_overlap"] = s1.max_overlap;
  j["packing_fraction"] = b.packing_fraction;
  j["time"] = s1.time;
  j["temperature"] = s1.kinetic_energy / n;  // E = N T in 2D
  const double eint = eng.energy_time_integral();
  const bool measured = eng.measurement_time() > 0.0 && eint > 0.0 && b.gravity == Vec2{0, 0};
  j["compressibility_factor"] = measured ? nlohmann::json(1.0 + eng.virial_sum() / (2.0 * eint)) : nlohmann::json(nullptr);
  j["mean_temperature"] = measured ? nlohmann::json(eint / (n * eng.measurement_time())) : nlohmann::json(nullptr);
  Vec2 mom{0, 0};
  eng.for_each_particle([&](Vec2, Vec2 v) { mom += v; });
  j["momentum"] = {mom.x, mom.y};
  j["restitution"] = b.restitution;
  j["seed"] = b.seed;
  j["periodic"] = b.periodic;
  j["bytes_per_particle"] = eng.bytes_per_particle();
  j["interrupted"] = stopped;
  j["partial"] = stopped;  // fewer collisions (or less time) than requested
  scene::make_dirs(o.out_dir);
  scene::write_json_atomic(o.out_dir + "/summary.json", j);
  return j;
}

}  // namespace granular
