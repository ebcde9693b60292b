#pragma once
// Clustered grids whose shock-aligned strips make the scene's scheme
// diverge. On strong oblique shocks (wedges at Mach 5.5 / 27 deg, 7 / 25,
// 6.5 / 30: pressure ratios 13-20) Kurganov + vanLeer diverged in the
// start-up transient on clustered grids with strips from 547 cells up, where
// the isotropic band at the same sizes held it on every level of the first
// two (docs/reliability.md, "Strong oblique shocks"). The robust scheme that
// then ran gave 1.4-1.8x the error per grid, so the family lost to uniform
// grids that held Kurganov. So the first time a strip grid ends on the robust
// scheme, the clustered family goes over to the isotropic band: that grid
// and those before it are meshed again without strips and solved with the
// scene's settings (each charged its strip run, mesh and CFD), and the levels
// after it are made so directly.
#include <string>
#include <vector>

#include "pipeline/compare.hpp"
#include "pipeline/grid_runs.hpp"

namespace pipeline {

// True when `r` calls for the isotropic band: its band holds strips and its
// run ended on the robust scheme after diverging.
bool strips_diverged(const GridRun& r, const std::string& robust_scheme);

// Every grid of the family meshed again with the isotropic band and solved
// with the scene's settings, charged its strip run.
void remesh_isotropic(GridRunner& grids, std::vector<GridRun>& family, const ShockInput& shock,
                      const PrimaryError& primary);

}  // namespace pipeline
