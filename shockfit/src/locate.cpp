#include "shockfit/locate.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <tuple>

#include "scene/body.hpp"
#include "scene/errors.hpp"
#include "scene/units.hpp"
#include "shockfit/profile.hpp"
#include "shockfit/shock_line.hpp"
#include "shockfit/two_line_fit.hpp"

namespace shockfit {

using scene::ShockKind;

namespace {

constexpr double kCi95 = 1.959963984540054;  // two-sided 95% normal quantile
constexpr int kMinAccepted = 3;              // fewest shock points for a shock line
// A shock on the stagnation line closer to the nose than this is attached
// (the nose station of a wedge finds the shock at its apex, up to the cell).
constexpr double kAttachedCells = 3.0;
constexpr double kAttachedFraction = 0.02;  // of the body length
// Outliers from the attached shock line: beyond this many robust sigmas, but
// never closer than one lattice spacing.
constexpr double kOutlierSigmas = 3.5;
constexpr double kOutlierFloorCells = 1.0;
// The near-axis parabola of a detached shock uses points within this many
// body lengths of the axis (Billig's hyperbola is a parabola there).
constexpr double kParabolaReach = 0.5;
// Blunt bodies' granular bow shocks are broad and stand far off: reach twice
// as far for enough points (the parabola is then a coarser approximation).
constexpr double kBluntParabolaReach = 1.0;
// Fewest points for the parabola to stand in for the stagnation station.
constexpr int kMinParabolaPoints = 5;
// The parabola's vertex and the stagnation station's shock agree within
// this many of the station's 95% half-widths, or this many lattice spacings.
constexpr double kVertexAgreeCi = 3.0;
constexpr double kVertexAgreeCells = 3.0;
// An attached shock leaves the apex downstream, so no point of it stands
// upstream of a sharp nose (over 150 granular runs of attached wedges the
// most upstream accepted point lay 0.034 body lengths downstream of the
// apex). This many accepted stations upstream of the nose, beyond the
// attached limit, are a shock standing off even when the stagnation line's
// jump is too smooth to pass its tests on its own (a granular bow shock just
// beyond the maximum deflection is as thick as its standoff); two, so that
// one noisy profile cannot decide.
constexpr int kMinStationsAhead = 2;
// Two stations closer than this (in lattice spacings) are the same point.
constexpr double kSamePointCells = 1e-6;
// A nose whose surface leaves the axis steeper than this (half-angle, deg)
// is blunt: no shock can attach to it (the largest deflection an attached
// shock turns, for any Mach number and gamma >= 1, is below 46 deg).
constexpr double kBluntNoseDeg = 46.0;
// Shock windows tried per station, in units of shockfit.window.
constexpr double kWindowWidening[] = {1.0, 2.0, 4.0};

const char* const kDensityFields[] = {"volume_fraction", "rho", "number_density"};
constexpr const char* kVelocityField = "v";

std::string density_field(const scene::Lattice& lat) {
  for (const char* f : kDensityFields)
    if (lat.has(f)) return f;
  return "";
}

void check_overlap(const scene::Scene& s, const scene::Domain& d, const scene::Lattice& lat) {
  if (lat.nx < 1 || lat.ny < 1) throw scene::InputError("lattice has no cells");
  const double x1 = lat.x0 + lat.nx * lat.dx, y1 = lat.y0 + lat.ny * lat.dy;
  if (!(x1 > d.xmin && lat.x0 < d.xmax && y1 > d.ymin && lat.y0 < d.ymax))
    throw scene::InputError("lattice spans x [" + std::to_string(lat.x0) + ", " + std::to_string(x1) + "], y [" +
                            std::to_string(lat.y0) + ", " + std::to_string(y1) + "], which misses the domain of scene '" +
                            s.name + "'");
}

StationFit fit_station(const scene::Lattice& lat, const std::string& field, const scene::Domain& d,
                       const scene::ShockfitParams& p, int index, scene::Vec2 origin, scene::Vec2 normal) {
  StationFit sf;
  sf.station = index;
  sf.surface = origin;
  sf.normal = normal;
  sf.shock = {kNaN, kNaN};
  sf.distance = sf.ci = sf.fit_error = kNaN;
  const Profile prof = sample_profile(lat, field, d, origin, normal, p.min_samples);
  // Shocks are a few cells wide in CFD fields but can span ten cells of a
  // granular lattice; a window much narrower than the shock makes the sharp
  // step model lose to a smooth curve. Widen the window until the station
  // accepts a jump (the narrowest that does wins, for resolution).
  TwoLineFit fit;
  for (const double widen : kWindowWidening) {
    TwoLineOptions opt = two_line_options(prof, p);
    opt.window *= widen;
    opt.min_segment = std::max(opt.min_segment, static_cast<int>(std::ceil(opt.window / std::max(prof.step, 1e-300))));
    TwoLineFit f = fit_two_lines(prof.t, prof.f, opt);
    if (widen == kWindowWidening[0] || f.accepted) fit = f;
    if (fit.accepted) break;
  }
  if (!fit.valid) return sf;
  sf.distance = fit.position;
  sf.shock = origin + fit.position * normal;
  sf.ci = kCi95 * fit.sigma_position;
  sf.fit_error = fit.rms;
  sf.accepted = fit.accepted;
  return sf;
}

// The shock of one station, jointly from the density and the velocity
// normal to the free stream. A granular shock is several mean free paths
// thick and its fields do not jump together: on the Mach 4.5 / 12 deg wedge
// the mid-point of the v jump stands about one lattice spacing upstream of
// that of the density (the flow turns before the disks pile up), and
// neither is privileged as the thin gas shock. One definition, the same in
// every run, is the mean of the two mid-points, where both fields see a
// jump (a station where only one does would switch definitions).
StationFit joint_station(const StationFit& fd, const StationFit& fv) {
  StationFit j = fd;
  if (!(fd.accepted && fv.accepted)) {
    j.accepted = false;
    return j;
  }
  j.distance = 0.5 * (fd.distance + fv.distance);
  j.shock = fd.surface + j.distance * fd.normal;
  // The two fields' noises come from the same disks; treated as independent
  // here: the per-point noise is a small part of the shock line's bootstrap
  // interval, which the scatter between stations dominates.
  j.ci = 0.5 * std::hypot(fd.ci, fv.ci);
  return j;
}

void require_body(const scene::Scene& s) {
  if (!s.body)
    throw scene::InputError((s.source_file.empty() ? s.name : s.source_file) +
                            ": scene has no body: nothing to locate a shock on");
}

// Half-angle at which the surface leaves the nose (upper side, clockwise
// from the nose on the CCW outline), in degrees.
bool blunt_nose(const scene::BodyGeometry& g) {
  const auto& P = g.polyline;
  const std::size_t n = P.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!(P[i] == g.nose)) continue;
    const scene::Vec2 up = P[(i + n - 1) % n] - g.nose, lo = P[(i + 1) % n] - g.nose;
    const double a_up = std::atan2(std::abs(up.y), up.x), a_lo = std::atan2(std::abs(lo.y), lo.x);
    return std::max(a_up, a_lo) / scene::kDeg > kBluntNoseDeg;
  }
  return false;
}

