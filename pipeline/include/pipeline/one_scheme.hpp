#pragma once
// One scheme per family. A grid whose run with the scene's scheme diverged
// where no written state could bridge it ends on the robust scheme
// (cfd::robust_settings: Tadmor, Minmod); its family's errors then mix two
// schemes' truncation errors, not monotone in h, and the family's fit means
// nothing. So once some grid of a family ends on the robust scheme, every
// grid of that family that ended on another is solved again with the robust
// settings from the start, and charged both runs. The other family keeps the
// scheme that held on all its grids: a user would run each kind of grid with
// the most accurate scheme it stands, so where only the clustered grids
// need the robust scheme the verdict prices that.
#include <string>
#include <vector>

#include "pipeline/compare.hpp"
#include "pipeline/grid_runs.hpp"

namespace pipeline {

// True when the family's schemes differ and one of them is `robust`.
bool needs_one_scheme(const std::vector<GridRun>& family, const std::string& robust);

// `again` (the grid run once more, as `why` says) charged with `first`'s CFD
// CPU, wall seconds and steps, and its meshing CPU where `again` has its own
// mesh; noted.
GridRun charge_first_run(const GridRun& first, GridRun again, const std::string& why);

// The family on one scheme (above). `base`: how the family's grids were
// made (the robust runs keep their meshes). A grid whose robust run fails
// keeps its first run, noted.
void one_scheme(GridRunner& grids, std::vector<GridRun>& family, const ShockInput& shock,
                const PrimaryError& primary, GridVariant base = {});

// The scheme every grid of the family carries, "mixed (A, B)" when they
// differ, empty without CFD runs.
std::string family_scheme(const std::vector<GridRun>& family);

}  // namespace pipeline
