#pragma once

namespace scene {

// `cfd:` section. Times in body lengths / free-stream speed of sound.
struct CfdParams {
  double max_co = 0.5;             // rhoCentralFoam maxCo
  double end_time = 10.0;          // hard stop (flow-through times)
  double write_interval = 0.1;     // flow-through times between checks
  double steady_tol = 1e-3;        // relative density change per flow-through time
  double force_tol = 1e-3;         // relative body-force change per flow-through time
  bool local_time_stepping = false;
  int np = 1;
};

}  // namespace scene