// Uncertainty that decides between fields: the interval of the reported number.
double uncertainty(const ShockResult& r) {
  const double u = r.shock == ShockKind::attached   ? r.shock_angle_ci_deg
                   : r.shock == ShockKind::detached ? r.standoff_ci
                                                    : kNaN;
  return std::isfinite(u) ? u : std::numeric_limits<double>::infinity();
}

}  // namespace

int ShockResult::accepted_count() const {
  return static_cast<int>(std::count_if(stations.begin(), stations.end(), [](const StationFit& f) { return f.accepted; }));
}

nlohmann::json ShockResult::summary() const {
  auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  nlohmann::json j;
  j["shock"] = scene::to_string(shock);
  j["field"] = field;
  j["shock_angle_deg"] = num(shock_angle_deg);
  j["shock_angle_ci_deg"] = num(shock_angle_ci_deg);
  j["shock_angle_pooled_deg"] = num(shock_angle_pooled_deg);
  j["shock_angle_ci95_deg"] = std::isfinite(shock_angle_lo_deg)
                                  ? nlohmann::json::array({shock_angle_lo_deg, shock_angle_hi_deg})
                                  : nlohmann::json(nullptr);
  j["standoff"] = num(standoff);
  j["standoff_ci"] = num(standoff_ci);
  j["standoff_stagnation"] = num(standoff_stagnation);
  j["standoff_pooled"] = num(standoff_pooled);
  j["stations"] = static_cast<int>(stations.size());
  j["stations_accepted"] = accepted_count();
  j["shock_line"] = shock == ShockKind::attached
                        ? nlohmann::json{{"point", {line_point.x, line_point.y}},
                                         {"direction", {line_dir.x, line_dir.y}}}
                        : nlohmann::json(nullptr);
  j["shock_vertex_x"] = num(vertex_x);
  j["shock_curvature_radius"] = num(curvature_radius);
  j["field_candidates"] = candidates;
  j["interval_method"] = interval_method;
  j["interval_groups"] =
      interval_groups > 0 ? nlohmann::json(interval_groups) : nlohmann::json(nullptr);
  j["interval_group_values"] = interval_group_values;
  j["group_own_angles_deg"] = group_own_angles;
  return j;
}

