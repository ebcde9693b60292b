#include "pipeline/predictor.hpp"

#include <cmath>

#include "json_fields.hpp"
#include "pipeline/predictors.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/shock_csv.hpp"
#include "scene/units.hpp"
#include "shockfit/group_interval.hpp"

namespace pipeline {

namespace {

// Billig's cylinder shock for Mach `mach` and nose radius `radius`, its
// vertex at `vertex`, upper branch (and the lower one when the domain is not
// symmetric) clipped to the domain, every point with the 95% half-width
// `half_width`.
ShockCurve billig_curve(const scene::Domain& d, double mach, double radius, scene::Vec2 vertex,
                        double half_width) {
  constexpr int kPoints = 40;  // per branch
  ShockCurve c;
  const double y_top = d.ymax - vertex.y, y_bottom = d.symmetric ? 0.0 : vertex.y - d.ymin;
  auto add = [&](double dy) {
    const double x = vertex.x + scene::billig_shock_x(mach, radius, std::abs(dy));
    if (x <= d.xmax && x >= d.xmin) {
      c.points.push_back({x, vertex.y + dy});
      c.half_width.push_back(half_width);
    }
  };
  for (int k = kPoints; k >= 1 && !d.symmetric; --k) add(-y_bottom * k / kPoints);
  for (int k = 0; k <= kPoints; ++k) add(y_top * k / kPoints);
  return c;
}
}  // namespace

nlohmann::json Prediction::summary() const {
  nlohmann::json j;
  j["predictor"] = predictor;
  j["shock"] = scene::to_string(kind);
  j["shock_angle_deg"] = json_number(shock_angle_deg);
  j["shock_angle_ci_deg"] = json_number(shock_angle_ci_deg);
  j["standoff"] = json_number(standoff);
  j["standoff_ci"] = json_number(standoff_ci);
  j["cpu_seconds"] = cpu_seconds;
  j["wall_seconds"] = wall_seconds;
  j["shock_points"] = static_cast<long>(curve.size());
  j["shock_csv"] = shock_csv;
  j["size_fields"] = nlohmann::json::array();
  for (const auto& [level, path] : size_fields)
    j["size_fields"].push_back({{"level", level}, {"path", path}});
  j["details"] = details;
  return j;
}

void write_shock_curve(const std::string& path, const std::vector<scene::Vec2>& curve,
                       const std::vector<double>& half_width) {
  using scene::kNaN;
  std::vector<scene::ShockCsvRow> rows;
  for (std::size_t i = 0; i < curve.size(); ++i) {
    scene::ShockCsvRow r;
    r.station = static_cast<int>(i);
    r.surface = r.normal = {kNaN, kNaN};
    r.shock = curve[i];
    r.distance = r.fit_error = kNaN;
    r.ci = i < half_width.size() ? half_width[i] : 0.0;
    r.accepted = true;
    rows.push_back(r);
  }
  scene::write_shock_csv(path, rows);
}

ShockCurve apex_ray(const scene::Domain& d, scene::Vec2 apex, double angle_deg,
                    double angle_ci_deg) {
  constexpr int kPoints = 40;
  const double a = angle_deg * scene::kDeg;
  const scene::Vec2 dir{std::cos(a), std::sin(a)};
  // Distance to the first domain edge the ray meets.
  double len = 1e300;
  if (dir.x > 0) len = std::min(len, (d.xmax - apex.x) / dir.x);
  if (dir.x < 0) len = std::min(len, (d.xmin - apex.x) / dir.x);
  if (dir.y > 0) len = std::min(len, (d.ymax - apex.y) / dir.y);
  if (dir.y < 0) len = std::min(len, (d.ymin - apex.y) / dir.y);
  ShockCurve c;
  if (!(len > 0.0 && len < 1e300)) return c;
  const double spread = std::isfinite(angle_ci_deg) ? std::tan(angle_ci_deg * scene::kDeg) : 0.0;
  for (int k = 0; k <= kPoints; ++k) {
    const double s = len * k / kPoints;
    c.points.push_back(apex + s * dir);
    c.half_width.push_back(s * spread);
  }
  return c;
}

double billig_standoff(const scene::Scene& s) {
  return scene::billig_standoff_cylinder(s.freestream.mach) *
         scene::correlation_nose_radius(*s.body);
}

ShockCurve billig_bow_shock(const scene::Scene& s, double relative_half_width) {
  const double standoff = billig_standoff(s);
  const scene::Vec2 nose = scene::make_body(*s.body).nose;
  return billig_curve(scene::scene_domain(s), s.freestream.mach,
                      scene::correlation_nose_radius(*s.body), {nose.x - standoff, nose.y},
                      relative_half_width * standoff);
}

double band_angle_half_width_deg(double angle_ci_deg, double calibration_scatter_deg) {
  if (!std::isfinite(calibration_scatter_deg)) return angle_ci_deg;
  const double own = std::isfinite(angle_ci_deg) ? angle_ci_deg : 0.0;
  return std::hypot(own, shockfit::kNormal95 * calibration_scatter_deg);
}

double band_bow_half_width(double ci, double distance, double relative_rms) {
  const double own = std::isfinite(ci) ? ci : 0.0;
  if (!std::isfinite(relative_rms) || !std::isfinite(distance)) return own;
  return std::hypot(own, shockfit::kNormal95 * relative_rms * distance);
}

std::vector<ShockPoint> read_accepted_shock(const std::string& path) {
  std::vector<ShockPoint> out;
  for (const auto& r : scene::read_shock_csv(path).rows)
    if (r.accepted) out.push_back({r.shock, std::isfinite(r.ci) ? r.ci : 0.0, r.distance});
  return out;
}

std::vector<std::string> predictor_names() {
  return {"granular", "correlation", "coarse_cfd", "adapt"};
}

std::unique_ptr<Predictor> make_predictor(const std::string& name) {
  if (name == "granular") return std::make_unique<GranularPredictor>();
  if (name == "correlation") return std::make_unique<CorrelationPredictor>();
  if (name == "coarse_cfd") return std::make_unique<CoarseCfdPredictor>();
  if (name == "adapt") return std::make_unique<AdaptPredictor>();
  std::string known;
  for (const auto& n : predictor_names()) known += (known.empty() ? "" : ", ") + n;
  throw scene::InputError("--predictor: unknown predictor '" + name + "' (known: " + known + ")");
}

}  // namespace pipeline
