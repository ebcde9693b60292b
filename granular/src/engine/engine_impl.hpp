#pragma once
// Engine internals, shared by the event loop (engine.cpp), setup
// (engine_setup.cpp) and checkpointing (checkpoint.cpp).
#include <cstdint>
#include <vector>

#include "calendar.hpp"
#include "huge_alloc.hpp"
#include "granular/engine.hpp"

namespace granular {

namespace detail {

enum class EventType : std::uint8_t { none, disk, wall, vertex };

// What Slot::cell_t is the time of: a face of the disk's cell, or (drifting
// grid only) the rectangle's x faces and the wall look-up's horizon.
enum CellEvent : std::uint8_t {
  FACE_LEFT,
  FACE_RIGHT,
  FACE_BOTTOM,
  FACE_TOP,
  EXIT_LEFT,
  EXIT_RIGHT,
  WALL_RECHECK
};

// Cold per-slot state: the slot's earliest collision prediction and its
// next cell crossing, kept apart so that a cell crossing does not cost the
// collision prediction (only the newly adjacent cells are scanned).
struct Slot {
  double coll_t;          // predicted collision time (kNever: none)
  double cell_t;          // next cell-face crossing
  std::int32_t partner;   // disk slot, wall or vertex index
  std::uint32_t pcount;   // partner's collision counter when predicted
  EventType type;
  std::uint8_t cell_dir;   // CellEvent
  std::uint8_t timer_dir;  // drifting grid: CellEvent of Impl::timer_t (EXIT_* or WALL_RECHECK)
  std::uint32_t qver;     // calendar version: only the entry carrying it is live

  double key() const { return coll_t < cell_t ? coll_t : cell_t; }  // next event time
  bool crossing_first() const { return cell_t <= coll_t; }          // next event is a cell crossing
};

// The walls and vertices of a cell of the fixed look-up grid: the first of
// each in Impl::wall_list / vertex_list (the next cell's first ends them),
// and (drifting grid) how far a disk in the cell may travel before it must
// look again, rounded down. One 16-byte record: a look-up reads one line.
struct SurfaceCell {
  std::int32_t walls = 0, vertices = 0;
  float clear = 0.0f;
  std::int32_t unused = 0;
};

struct WallGeom {
  Vec2 a, n, t;  // start, outward unit normal, unit tangent
  double length;
  double e;      // < 0: species value
};

}  // namespace detail

struct Engine::Impl {
  EngineConfig cfg;
  // Species tables.
  std::vector<double> radius, mass, e_wall, e_vertex, e_disk;  // e_disk: ns x ns
  std::size_t ns = 1;
  double max_diameter = 1.0;
  // Grid.
  // A cell is named by its column and row packed in one int (cx | cy << 16),
  // so that finding its neighbours costs no integer division. The list
  // heads are stored in tiles of 4 x 4 cells, one cache line each: a 3 x 3
  // block of heads spans 2.25 lines on average instead of ~3.4 in row
  // order (the heads were a sixth of the cache misses at N = 10^6).
  static constexpr int kCellBits = 16;
  static constexpr int kMaxCellsPerSide = (1 << (kCellBits - 1)) - 1;  // cy << 16 fits an int
  static constexpr std::uint32_t kTile = 4;
  static int pack_cell(int cx, int cy) { return cx | (cy << kCellBits); }
  static int cell_x(int c) { return c & ((1 << kCellBits) - 1); }
  static int cell_y(int c) { return c >> kCellBits; }
  // The tiled head index is a column share plus a row share.
  static std::uint32_t head_col(int cx) {
    const auto x = static_cast<std::uint32_t>(cx);
    return (x / kTile) * kTile * kTile + x % kTile;
  }
  std::uint32_t head_row(int cy) const {
    const auto y = static_cast<std::uint32_t>(cy);
    return (y / kTile) * tiles_x * kTile * kTile + (y % kTile) * kTile;
  }
  std::size_t head_index(int c) const { return head_row(cell_y(c)) + head_col(cell_x(c)); }
  std::size_t linear_cell(int c) const {  // row-major index (wall and vertex tables)
    return static_cast<std::size_t>(cell_y(c)) * static_cast<std::size_t>(ncx) +
           static_cast<std::size_t>(cell_x(c));
  }
  // The (up to) nine cells of the 3 x 3 block around a cell, in row order,
  // with their periodic image shifts.
  struct Block {
    int n = 0;
    std::uint32_t head[9];
    double shx[9], shy[9];
  };
  void block_of(int cell, Block& b) const;
  int ncx = 1, ncy = 1;
  std::uint32_t tiles_x = 1;
  double cw = 1, ch = 1, lx = 1, ly = 1;
  bool periodic_x = false, periodic_y = false;
  // Columns wrap around (periodic x, or a drifting grid, whose columns are
  // numbered modulo ncx) with this image shift (0 for a drifting grid).
  bool wrap_x = false;
  double wrap_lx = 0.0;
  // Drifting grid (EngineConfig::grid_speed != 0): column k spans
  // [k cw, (k + 1) cw) in xi = x - xmin - drift * t and is stored as k
  // modulo ncx; ncx exceeds the columns the rectangle spans by spare ones,
  // so that columns on opposite sides never look adjacent. The rectangle's
  // x faces are then events of their own (EXIT_LEFT / EXIT_RIGHT).
  bool drifting = false;
  double drift = 0.0;
  double inv_cw = 1.0, inv_ncx = 1.0;
  std::vector<std::int32_t, detail::HugeAlloc<std::int32_t>> head;  // tiled cell -> first slot
  // Walls and vertices by cell of the fixed grid (the cell grid itself when
  // it does not drift; else a coarser fixed grid, wnx columns by wny
  // rows): surfaces[cell] .. surfaces[cell + 1] (empty without walls
  // and vertices). With a drifting grid a cell lists every item within the
  // disk radius plus the cell's `clear` of it, and a disk in the cell looks
  // again (WALL_RECHECK) once it may have travelled `clear`.
  int wnx = 1, wny = 1;
  double inv_wcw = 1.0, inv_wch = 1.0;
  std::vector<detail::SurfaceCell> surfaces;
  std::vector<std::int32_t> wall_list, vertex_list;
  // Drifting grid, per slot: the earliest of the disk's arrival at an x
  // face of the rectangle and its wall look-up horizon (Slot::timer_dir
  // says which). Both hold along the disk's path, so a crossing of the
  // drifting cells keeps them; only a new path (predict()) or the horizon
  // itself recomputes them.
  std::vector<double> timer_t;
  std::vector<detail::WallGeom> walls;
  // Particles.
  std::vector<Particle, detail::HugeAlloc<Particle>> p;
  std::vector<detail::Slot, detail::HugeAlloc<detail::Slot>> s;
  std::vector<std::int32_t> free_slots;
  detail::Calendar cal;
  bool started = false;
  double now = 0.0;
  // Statistics and measurement.
  Stats st;
  double energy = 0.0;        // running kinetic energy (changed at collisions)
  double virial = 0.0;        // sum r_ij . dp_i over disk collisions
  double meas_start = 0.0;
  double energy_integral = 0.0;
  double energy_since = 0.0;  // time energy_integral is accumulated to
  std::uint64_t events = 0;
  std::uint64_t crossings = 0;      // EventCounts::cell_crossings
  std::uint64_t rechecks = 0;       // EventCounts::wall_rechecks
  std::uint64_t repredictions = 0;  // EventCounts::repredictions
  // Start of the current inelastic-collapse window (check_collapse()).
  std::uint64_t window_events = 0;
  double window_time = 0.0;
  std::uint64_t next_reorder = 0;  // collision count of the next spatial sort
  bool full_look_ahead = false;    // prefetch stages two to four (choose_look_ahead())