namespace {

// Fits one station along `normal` from `origin`; index -1 is the stagnation line.
using StationFitter = std::function<StationFit(int index, scene::Vec2 origin, scene::Vec2 normal)>;

ShockResult locate_with_fitter(const scene::Scene& s, const scene::Lattice& lat,
                               const std::string& field, const StationFitter& fit_at);

constexpr char kJointFieldSeparator = '+';
std::string joint_field_label(const std::string& density, const std::string& velocity) {
  return density + kJointFieldSeparator + velocity;
}

}  // namespace

std::pair<std::string, std::string> split_field_label(const std::string& label) {
  const std::size_t at = label.find(kJointFieldSeparator);
  if (at == std::string::npos) return {label, ""};
  return {label.substr(0, at), label.substr(at + 1)};
}

ShockResult locate_shock_with(const scene::Scene& s, const scene::Lattice& lat, const std::string& field) {
  require_body(s);
  (void)lat.field(field);  // InputError naming the fields there are
  const scene::Domain d = scene::scene_domain(s);
  return locate_with_fitter(s, lat, field, [&](int k, scene::Vec2 origin, scene::Vec2 normal) {
    return fit_station(lat, field, d, s.shockfit, k, origin, normal);
  });
}

ShockResult locate_shock_joint(const scene::Scene& s, const scene::Lattice& lat,
                               const std::string& density, const std::string& velocity) {
  require_body(s);
  (void)lat.field(density);
  (void)lat.field(velocity);
  const scene::Domain d = scene::scene_domain(s);
  const std::string label = joint_field_label(density, velocity);
  return locate_with_fitter(s, lat, label, [&](int k, scene::Vec2 origin, scene::Vec2 normal) {
    const StationFit fd = fit_station(lat, density, d, s.shockfit, k, origin, normal);
    // On the stagnation line v is zero on both sides of the shock (symmetry):
    // only the density can place it there.
    if (k < 0) return fd;
    const StationFit fv = fit_station(lat, velocity, d, s.shockfit, k, origin, normal);
    return joint_station(fd, fv);
  });
}

