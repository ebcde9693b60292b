#pragma once
#include <cstdint>
#include <optional>

#include "scene/vec2.hpp"

namespace scene {

// `granular:` section. Lengths in particle diameters, masses in particle
// masses, times in d / sqrt(T_inflow/m) unless stated (docs/units.md).
// Disks in a flow domain at the inflow density when neither
// granular.body_diameters nor granular.particles is given.
inline constexpr double kDefaultFlowParticles = 9200.0;

// The averaging an attached shock's angle gets when the scene sets none. At
// 4 flow-through times one run's angle scatters by 0.27 deg (sd over seeds,
// 16 unseen wedges x 3 seeds), so no honest 95% interval can be within
// +-0.25 deg. With the groups' own fits' mean as the angle, 12 meets the
// angle, interval and CPU targets on 16 fresh wedges x 3 seeds (0.177 deg
// RMS, pairs 46 / 48, median half-width 0.236, every run under 10 CPU s;
// 16 cost a third more: docs/shockfit.md, "Twelve flow-through times?").
// Averaging longer moves no mean (16 against 4: -0.02 deg, 95% -0.13 to
// +0.09), so tables fitted at 4 serve. Bow shocks keep 4: their
// calibrations and bands were measured there.
inline constexpr double kAttachedShockAveraging = 12.0;

// Independent replicas (seeds) a run averages when the scene sets none.
inline constexpr int kDefaultReplicas = 2;
// A bow shock's standoff (the gas shock detached: discs, capsules, wedges
// beyond the maximum deflection) gets twice as many: at two the groups' 95%
// interval is +-3.0-3.6% of the standoff on discs, at four +-1.8-2.5%, and
// it still covers (docs/shockfit.md, "The groups' mean standoff"); longer
// averaging narrows the interval faster than the truth there (a bow shock
// wanders slowly), more replicas do not.
inline constexpr int kBowShockReplicas = 4;

struct GranularParams {
  // Box scenes: exactly as ../shared/contract.md.
  std::optional<std::int64_t> particles;
  std::optional<double> packing_fraction;
  double restitution = 1.0;            // disk-disk e, in (0, 1]
  bool restitution_given = false;      // set in the file (else the pipeline may calibrate it)
  std::optional<double> restitution_wall;  // disk-wall/vertex e; default = restitution
  std::uint64_t seed = 1;
  std::optional<double> collisions;    // stop after this many collisions
  std::optional<double> time;          // or after this simulated time
  std::optional<double> checkpoint_interval;  // box scenes: collisions between OUT/checkpoint.bin writes
  double tc = 1e-6;                    // TC model: collision within tc of the last is elastic
  // Flow scenes: disk-disk impacts slower than this (normal approach speed,
  // in units of the inflow's thermal speed sqrt(T_inflow/m)) are elastic, as
  // viscoelastic disks tend to e = 1 at low impact speed; 0: every impact
  // takes `restitution`. Keeps the free stream from cooling (its Mach number
  // rising downstream) while the shock's impacts, at about the stream speed,
  // stay dissipative (docs/calibration.md, "Discs with the stagnation-line
  // reference"). The calibration tables are fitted without it.
  double elastic_impact_speed = 0.0;
  Vec2 gravity{0.0, 0.0};              // uniform force per unit mass
  // Flow scenes.
  std::optional<double> mach;          // overrides freestream.mach for the granular gas
  // Defaults give a clean wedge M3/10 shock known to +-0.5 deg in ~10 s on
  // 2 cores (docs/granular_flow.md): mean free path ~2 d, body 300 d.
  double inflow_packing_fraction = 0.1;
  // Body length in particle diameters. Unset: the scale follows from
  // `particles` (disks in the domain at the inflow density), and with neither
  // given from kDefaultFlowParticles (the wedge M3/10 domain then holds a
  // 300 d wedge; blunt bodies, with larger domains, get smaller bodies).
  std::optional<double> body_diameters;
  int lattice_nx = 200;
  int lattice_ny = 200;
  std::optional<double> warmup;        // flow-through times; unset: detect steady state
  // Flow-through times averaged (no precision target). Unset: 4, or
  // kAttachedShockAveraging where the gas shock is attached (scene.cpp).
  double averaging = 4.0;
  bool averaging_given = false;  // set in the file (else a pipeline run may stop at its band)
  // Precision on demand (docs/granular_flow.md): average until the shock's
  // 95% position half-width (body lengths) is at most the target, the CPU
  // budget is spent, or max_averaging flow-through times are averaged. The
  // pipeline judges the half-width (it runs shockfit); unset: `averaging`.
  std::optional<double> target_half_width;  // body lengths
  bool target_from_mesh = false;  // `target_half_width: mesh`: k h_min of the finest clustered grid
  // `target_half_width: band`: an attached shock's angle interval small
  // against the calibrated band it widens (pipeline/precision_goal.hpp).
  bool target_from_band = false;
  // `target_half_width: standoff`: a bow shock's standoff interval at most a
  // fixed fraction of the standoff (pipeline/precision_goal.hpp).
  bool target_from_standoff = false;
  // Whether the scene asks for precision on demand (any of the four forms).
  [[nodiscard]] bool asks_precision() const {
    return target_half_width || target_from_mesh || target_from_band || target_from_standoff;
  }
  std::optional<double> cpu_budget;    // CPU seconds of the granular stage
  double max_averaging = 16.0;         // flow-through times, with a target
  // Independent seeds (seed, seed+1, ...). Unset: kDefaultReplicas, or
  // kBowShockReplicas where the gas shock is detached (scene.cpp).
  int replicas = kDefaultReplicas;
  bool replicas_given = false;         // set in the file (else a pipeline run may use fewer)
  bool snapshots = false;              // write particle snapshots
};

}  // namespace scene