  // RunError when the last window's event rate shows inelastic collapse.
  void check_collapse();
  bool reorder();  // true when the slots were renumbered (and the calendar rebuilt)
  void choose_look_ahead();  // from cfg.look_ahead and the arrays' size (reorder(), load())
  void init(EngineConfig c);
  // Geometry helpers.
  int cell_of(double x, double y) const;
  std::size_t wall_cell(double x, double y) const;  // fixed-grid cell of a point (drifting grid)
  double column_of(double xi, int cx) const;        // unwrapped column of stored column cx at xi
  void register_surfaces();
  void cell_insert(std::int32_t i, int c);
  void cell_remove(std::int32_t i, int c);
  bool overlaps(Vec2 r, int species, double tol, std::int32_t skip) const;
  // Event loop.
  void advance(Particle& q) const;
  void predict(std::int32_t i);
  void predict_cell(std::int32_t i);
  void predict_cell_drifting(std::int32_t i);
  void scan_surfaces(std::int32_t i, int c, double rx, double ry, double vx, double vy);
  void join_timer(std::int32_t i);
  bool neighbour_cell(int cx, int cy, int& cell, double& shx, double& shy) const;
  void scan_list(std::int32_t i, std::int32_t first, double shx, double shy, double rx, double ry,
                 double vx, double vy, double rad_i);
  void scan_cell_for(std::int32_t i, int cx, int cy, double rx, double ry, double vx, double vy,
                     double sig_i);
  void scan_walls_for(std::int32_t i, std::size_t wall_cell, double rx, double ry, double vx,
                      double vy);
  void schedule(std::int32_t i);
  void process(std::int32_t i);
  bool live(const detail::Calendar::Entry& e) const { return s[e.slot].qver == e.ver; }
  void prefetch_ahead();
  void prefetch_records(std::size_t i) const;
  std::size_t scan_partner(std::size_t i) const;
  int event_cell(std::size_t i) const;
  void prefetch_corner_heads(int cell) const;
  void prefetch_block_disks(int cell, std::size_t self) const;
  void prefetch_stage2(std::size_t i) const;
  void prefetch_stage3(std::size_t i) const;
  void prefetch_stage4(std::size_t i) const;
  void rebuild_calendar();
  void cross_cell(std::int32_t i);
  void leave_or_recheck(std::int32_t i);
  void collide_disks(std::int32_t i, std::int32_t j);
  void collide_surface(std::int32_t i, Vec2 normal, double e, double overlap);
  void remove(std::int32_t i);
  std::int32_t add_slot(Vec2 r, Vec2 v, int species);
  void integrate_energy();
  void build_all();
};

}  // namespace granular
