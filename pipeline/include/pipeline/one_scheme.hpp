#pragma once
// One scheme per comparison. A grid whose run with the scene's scheme
// diverged where no written state could bridge it ends on the robust scheme
// (cfd::robust_settings: Tadmor, Minmod); its family's errors then mix two
// schemes' truncation errors, not monotone in h, and the families compare
// schemes as much as grids. So once some grid of the comparison ends on the
// robust scheme, every grid that ended on another is solved again with the
// robust settings from the start, and charged both runs.
#include <string>
#include <vector>

#include "pipeline/compare.hpp"
#include "pipeline/grid_runs.hpp"

namespace pipeline {

// True when the runs' schemes differ and one of them is `robust`.
bool needs_one_scheme(const std::vector<GridRun>& clustered, const std::vector<GridRun>& uniform,
                      const std::string& robust);

// `again` (the grid solved robust from the start) charged with `first`'s CFD
// CPU, wall seconds and steps, and noted.
GridRun charge_first_run(const GridRun& first, GridRun again);

// Both families on one scheme (above); true when the comparison went over to
// the robust scheme. A grid whose robust run fails keeps its first run, noted.
bool share_one_scheme(GridRunner& grids, std::vector<GridRun>& clustered,
                      std::vector<GridRun>& uniform, const ShockInput& shock,
                      const PrimaryError& primary);

}  // namespace pipeline
