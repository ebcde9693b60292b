#pragma once
// Clustered grids whose shock-aligned strips make the scene's scheme
// diverge. On strong oblique shocks (wedges at Mach 5.5 / 27 deg, 6.5 / 30,
// 7 / 25: pressure ratios 13-20) Kurganov + vanLeer diverged in the start-up
// transient on clustered grids with strips from their second or third level
// on, where the uniform grids at the same h_min held it up to 12,681 cells
// and the isotropic band held it on every level (docs/reliability.md, "One
// scheme per family"). The robust scheme that then ran is about twice as
// inaccurate per cell, so the family lost to the uniform grids. So the first
// time a strip grid ends on the robust scheme, the clustered family goes over
// to the isotropic band: that grid and those before it are meshed again
// without strips and solved with the scene's settings (each charged its
// strip run, mesh and CFD), and the levels after it are made so directly.
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