namespace {

// The station from a sharp nose straight upstream along the axis.
bool is_nose_station(const StationFit& f, const scene::BodyGeometry& g, double cell) {
  return scene::norm(f.surface - g.nose) < kSamePointCells * cell && f.normal.x < 0 &&
         std::abs(f.normal.y) < kSamePointCells;
}

// Near the axis a bow shock is a parabola x = x0 + c y^2 (Billig's
// hyperbola to second order), fitted through every accepted point there.
struct AxisParabola {
  std::vector<scene::Vec2> points, normals;  // points with y from the nose's height
  std::vector<double> sigma;
  double x0 = kNaN, c = kNaN;
  bool fitted = false;  // enough points for a parabola
  bool valid = false;   // a vertex inside the lattice, not downstream of the nose
};

AxisParabola fit_near_axis(const ShockResult& r, const scene::BodyGeometry& g,
                           const scene::Lattice& lat, bool blunt) {
  const double reach = (blunt ? kBluntParabolaReach : kParabolaReach) * g.length;
  AxisParabola a;
  for (const StationFit& f : r.stations)
    if (f.accepted && std::abs(f.shock.y - g.nose.y) <= reach) {
      a.points.push_back(f.shock - scene::Vec2{0.0, g.nose.y});
      a.normals.push_back(f.normal);
      a.sigma.push_back(f.ci / kCi95);
    }
  if (a.points.size() >= static_cast<std::size_t>(kMinParabolaPoints))
    std::tie(a.x0, a.c) = fit_axis_parabola(a.points);
  a.fitted = std::isfinite(a.x0);
  // A vertex outside the lattice (a nearly flat, scattered set of points)
  // is no vertex: fall back to the stagnation station.
  a.valid = std::isfinite(a.x0) && a.x0 >= lat.x0 && a.x0 <= g.nose.x;
  return a;
}

// Enough accepted stations upstream of a sharp nose, with the stagnation
// line's best jump (accepted or not) standing off too: see kMinStationsAhead.
// Not one noisy profile, so neither the stagnation line's own tests nor its
// agreement with the near-axis parabola (both fail where the shock is as
// thick as its standoff) need to pass.
bool stations_stand_ahead(const ShockResult& r, const scene::BodyGeometry& g, double attached_limit,
                          double cell) {
  if (!(r.stagnation.distance > attached_limit)) return false;  // NaN: no jump at all
  const auto ahead = std::count_if(r.stations.begin(), r.stations.end(), [&](const StationFit& f) {
    return f.accepted && !is_nose_station(f, g, cell) && g.nose.x - f.shock.x > attached_limit;
  });
  return ahead >= kMinStationsAhead;
}

// A detached shock needs a jump on the stagnation line away from the nose
// and, where the stations near the axis allow the check, a vertex there
// too: one noisy profile alone must not turn an attached shock into a bow
// shock. On a blunt nose a shock can only stand off: then the parabola
// alone (or the stagnation station alone) decides.
bool is_detached(const ShockResult& r, const AxisParabola& a, const scene::BodyGeometry& g,
                 bool blunt, double attached_limit, double cell) {
  const double vertex_tol = std::max(kVertexAgreeCi * r.stagnation.ci, kVertexAgreeCells * cell);
  const bool stagnation_off = r.stagnation.accepted && r.stagnation.distance > attached_limit;
  const bool parabola_off = a.valid && std::isfinite(a.x0) && g.nose.x - a.x0 > attached_limit;
  if (blunt) return parabola_off || stagnation_off;
  if (stations_stand_ahead(r, g, attached_limit, cell)) return true;
  if (!stagnation_off) return false;
  if (a.valid) return std::abs(a.x0 - r.stagnation.shock.x) <= vertex_tol;
  if (!a.fitted) return true;  // too few points to check: the stagnation line decides
  // A parabola with no vertex ahead of a sharp nose (the two sides of an
  // attached shock meeting at the apex fit one with its vertex behind it):
  // a bow shock needs points of its own upstream of the nose; without them
  // the stagnation line's jump is a fluctuation (disks thrown back off the
  // apex), not a shock.
  return std::any_of(a.points.begin(), a.points.end(),
                     [&](scene::Vec2 q) { return g.nose.x - q.x > attached_limit; });
}

void set_detached(ShockResult& r, const AxisParabola& a, const scene::BodyGeometry& g,
                  const scene::ShockfitParams& p) {
  const double L = g.length;
  r.shock = ShockKind::detached;
  r.standoff_stagnation = r.stagnation.distance / L;
  r.standoff = r.standoff_stagnation;
  r.standoff_ci = r.stagnation.ci / L;
  // The parabola's vertex is the shock on the stagnation line with the
  // noise of many stations instead of one: the standoff, with a bootstrap
  // interval.
  if (!a.valid) return;
  r.vertex_x = a.x0;
  r.curvature_radius = a.c > 0 ? 1.0 / (2.0 * a.c) / L : kNaN;
  const Interval iv =
      bootstrap(a.points, a.normals, a.sigma, p.bootstrap, p.seed,
                [](const std::vector<scene::Vec2>& q) { return fit_axis_parabola(q).first; });
  if (std::isfinite(a.x0) && std::isfinite(iv.lo) && a.x0 < g.nose.x) {
    r.standoff = (g.nose.x - a.x0) / L;
    r.standoff_ci = 0.5 * (iv.hi - iv.lo) / L;
  }
}

void set_no_shock(ShockResult& r) {
  r.shock = ShockKind::none;
  for (StationFit& f : r.stations) f.accepted = false;
}

// The stations an attached shock line is fitted through: accepted, not the
// nose station (kept as the apex of the curve only when the shock meets it
// there, never fitted: it looks upstream along the axis), and on the upper
// side of an asymmetric body (one shock line). Unaccepts the others.
std::vector<std::size_t> line_stations(ShockResult& r, const scene::BodyGeometry& g,
                                       double attached_limit, double cell) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < r.stations.size(); ++i) {
    StationFit& f = r.stations[i];
    if (!f.accepted) continue;
    if (is_nose_station(f, g, cell)) {
      f.accepted = f.distance <= attached_limit;
      continue;
    }
    if (!g.symmetric && f.surface.y < g.nose.y) {
      f.accepted = false;
      continue;
    }
    idx.push_back(i);
  }
  return idx;
}

