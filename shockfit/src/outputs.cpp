#include "plot.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"
#include "scene/shock_csv.hpp"
#include "shockfit/locate.hpp"

namespace shockfit {

void write_outputs(const scene::Scene& s, const scene::Lattice& fields, const ShockResult& r,
                   const std::string& out_dir) {
  scene::make_dirs(out_dir);
  std::vector<scene::ShockCsvRow> rows;
  rows.reserve(r.stations.size());
  for (const StationFit& f : r.stations)
    rows.push_back({f.station, f.surface, f.normal, f.shock, f.distance, f.ci, f.fit_error, f.accepted});
  scene::write_shock_csv(out_dir + "/shock.csv", rows);
  nlohmann::json j = r.summary();
  j["scene"] = s.name;
  scene::write_json_atomic(out_dir + "/summary.json", j);
  std::string why;
  if (!write_plots(s, fields, r, out_dir, why)) scene::log_line("shockfit: warning: no PNG written: " + why, true);
}

}  // namespace shockfit
