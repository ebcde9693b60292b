#include "pipeline/one_scheme.hpp"

#include <fmt/format.h>

#include <set>

#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/progress.hpp"

namespace pipeline {

bool needs_one_scheme(const std::vector<GridRun>& clustered, const std::vector<GridRun>& uniform,
                      const std::string& robust) {
  std::set<std::string> schemes;
  for (const auto* family : {&clustered, &uniform})
    for (const GridRun& r : *family)
      if (!r.scheme.empty()) schemes.insert(r.scheme);
  return schemes.size() > 1 && schemes.count(robust) != 0;
}

GridRun charge_first_run(const GridRun& first, GridRun again) {
  const std::string why = fmt::format(
      "solved again with {} from the start so that every grid of the comparison shares one scheme; "
      "its {} run ({:.3g} CPU s) is charged too",
      again.scheme, first.scheme, first.cfd_cpu_seconds);
  again.cfd_cpu_seconds += first.cfd_cpu_seconds;
  again.cfd_wall_seconds += first.cfd_wall_seconds;
  again.steps += first.steps;
  again.note = why + (again.note.empty() ? "" : "; " + again.note);
  return again;
}

bool share_one_scheme(GridRunner& grids, std::vector<GridRun>& clustered,
                      std::vector<GridRun>& uniform, const ShockInput& shock,
                      const PrimaryError& primary) {
  const std::string robust = grids.robust_scheme();
  if (!needs_one_scheme(clustered, uniform, robust)) return false;
  scene::log_line("pipeline: some grids ended on " + robust +
                      " after diverging; the others are solved again with it",
                  true);
  for (auto* family : {&clustered, &uniform})
    for (GridRun& r : *family) {
      if (r.scheme.empty() || r.scheme == robust) continue;
      try {
        r = charge_first_run(r, grids.run(r.family, r.level, shock, primary, true));
      } catch (const scene::RunError& e) {
        if (scene::interrupted()) throw;
        r.note += (r.note.empty() ? "" : "; ") + std::string("its robust run failed (") + e.what() +
                  "): the comparison mixes schemes";
        scene::log_line("pipeline: " + level_name(r.family, r.level) + ": " + r.note, true);
      }
    }
  return true;
}

}  // namespace pipeline
