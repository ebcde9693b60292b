#include "pipeline/one_scheme.hpp"

#include <fmt/format.h>

#include <set>

#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/progress.hpp"

namespace pipeline {

namespace {
std::set<std::string> schemes_of(const std::vector<GridRun>& family) {
  std::set<std::string> schemes;
  for (const GridRun& r : family)
    if (!r.scheme.empty()) schemes.insert(r.scheme);
  return schemes;
}
}  // namespace

bool needs_one_scheme(const std::vector<GridRun>& family, const std::string& robust) {
  const std::set<std::string> schemes = schemes_of(family);
  return schemes.size() > 1 && schemes.count(robust) != 0;
}

std::string family_scheme(const std::vector<GridRun>& family) {
  const std::set<std::string> schemes = schemes_of(family);
  if (schemes.size() <= 1) return schemes.empty() ? "" : *schemes.begin();
  std::string all;
  for (const auto& x : schemes) all += (all.empty() ? "" : ", ") + x;
  return "mixed (" + all + ")";
}

GridRun charge_first_run(const GridRun& first, GridRun again, const std::string& why) {
  const bool own_mesh = again.mesh_name != first.mesh_name;
  const double charged = first.cfd_cpu_seconds + (own_mesh ? first.mesh_cpu_seconds : 0.0);
  const std::string what = fmt::format("{}; its first run ({}{}, {:.3g} CPU s) is charged too", why,
                                       first.scheme, first.strips ? ", strips" : "", charged);
  if (own_mesh) {
    again.mesh_cpu_seconds += first.mesh_cpu_seconds;
    again.mesh_seconds += first.mesh_seconds;
  }
  again.cfd_cpu_seconds += first.cfd_cpu_seconds;
  again.cfd_wall_seconds += first.cfd_wall_seconds;
  again.steps += first.steps;
  again.note = what + (again.note.empty() ? "" : "; " + again.note) +
               (first.note.empty() ? "" : "; before that: " + first.note);
  return again;
}

void one_scheme(GridRunner& grids, std::vector<GridRun>& family, const ShockInput& shock,
                const PrimaryError& primary, GridVariant base) {
  const std::string robust = grids.robust_scheme();
  if (!needs_one_scheme(family, robust)) return;
  base.robust = true;
  scene::log_line("pipeline: some " + family.front().family + " grids ended on " + robust +
                      " after diverging; the family's other grids are solved again with it",
                  true);
  for (GridRun& r : family) {
    if (r.scheme.empty() || r.scheme == robust) continue;
    try {
      r = charge_first_run(
          r, grids.run(r.family, r.level, shock, primary, base),
          "solved again with " + robust +
              " from the start so that every grid of its family shares one scheme");
    } catch (const scene::RunError& e) {
      if (scene::interrupted()) throw;
      r.note += (r.note.empty() ? "" : "; ") + std::string("its robust run failed (") + e.what() +
                "): the family mixes schemes";
      scene::log_line("pipeline: " + level_name(r.family, r.level) + ": " + r.note, true);
    }
  }
}

}  // namespace pipeline