// Attached (or none): the shock line through the accepted points, outliers
// dropped, with a bootstrap interval of its angle.
void fit_attached(ShockResult& r, const scene::BodyGeometry& g, double attached_limit, double cell,
                  const scene::ShockfitParams& p) {
  const std::vector<std::size_t> idx = line_stations(r, g, attached_limit, cell);
  std::vector<scene::Vec2> pts;
  for (const std::size_t i : idx) pts.push_back(r.stations[i].shock);
  const std::vector<std::size_t> keep = inliers(pts, kOutlierSigmas, kOutlierFloorCells * cell);
  std::vector<bool> kept(idx.size(), false);
  for (const std::size_t k : keep) kept[k] = true;
  std::vector<scene::Vec2> good, normals;
  std::vector<double> sig;
  for (std::size_t k = 0; k < idx.size(); ++k) {
    StationFit& f = r.stations[idx[k]];
    if (!kept[k]) {
      f.accepted = false;
      continue;
    }
    good.push_back(f.shock);
    normals.push_back(f.normal);
    sig.push_back(f.ci / kCi95);
  }
  if (good.size() < static_cast<std::size_t>(kMinAccepted)) {
    set_no_shock(r);
    return;
  }
  r.shock = ShockKind::attached;
  const LineFit lf = fit_orthogonal_line(good);
  r.shock_angle_deg = lf.angle_deg;
  r.line_point = lf.point;
  r.line_dir = lf.dir;
  const Interval iv =
      bootstrap(good, normals, sig, p.bootstrap, p.seed,
                [](const std::vector<scene::Vec2>& q) { return fit_orthogonal_line(q).angle_deg; });
  r.shock_angle_lo_deg = iv.lo;
  r.shock_angle_hi_deg = iv.hi;
  r.shock_angle_ci_deg = 0.5 * (iv.hi - iv.lo);
}

// The station whose profile is plotted: the middle accepted one.
int plot_station(const ShockResult& r, const scene::BodyGeometry& g, double cell) {
  if (r.stations.empty()) return -1;
  if (r.shock == ShockKind::detached) return 0;
  std::vector<int> acc;
  for (const StationFit& f : r.stations)
    if (f.accepted && !is_nose_station(f, g, cell)) acc.push_back(f.station);
  if (!acc.empty()) return acc[acc.size() / 2];
  return static_cast<int>(r.stations.size() / 2);
}

