#pragma once
// The shock locator: two-line fits along body normals (docs/shockfit.md).
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "scene/lattice.hpp"
#include "scene/scene.hpp"
#include "scene/shock_kind.hpp"
#include "scene/units.hpp"
#include "scene/vec2.hpp"

namespace shockfit {

using scene::kNaN;

struct StationFit {
  int station = 0;
  scene::Vec2 surface, normal, shock;  // shock: NaN where no fit was possible
  double distance = 0.0;               // shock distance from the surface along the normal
  double ci = 0.0;                     // 95% half-width of `distance` (scene units)
  double fit_error = 0.0;              // rms residual of the two lines (field units)
  bool accepted = false;               // a jump was found (and, attached, it lies on the shock line)
};

struct ShockResult {
  scene::ShockKind shock = scene::ShockKind::none;
  std::string field;           // lattice field used
  double shock_angle_deg = kNaN, shock_angle_ci_deg = kNaN;  // NaN when n/a
  double standoff = kNaN, standoff_ci = kNaN;              // body lengths
  std::vector<StationFit> stations;

  // Details (NaN when n/a).
  double shock_angle_lo_deg = kNaN, shock_angle_hi_deg = kNaN;  // 95% interval
  scene::Vec2 line_point{kNaN, kNaN}, line_dir{kNaN, kNaN};  // fitted attached shock
  double standoff_stagnation = kNaN;  // detached: from the stagnation-line station alone (body lengths)
  // Detached with groups: the pooled fields' own standoff (body lengths);
  // `standoff` is then the groups' mean (group_interval.hpp).
  double standoff_pooled = kNaN;
  // Attached with groups: the pooled fields' own line angle (deg);
  // `shock_angle_deg` is then the groups' own fits' mean (group_interval.hpp).
  double shock_angle_pooled_deg = kNaN;
  double vertex_x = kNaN;          // detached: shock vertex x from the near-axis parabola
  double curvature_radius = kNaN;  // detached: shock radius of curvature at the vertex (body lengths)
  StationFit stagnation;                // the fit along the stagnation line (from the nose, along -x)
  bool stagnation_valid = false;
  int plot_station = -1;                // station whose profile is plotted
  // How the angle's / standoff's 95% interval was made: "bootstrap" over
  // stations, or "groups": the spread of interval_groups averaging groups
  // (group_interval.hpp).
  std::string interval_method = "bootstrap";
  int interval_groups = 0;
  // Each group's angle (deg) or standoff (body lengths), in the order of the
  // groups file: replica by replica. Empty with the bootstrap.
  std::vector<double> interval_group_values;
  // Attached with groups: each group's angle found from scratch on its
  // fields alone (its own stations and tests; NaN where it finds no attached
  // shock), whose spread bounds the interval from below (group_interval.hpp).
  std::vector<double> group_own_angles;
  nlohmann::json candidates = nlohmann::json::object();  // per field tried: shock, uncertainty

  int accepted_count() const;
  nlohmann::json summary() const;
};

// Throws scene::InputError for a scene without a body, a lattice that does
// not overlap the domain, or a missing field.
ShockResult locate_shock(const scene::Scene& s, const scene::Lattice& fields);
// One named field, no automatic choice.
ShockResult locate_shock_with(const scene::Scene& s, const scene::Lattice& fields, const std::string& field);
// The joint shock: per station, the mean of the jump mid-points of the
// density and the velocity field (docs/shockfit.md, "Shock definition");
// the stagnation line uses the density alone.
ShockResult locate_shock_joint(const scene::Scene& s, const scene::Lattice& fields,
                               const std::string& density, const std::string& velocity);

// A ShockResult's `field` label split into the density-like field and the
// velocity of a joint shock ("volume_fraction+v"); the velocity is empty for
// a one-field label.
std::pair<std::string, std::string> split_field_label(const std::string& label);

// The shock found from scratch with the field definition a ShockResult's
// `field` label names: one field ("density"), or the joint shock of two
// ("density+velocity").
ShockResult locate_shock_as(const scene::Scene& s, const scene::Lattice& fields,
                            const std::string& field_label);

// The angle (attached, deg) or standoff (detached, body lengths) of `like`'s
// shock found again on another lattice of the same scene (the fields of one
// averaging group): the stations `like` kept, refitted with its field
// definition, through its line or near-axis parabola. NaN where too few of
// them find a jump.
double relocate_value(const scene::Scene& s, const scene::Lattice& fields, const ShockResult& like);

// DIR/shock.csv, DIR/summary.json, DIR/shock.png and DIR/profile.png (the
// PNGs only when gnuplot runs; otherwise a warning on stderr).
void write_outputs(const scene::Scene& s, const scene::Lattice& fields, const ShockResult& r,
                   const std::string& out_dir);

}  // namespace shockfit
