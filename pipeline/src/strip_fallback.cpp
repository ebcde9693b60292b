#include "pipeline/strip_fallback.hpp"

#include "pipeline/one_scheme.hpp"
#include "scene/progress.hpp"

namespace pipeline {

bool strips_diverged(const GridRun& r, const std::string& robust_scheme) {
  return r.strips && r.fell_back && r.scheme == robust_scheme;
}

void remesh_isotropic(GridRunner& grids, std::vector<GridRun>& family, const ShockInput& shock,
                      const PrimaryError& primary) {
  if (family.empty()) return;
  scene::log_line(
      "pipeline: " + level_name(family.back().family, family.back().level) +
          " diverged on its shock-aligned strips; the clustered family is meshed with the "
          "isotropic band from here on",
      true);
  GridVariant isotropic;
  isotropic.isotropic = true;
  for (GridRun& r : family)
    r = charge_first_run(
        r, grids.run(r.family, r.level, shock, primary, isotropic),
        "meshed again with the isotropic band and solved with the scene's settings, "
        "since a strip grid of its family diverged");
}

}  // namespace pipeline
