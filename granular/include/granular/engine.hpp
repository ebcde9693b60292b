#pragma once
// Event-driven hard-disk engine (docs/granular_engine.md).
//
// Units: lengths in particle diameters d = 1 of the reference species, masses
// in its mass m = 1, times in d / sqrt(T/m) of the initial / inflow
// temperature. Disks fly freely (straight lines, or parabolas under a uniform
// force) between instantaneous binary collisions; every event is predicted
// exactly and processed in time order.
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "scene/vec2.hpp"

namespace granular {

using scene::Vec2;

struct Stats {
  std::uint64_t collisions = 0;       // all collisions (disk-disk + wall + vertex)
  std::uint64_t disk_collisions = 0;
  std::uint64_t wall_collisions = 0;  // walls and vertices
  std::uint64_t recoveries = 0;       // overlaps beyond round-off that were repaired
  std::uint64_t inserted = 0;         // open boundaries: particles added
  std::uint64_t removed = 0;          // open boundaries: particles that left
  double max_overlap = 0.0;           // largest overlap depth seen, in diameters
  double kinetic_energy = 0.0;        // sum m v^2 / 2 at time
  std::size_t particles = 0;          // particles now in the system
  double time = 0.0;                  // simulated time
};

// What the event loop spent its events on (a diagnostic for benchmarks; not
// saved by checkpoints, so a restored engine counts from zero).
struct EventCounts {
  std::uint64_t events = 0;          // calendar entries processed (all kinds below)
  std::uint64_t cell_crossings = 0;  // cell-face crossings, removals at open faces included
  std::uint64_t repredictions = 0;   // collisions found stale (the partner had changed course)
  std::uint64_t wall_rechecks = 0;   // wall look-ups repeated at their horizon (drifting grid)
};

// A particle species: every disk belongs to one.
struct Species {
  double radius = 0.5;
  double mass = 1.0;
  double restitution_wall = 1.0;    // against walls
  double restitution_vertex = 1.0;  // against vertices (segment end points)
};

// An oriented line segment. Only its outer side collides: the outward normal
// is perp(b - a) (left of travel from a to b). `restitution` < 0 means: use
// the colliding species' restitution_wall.
struct Wall {
  Vec2 a, b;
  double restitution = -1.0;
};

// A zero-radius, infinitely massive disk (a convex corner or a segment end).
// `restitution` < 0: use the species' restitution_vertex.
struct Vertex {
  Vec2 p;
  double restitution = -1.0;
};

// What happens when a disk centre crosses a face of the simulated rectangle.
enum class Face : std::uint8_t {
  closed,    // walls keep disks inside (add Wall segments); crossing is a recovered error
  periodic,  // both faces of the axis must be periodic
  open,      // the disk leaves the system (counted in Stats::removed)
};

// How far ahead the event loop asks for the memory of coming events. A speed
// hint only: trajectories are the same bit for bit whatever it is.
enum class LookAhead : std::uint8_t {
  automatic,  // `full` once the particle arrays outgrow the caches (~32 MB)
  records,    // the coming events' own records only
  full,       // also their partners, cell heads and neighbours
};

struct EngineConfig {
  double xmin = 0, xmax = 10, ymin = 0, ymax = 10;
  Face left = Face::periodic, right = Face::periodic;
  Face bottom = Face::periodic, top = Face::periodic;
  std::vector<Species> species{Species{}};
  // Disk-disk restitution, species x species (row-major); empty: all 1.
  std::vector<double> restitution;
  std::vector<Wall> walls;
  std::vector<Vertex> vertices;
  Vec2 gravity{0, 0};
  // TC model (Luding & McNamara): a collision within tc of either disk's
  // previous collision is elastic, so inelastic collapse cannot stall a run.
  double tc = 0.0;
  // Disk-disk impacts with a normal approach speed below this are elastic
  // (a speed-dependent restitution, as of viscoelastic disks); 0: none.
  double elastic_below = 0.0;
  // Smallest cell side; 0: the largest diameter. Cells are never smaller
  // than the largest diameter.
  double min_cell = 0.0;
  // Speed (along +x) at which the cell grid drifts; 0: a fixed grid. In a
  // stream the cells move with the gas, so that a disk crosses cell faces
  // at its thermal speed instead of the stream's: far fewer events. Walls
  // and vertices are then looked up in a fixed grid of their own, and the
  // x faces of the rectangle must not be periodic.
  double grid_speed = 0.0;
  // Not saved by checkpoints (it changes no result).
  LookAhead look_ahead = LookAhead::automatic;
};

// Hot per-disk state, exactly one cache line: everything a neighbour scan
// reads. Lazy clock: the state is at time t.
struct alignas(64) Particle {
  double x, y, vx, vy, t;
  double last_coll;      // time of the previous collision (TC model)
  std::uint32_t count;   // collision counter: a change invalidates predictions
  std::int32_t next;     // next disk in the same cell (-1: end)
  std::int32_t cell;     // current cell
  std::uint16_t species;
  std::uint16_t alive;
};

class Engine {
 public:
  explicit Engine(EngineConfig cfg);
  ~Engine();
  Engine(Engine&&) noexcept;
  Engine& operator=(Engine&&) noexcept;
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  // Adds a disk at the current time. Throws scene::InputError when it would
  // overlap another disk or a wall (beyond round-off) or lies outside.
  std::size_t add(Vec2 r, Vec2 v, int species = 0);
  // As add(), but returns false instead of throwing on overlap.
  bool try_add(Vec2 r, Vec2 v, int species = 0);
  // Room for n disks without reallocation (memory: no growth slack).
  void reserve(std::size_t n);
  // Builds the event calendar; called automatically by the first run.
  void start();