ShockResult locate_with_fitter(const scene::Scene& s, const scene::Lattice& lat,
                               const std::string& field, const StationFitter& fit_at) {
  require_body(s);
  const scene::BodyGeometry g = scene::make_body(*s.body);
  const scene::Domain d = scene::scene_domain(s);
  check_overlap(s, d, lat);
  const scene::ShockfitParams& p = s.shockfit;
  const double cell = std::min(lat.dx, lat.dy);

  ShockResult r;
  r.field = field;
  const std::vector<scene::Station> st = scene::surface_stations(g, p.stations);
  for (int k = 0; k < static_cast<int>(st.size()); ++k)
    r.stations.push_back(fit_at(k, st[k].point, st[k].normal));
  // The stagnation line: from the nose upstream against the free stream.
  r.stagnation = fit_at(-1, g.nose, {-1.0, 0.0});
  r.stagnation_valid = std::isfinite(r.stagnation.distance);

  const double attached_limit = std::max(kAttachedCells * cell, kAttachedFraction * g.length);
  const bool blunt = blunt_nose(g);
  const AxisParabola axis = fit_near_axis(r, g, lat, blunt);
  if (is_detached(r, axis, g, blunt, attached_limit, cell))
    set_detached(r, axis, g, p);
  else if (blunt)
    set_no_shock(r);  // no shock can attach to a blunt nose: without a standoff, no shock
  else
    fit_attached(r, g, attached_limit, cell, p);

  r.plot_station = plot_station(r, g, cell);
  const double u = uncertainty(r);
  r.candidates[field] = {
      {"shock", scene::to_string(r.shock)},
      {"uncertainty", std::isfinite(u) ? nlohmann::json(u) : nlohmann::json(nullptr)}};
  return r;
}

}  // namespace

ShockResult locate_shock_as(const scene::Scene& s, const scene::Lattice& lat,
                            const std::string& field_label) {
  const auto [dens, vel] = split_field_label(field_label);
  return vel.empty() ? locate_shock_with(s, lat, dens) : locate_shock_joint(s, lat, dens, vel);
}

