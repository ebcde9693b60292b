// shock.csv -> MeshRequest: the accepted shock points in file order, read by
// the shared reader (scene/shock_csv.hpp, whose errors name file, line and
// column).
#include "scene/shock_csv.hpp"

#include <cmath>

#include "meshgen/mesh.hpp"

namespace meshgen {

MeshRequest request_from_shock_csv(const std::string& path) {
  const scene::ShockCsv csv = scene::read_shock_csv(path);
  MeshRequest r;
  bool any_ci = false;
  for (const scene::ShockCsvRow& row : csv.rows) {
    if (!row.accepted) continue;
    r.shock_curve.push_back(row.shock);
    r.shock_ci.push_back(row.ci);
    any_ci = any_ci || std::isfinite(row.ci);
  }
  // No usable ci: the band falls back to band_width / its default.
  if (!any_ci) r.shock_ci.clear();
  return r;
}

}  // namespace meshgen
