#pragma once
// Time-averaged fields on a uniform lattice over the scene's domain.
// Particles are binned by centre; each block (an averaging group of one
// replica) keeps plain sums so blocks add exactly across threads and MPI
// ranks, and the spread between blocks gives the per-cell standard error.
#include <algorithm>
#include <cstddef>
#include <vector>

#include "granular/flow_setup.hpp"
#include "scene/lattice.hpp"
#include "scene/vec2.hpp"

namespace granular {

// Empty lattice (geometry only) spanning the setup's domain, nx x ny cells,
// in scene coordinates.
scene::Lattice flow_lattice(const FlowSetup& f, int nx, int ny);

// Sums over snapshots, for one block: per cell count, sum vx, sum vy,
// sum vx^2, sum vy^2, plus the snapshot count. One flat vector so that a
// reduction is a plain element-wise sum; a cell's five sums lie side by
// side, so binning a disk touches one cache line, not five arrays
// (snapshot_binning.hpp says why that matters).
class FieldSums {
 public:
  FieldSums() = default;
  explicit FieldSums(std::size_t cells) : data_(kArrays * cells + 1, 0.0), cells_(cells) {}
  enum Array : std::size_t { count = 0, sum_u, sum_v, sum_uu, sum_vv, kArrays };
  void add(std::size_t cell, scene::Vec2 v) {
    double* const d = &data_[kArrays * cell];
    d[count] += 1.0;
    d[sum_u] += v.x;
    d[sum_v] += v.y;
    d[sum_uu] += v.x * v.x;
    d[sum_vv] += v.y * v.y;
  }
  // Where a cell's sums start (kArrays doubles), for a prefetch.
  const double* cell_data(std::size_t cell) const { return &data_[kArrays * cell]; }
  void end_snapshot() { data_.back() += 1.0; }
  double at(Array a, std::size_t cell) const { return data_[kArrays * cell + a]; }
  double snapshots() const { return data_.empty() ? 0.0 : data_.back(); }
  std::size_t cells() const { return cells_; }
  std::vector<double>& raw() { return data_; }
  const std::vector<double>& raw() const { return data_; }
  void operator+=(const FieldSums& o) {
    for (std::size_t k = 0; k < data_.size(); ++k) data_[k] += o.data_[k];
  }
  void operator-=(const FieldSums& o) {
    for (std::size_t k = 0; k < data_.size(); ++k) data_[k] -= o.data_[k];
  }

 private:
  std::vector<double> data_;
  std::size_t cells_ = 0;
};

// Maps an engine-frame disk centre to its scene lattice cell (bin_snapshot,
// granular/src/flow/snapshot_binning.hpp, bins a whole snapshot with it).
class Binner {
 public:
  Binner(const FlowSetup& f, const scene::Lattice& geometry);
  // Cell index of an engine-frame position, or npos outside the lattice.
  // Inline: it runs for every disk at every snapshot.
  std::size_t cell_of(scene::Vec2 r_engine) const;
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

 private:
  double inv_scale_, x0_, y0_, inv_dx_, inv_dy_;
  int nx_, ny_;
};

inline std::size_t Binner::cell_of(scene::Vec2 r) const {
  const double fx = (r.x * inv_scale_ - x0_) * inv_dx_;
  const double fy = (r.y * inv_scale_ - y0_) * inv_dy_;
  if (!(fx >= 0.0 && fy >= 0.0)) return npos;
  // A disk exactly on the far edge belongs to the last cell.
  const int i = std::min(static_cast<int>(fx), nx_ - 1);
  const int j = std::min(static_cast<int>(fy), ny_ - 1);
  if (fx > nx_ || fy > ny_) return npos;
  return static_cast<std::size_t>(i + nx_ * j);
}

// Fields from the blocks (pooled sums for values, block spread for the _se
// fields): volume_fraction, number_density, u, v, temperature, pressure,
// mach, samples, inside_body, volume_fraction_se, u_se, v_se. Units: disks
// per d^2, velocities in sqrt(T/m) of the inflow, temperature in inflow T,
// pressure in T/d^2 (Henderson's Z times n T).
scene::Lattice make_fields(const FlowSetup& f, const scene::Lattice& geometry,
                           const std::vector<FieldSums>& blocks);

// The fields a shock locator reads (volume_fraction, v, samples, and the
// body mask) of each averaging group on its own, from the pooled `fields`
// (make_fields of the same groups) and the groups' sums. Fewer than two
// groups: none.
std::vector<scene::Lattice> make_group_fields(const scene::Lattice& fields,
                                              const std::vector<FieldSums>& groups);

}  // namespace granular