  // Processes every event with time <= t, then sets time() = t. Returns
  // early (state consistent, time() = time of the last event) when
  // scene::interrupted() or `max_collisions` total collisions are reached.
  void run_until(double t, std::uint64_t max_collisions = std::numeric_limits<std::uint64_t>::max());
  // Processes events until `n` more collisions happened (or interrupted).
  void run_collisions(std::uint64_t n);

  double time() const;
  Stats stats() const;  // kinetic_energy computed at time() (O(N))
  Stats stats_light() const;  // counters only: kinetic_energy and particles left 0
  EventCounts event_counts() const;
  Vec2 cell_size() const;  // side of the cell grid's cells along x and y (diameters)
  const EngineConfig& config() const;

  // f(Vec2 r, Vec2 v) at time() for every disk in the system.
  template <class F>
  void for_each_particle(F&& f) const {
    for_each_particle_species([&](Vec2 r, Vec2 v, int) { f(r, v); });
  }
  // Same with the particle's species: f(r, v, species). Each disk's lazy
  // clock is advanced to time() along its exact (parabolic) free flight.
  template <class F>
  void for_each_particle_species(F&& f) const {
    const double now = time();
    const Vec2 g = config().gravity;
    for (const Particle& p : particles()) {
      if (!p.alive) continue;
      const double dt = now - p.t;
      f(Vec2{p.x + p.vx * dt + 0.5 * g.x * dt * dt, p.y + p.vy * dt + 0.5 * g.y * dt * dt},
        Vec2{p.vx + g.x * dt, p.vy + g.y * dt}, static_cast<int>(p.species));
    }
  }
  // Slot storage (dead slots have alive == 0); states are at their own
  // clocks. Slots are renumbered now and then (spatial sorting).
  std::span<const Particle> particles() const;

  // Collisional virial sum_collisions r_ij . dp_i accumulated since the last
  // reset, and the time-integral of the kinetic energy since then (for the
  // compressibility factor p/(nT) = 1 + virial / (2 * int E dt) in 2D).
  void reset_measurement();
  double virial_sum() const;
  double measurement_time() const;
  double energy_time_integral() const;  // int E_kin dt (exact without gravity)

  // Checkpoint / restart: the restored engine continues bit-identically.
  void save(std::ostream& out) const;
  static Engine load(std::istream& in);

  // Bytes held per particle slot (engine data structures, for the benchmark).
  double bytes_per_particle() const;

  struct Impl;  // internal (src/engine/engine_impl.hpp)

 private:
  std::unique_ptr<Impl> impl_;
};

// Open-boundary supersonic stream (everything in diameters).
struct FlowConfig {
  double xmin = 0, xmax = 100, ymin = 0, ymax = 100;
  bool symmetric = false;  // y = ymin is a symmetry plane: specular, elastic mirror wall
  // Polylines of the body surface, each traversed with the body on its RIGHT
  // (outward normal = perp(tangent), left of travel). Segments are one-sided
  // walls; chain end points and convex interior points are vertices.
  std::vector<std::vector<Vec2>> body_chains;
  double inflow_speed = 3.0;      // U along +x
  double temperature = 1.0;       // inflow temperature T (m = 1): components ~ N(0, T)
  double packing_fraction = 0.05; // inflow nu = n pi d^2 / 4
  double radius = 0.5, mass = 1.0;
  double restitution = 1.0, restitution_wall = 1.0, tc = 0.0;
  double elastic_below = 0.0;  // EngineConfig::elastic_below (units of sqrt(T/m))
  Vec2 gravity{0, 0};
  std::uint64_t seed = 1;
  bool prefill = true;  // start with free stream filling the domain outside the body
  // Free-stream sides (y = ymax, and y = ymin unless symmetric):
  //  mirror:    elastic specular walls. For an undisturbed free stream this is
  //             exactly the Maxwellian in/outflux AND supplies the collisional
  //             pressure of the gas beyond (default; docs/granular_engine.md).
  //  open_flux: disks leave; Maxwellian influx inserted on the line. The
  //             missing collisional pressure lets the side gas expand
  //             (density -5% near the sides at nu = 0.1).
  enum class Sides { mirror, open_flux } sides = Sides::mirror;
  // Engine cell side in diameters; 0: automatic_cell() (from the inflow's
  // mean free path).
  double cell = 0.0;
  // Cells drift with the inflow speed (EngineConfig::grid_speed); false: a
  // fixed grid (the engine before 2026-12-02; same physics, more events).
  bool comoving_cells = true;
};

// The engine cell side FlowConfig::cell = 0 stands for (diameters): a
// third of the inflow gas's mean free path, at least one diameter.
double automatic_cell(const FlowConfig& c);

class FlowSimulation {
 public:
  explicit FlowSimulation(const FlowConfig& cfg);
  ~FlowSimulation();
  FlowSimulation(FlowSimulation&&) noexcept;
  FlowSimulation& operator=(FlowSimulation&&) noexcept;

  // Processes all events up to simulated time t (inflow insertions
  // included); returns early, state consistent, if scene::interrupted().
  void run_until(double t);
  double time() const;
  Stats stats() const;
  const FlowConfig& config() const;
  const Engine& engine() const;

  template <class F>
  void for_each_particle(F&& f) const {
    engine().for_each_particle(std::forward<F>(f));
  }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace granular
