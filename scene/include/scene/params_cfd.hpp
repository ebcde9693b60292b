#pragma once
#include <optional>
#include <string>

namespace scene {

// `cfd:` section. Times in flow-through times (domain length / free-stream
// speed) unless a name says otherwise; see docs/cfd_cases.md.
struct CfdParams {
  double max_co = 0.3;             // rhoCentralFoam maxCo (0.5 leaves a noisy limit cycle at shocks)
  double end_time = 10.0;          // hard stop (flow-through times)
  double write_interval = 0.2;     // flow-through times between written times (steady checks)
  double steady_tol = 0.05;        // L2 density change per flow-through time, relative to rho_inf
  double force_tol = 2e-3;         // relative body-force change per flow-through time
  // ddt localEuler (rhoCentralFoam LTS); unset = auto: time-accurate
  // (LTS's steady stop is not yet trusted to reach the same solution).
  std::optional<bool> local_time_stepping;
  int np = 1;                      // MPI ranks (decomposePar / mpirun / reconstructPar)
  // Flux: Kurganov | Tadmor | auto (Kurganov, except Tadmor where a
  // free-stream start meets a sharp base inside the domain: a detached
  // wedge, whose base expansion diverges under Kurganov).
  std::string flux_scheme = "auto";
  // Reconstruction limiter: vanLeer | Minmod | auto (vanLeer for
  // attached-shock wedges, Minmod for blunt bodies: with vanLeer the Apollo
  // capsule at Mach 5 diverges at its afterbody).
  std::string limiter = "auto";
  double min_time = 1.0;           // flow-through times before a steady state may be declared
  int steady_checks = 2;           // consecutive written times that must meet both tolerances
  // Initial state: freestream | rest | auto (free stream for attached-shock
  // wedges, rest otherwise: an impulsive start behind a blunt body diverges).
  std::string start = "auto";
  // On divergence, restart once from the initial state with the robust
  // settings (Tadmor flux, Minmod limiter, half the Courant number),
  // recorded in the case's summary as `fallback`.
  bool fallback = true;
};

}  // namespace scene