double relocate_value(const scene::Scene& s, const scene::Lattice& lat, const ShockResult& like) {
  require_body(s);
  if (like.shock != ShockKind::attached && like.shock != ShockKind::detached) return kNaN;
  const scene::BodyGeometry g = scene::make_body(*s.body);
  const scene::Domain d = scene::scene_domain(s);
  const auto [dens, vel] = split_field_label(like.field);
  auto refit = [&](const StationFit& f) {
    StationFit a = fit_station(lat, dens, d, s.shockfit, f.station, f.surface, f.normal);
    if (vel.empty() || f.station < 0) return a;
    const StationFit b = fit_station(lat, vel, d, s.shockfit, f.station, f.surface, f.normal);
    a.distance = 0.5 * (a.distance + b.distance);  // NaN unless both fields place a jump
    a.shock = a.surface + a.distance * a.normal;
    a.accepted = a.accepted && b.accepted;
    return a;
  };
  // The stations `like` kept, found again on this lattice: the same points
  // fitted the same way, so that the value moves with the data alone and not
  // with which stations pass the acceptance and outlier tests.
  std::vector<scene::Vec2> all;
  std::vector<double> shift;  // along the normal, from the full fit's point
  const double cell = std::min(lat.dx, lat.dy);
  const double reach = (blunt_nose(g) ? kBluntParabolaReach : kParabolaReach) * g.length;
  for (const StationFit& f : like.stations) {
    if (!f.accepted || is_nose_station(f, g, cell)) continue;
    if (like.shock == ShockKind::detached && std::abs(f.shock.y - g.nose.y) > reach) continue;
    const StationFit q = refit(f);
    // The full fit found a jump here; on one group's noisier profile the
    // fit's position is wanted even where the jump does not pass the noise
    // test (outliers are dropped below).
    if (!std::isfinite(q.distance)) continue;
    all.push_back(like.shock == ShockKind::detached ? q.shock - scene::Vec2{0.0, g.nose.y}
                                                    : q.shock);
    shift.push_back(q.distance - f.distance);
  }
  if (like.shock == ShockKind::attached) {
    // The full fit's outlier test about the line: a group's noisier profile
    // can put a station's jump far off it.
    std::vector<scene::Vec2> good;
    for (const std::size_t k : inliers(all, kOutlierSigmas, kOutlierFloorCells * cell))
      good.push_back(all[k]);
    return good.size() >= static_cast<std::size_t>(kMinAccepted)
               ? fit_orthogonal_line(good).angle_deg
               : kNaN;
  }
  // A bow shock's stations do not lie on a line: points whose shift from the
  // full fit's lies beyond kOutlierSigmas robust sigmas of the others' (and
  // at least a lattice spacing) are dropped before the parabola, whose
  // vertex one wild station near the axis would throw (the default disc's
  // standoff interval was 1.6x too wide without it, 0.95x with it).
  std::vector<scene::Vec2> pts;
  for (const std::size_t k : near_median(shift, kOutlierSigmas, kOutlierFloorCells * cell))
    pts.push_back(all[k]);
  // Detached: the near-axis parabola's vertex through the same stations;
  // without one, the stagnation line.
  if (std::isfinite(like.vertex_x) && pts.size() >= static_cast<std::size_t>(kMinParabolaPoints)) {
    const double x0 = fit_axis_parabola(pts).first;
    return std::isfinite(x0) ? (g.nose.x - x0) / g.length : kNaN;
  }
  const StationFit st = refit(like.stagnation);
  return st.distance / g.length;
}

ShockResult locate_shock(const scene::Scene& s, const scene::Lattice& lat) {
  const std::string want = s.shockfit.field;
  const std::string dens = density_field(lat);
  if (want == "density") {
    if (dens.empty()) throw scene::InputError("shockfit.field 'density': the lattice has none of volume_fraction, rho, number_density");
    return locate_shock_with(s, lat, dens);
  }
  if (want != "auto") return locate_shock_with(s, lat, want);

  // With both a density and v, the shock is their joint mid-point (one
  // definition, not whichever field happens to be less noisy in this run).
  // Where the joint shock finds nothing (too few stations where both fields
  // jump) but one field alone does, that field's shock is reported rather
  // than none.
  std::vector<ShockResult> cand;
  if (!dens.empty()) cand.push_back(locate_shock_with(s, lat, dens));
  if (lat.has(kVelocityField)) cand.push_back(locate_shock_with(s, lat, kVelocityField));
  if (cand.size() == 2) {
    ShockResult joint = locate_shock_joint(s, lat, dens, kVelocityField);
    for (const ShockResult& c : cand) joint.candidates.update(c.candidates);
    if (joint.shock != ShockKind::none ||
        (cand[0].shock == ShockKind::none && cand[1].shock == ShockKind::none))
      return joint;
  }
  if (cand.empty())
    throw scene::InputError("lattice has none of the fields shockfit can use (volume_fraction, rho, number_density, v)");
  // Prefer a field that finds a shock; where both do but disagree on its
  // kind, trust the density (v has no jump on the stagnation line, where it
  // is zero on both sides); otherwise take the smaller uncertainty.
  std::size_t best = 0;
  for (std::size_t i = 1; i < cand.size(); ++i) {
    const ShockResult& a = cand[best];
    const ShockResult& b = cand[i];
    if (a.shock == ShockKind::none && b.shock != ShockKind::none)
      best = i;
    else if (a.shock != ShockKind::none && b.shock == a.shock && uncertainty(b) < uncertainty(a))
      best = i;
  }
  ShockResult r = cand[best];
  for (const ShockResult& c : cand) r.candidates.update(c.candidates);
  return r;
}

}  // namespace shockfit
