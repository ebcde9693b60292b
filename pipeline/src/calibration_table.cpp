#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "pipeline/bow_station_bias.hpp"
#include "pipeline/calibration.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"
#include "scene/yaml_text.hpp"
#include "shockfit/group_interval.hpp"

namespace pipeline {

namespace {
using scene::kNaN;
// Distances in an old table: one Mach number counts as much as 5 deg of wedge angle.
constexpr double kAngleScaleDeg = 5.0;
constexpr double kExactMatch = 1e-9;
// Per-point values are measured to far less than this many digits; the
// coefficients carry all 17 so that a reread table evaluates identically.
constexpr int kEntryDigits = 6;
constexpr int kCoefficientDigits = 17;
// training_points must repeat the entries' (Mach, angle) to this tolerance.
constexpr double kTrainingPointMatch = 1e-9;
// For people reading a table: what local_correction adds to the chosen model.
constexpr const char* kLocalFormula =
    "e += sum k_i w_i r_i / (sum k_i w_i + exp(-2) mean w), r_i = e_i - model_i, "
    "k_i = exp(-((ln M_i - ln M)/h_log_mach)^2/2 - ((theta_i - theta)/h_angle_deg)^2/2)";

[[noreturn]] void bad(const std::string& path, const YAML::Node& n, const std::string& key,
                      const std::string& what) {
  const std::string line =
      n.IsDefined() && n.Mark().line >= 0 ? ":" + std::to_string(n.Mark().line + 1) : "";
  throw scene::InputError(path + line + ": key '" + key + "': " + what);
}

RestitutionFit read_fit(const std::string& path, const YAML::Node& n, const std::string& key) {
  if (!n.IsMap()) bad(path, n, key, "expected a map {model, coefficients, residual_sd, loo_rms}");
  RestitutionFit f;
  const auto m = model_from_key(n["model"] ? n["model"].as<std::string>() : "");
  if (!m) {
    std::string known;
    for (const auto k : kRestitutionModels) known += (known.empty() ? "" : ", ") + model_key(k);
    bad(path, n, key + ".model", "unknown model (one of " + known + ")");
  }
  f.model = *m;
  const auto c = n["coefficients"];
  if (!c || !c.IsSequence() || c.size() != parameter_count(f.model))
    bad(path, n, key + ".coefficients",
        "expected " + std::to_string(parameter_count(f.model)) + " numbers for " +
            model_key(f.model));
  for (const auto& x : c) {
    const double v = x.as<double>();
    if (!std::isfinite(v)) bad(path, x, key + ".coefficients", "not a finite number");
    f.coefficients.push_back(v);
  }
  f.residual_sd = n["residual_sd"] ? n["residual_sd"].as<double>() : kNaN;
  f.loo_rms = n["loo_rms"] ? n["loo_rms"].as<double>() : kNaN;
  return f;
}

double optional_number(const YAML::Node& n, const char* key, double fallback) {
  return n[key] ? n[key].as<double>() : fallback;
}

BowShapeFit read_shape_fit(const std::string& path, const YAML::Node& n, const std::string& key) {
  if (!n.IsMap() || !n["shape"] || !n["coefficients"] || !n["relative_rms"] || !n["points"])
    bad(path, n, key, "expected a map {shape, coefficients, relative_rms, points}");
  BowShapeFit f;
  f.shape = n["shape"].as<std::string>();
  const auto c = n["coefficients"];
  if (!c.IsSequence() || c.size() != kBowShapeCoefficients)
    bad(path, c, key + ".coefficients", "expected [c0, c1] of e = c0 + c1/M^2");
  for (const auto& x : c) {
    const double v = x.as<double>();
    if (!std::isfinite(v)) bad(path, x, key + ".coefficients", "not a finite number");
    f.coefficients.push_back(v);
  }
  f.relative_rms = n["relative_rms"].as<double>();
  if (!(std::isfinite(f.relative_rms) && f.relative_rms >= 0))
    bad(path, n["relative_rms"], key + ".relative_rms", "expected a finite number >= 0");
  const auto pts = n["points"];
  if (!pts.IsSequence() || pts.size() <= kBowShapeCoefficients)
    bad(path, pts, key + ".points",
        "expected at least " + std::to_string(kBowShapeCoefficients + 1) + " training bodies");
  for (const auto& q : pts) {
    if (!q.IsMap() || !q["body"] || !q["mach"] || !q["restitution"])
      bad(path, q, key + ".points", "expected maps {body, mach, restitution, ...}");
    BowShapePoint p;
    p.body = q["body"].as<std::string>();
    p.mach = q["mach"].as<double>();
    p.restitution = q["restitution"].as<double>();
    p.restitution_ci = optional_number(q, "restitution_ci", 0.0);
    p.loo_restitution = optional_number(q, "loo_restitution", kNaN);
    p.loo_mean = optional_number(q, "loo_mean", kNaN);
    p.loo_rms = optional_number(q, "loo_rms", kNaN);
    p.loo_standoff = optional_number(q, "loo_standoff", kNaN);
    if (!(std::isfinite(p.mach) && p.mach > 0))
      bad(path, q["mach"], key + ".points.mach", "expected a finite number > 0");
    f.points.push_back(p);
  }
  return f;
}

// A key written only with a finite value (a NaN would not read back as a number).
void write_finite(YAML::Emitter& e, const char* key, double v) {
  if (std::isfinite(v)) e << YAML::Key << key << YAML::Value << v;
}

BowStationBias read_station_bias(const std::string& path, const YAML::Node& n,
                                 const std::string& key) {
  if (!n.IsMap() || !n["shape"] || !n["model"] || !n["coefficients"] || !n["relative_rms"])
    bad(path, n, key, "expected a map {shape, model, coefficients, relative_rms, ...}");
  BowStationBias b;
  b.shape = n["shape"].as<std::string>();
  b.model = n["model"].as<std::string>();
  const std::size_t want = station_bias_coefficients(b.model);
  if (want == 0)
    bad(path, n["model"], key + ".model",
        "unknown model '" + b.model + "' (" + station_bias_models() + ")");
  const auto c = n["coefficients"];
  if (!c.IsSequence() || c.size() != want)
    bad(path, c, key + ".coefficients",
        "expected " + std::to_string(want) + " coefficients for " + b.model);
  for (const auto& x : c) {
    const double v = x.as<double>();
    if (!std::isfinite(v)) bad(path, x, key + ".coefficients", "not a finite number");
    b.coefficients.push_back(v);
  }
  b.relative_rms = n["relative_rms"].as<double>();
  if (!(std::isfinite(b.relative_rms) && b.relative_rms >= 0))
    bad(path, n["relative_rms"], key + ".relative_rms", "expected a finite number >= 0");
  b.uncorrected_rms = optional_number(n, "uncorrected_rms", kNaN);
  b.max_inclination_deg = optional_number(n, "max_inclination_deg", 90.0);
  if (!(b.max_inclination_deg > 0 && b.max_inclination_deg <= 180))
    bad(path, n["max_inclination_deg"], key + ".max_inclination_deg", "expected (0, 180]");
  b.cpu_seconds = optional_number(n, "cpu_seconds", kNaN);
  b.mach_low = optional_number(n, "mach_low", kNaN);
  b.mach_high = optional_number(n, "mach_high", kNaN);
  if (!(b.mach_low > 0 && b.mach_high >= b.mach_low))
    bad(path, n, key, "expected mach_low > 0 and mach_high >= mach_low");
  if (const auto m = n["standoff_model"]) {
    b.standoff_model = m.as<std::string>();
    const std::size_t terms = standoff_term_coefficients(b.standoff_model);
    if (terms == kUnknownStandoffModel)
      bad(path, m, key + ".standoff_model",
          "unknown model '" + b.standoff_model + "' (" + standoff_term_models() + ")");
    const auto a = n["standoff_coefficients"];
    if (terms > 0 && (!a || !a.IsSequence() || a.size() != terms))
      bad(path, a ? a : n, key + ".standoff_coefficients",
          "expected " + std::to_string(terms) + " coefficients for " + b.standoff_model);
    for (std::size_t i = 0; i < terms; ++i) {
      const double v = a[i].as<double>();
      if (!std::isfinite(v)) bad(path, a[i], key + ".standoff_coefficients", "not a finite number");
      b.standoff_coefficients.push_back(v);
    }
  }
  if (const auto r = n["standoff_left_out_rms"]) {
    if (!r.IsMap()) bad(path, r, key + ".standoff_left_out_rms", "expected a map {model: rms}");
    for (const auto& kv : r)
      b.standoff_left_out_rms.emplace_back(kv.first.as<std::string>(), kv.second.as<double>());
  }
  if (const auto bodies = n["bodies"]) {
    if (!bodies.IsSequence()) bad(path, bodies, key + ".bodies", "expected a list");
    for (const auto& q : bodies) {
      if (!q.IsMap() || !q["body"]) bad(path, q, key + ".bodies", "expected maps {body, ...}");
      BowStationBiasBody r;
      r.body = q["body"].as<std::string>();
      r.mach = optional_number(q, "mach", kNaN);
      r.stations = q["stations"] ? q["stations"].as<int>() : 0;
      r.runs = q["runs"] ? q["runs"].as<int>() : 1;
      r.mean = optional_number(q, "mean", kNaN);
      r.rms = optional_number(q, "rms", kNaN);
      r.standoff = optional_number(q, "standoff", kNaN);
      r.loo_mean = optional_number(q, "loo_mean", kNaN);
      r.loo_rms = optional_number(q, "loo_rms", kNaN);
      r.loo_standoff = optional_number(q, "loo_standoff", kNaN);
      b.bodies.push_back(r);
    }
  }
  return b;
}

void write_station_bias(YAML::Emitter& e, const BowStationBias& b) {
  const auto number = [&e](const char* key, double v) { write_finite(e, key, v); };
  e << YAML::BeginMap << YAML::Key << "shape" << YAML::Value << b.shape << YAML::Key << "model"
    << YAML::Value << b.model << YAML::Key << "formula" << YAML::Value << YAML::DoubleQuoted
    << station_bias_formula(b.model) << YAML::Key << "coefficients" << YAML::Value << YAML::Flow
    << b.coefficients;
  number("relative_rms", b.relative_rms);
  number("uncorrected_rms", b.uncorrected_rms);
  number("max_inclination_deg", b.max_inclination_deg);
  number("mach_low", b.mach_low);
  number("mach_high", b.mach_high);
  number("cpu_seconds", b.cpu_seconds);
  e << YAML::Key << "standoff_model" << YAML::Value << b.standoff_model << YAML::Key
    << "standoff_formula" << YAML::Value << YAML::DoubleQuoted
    << standoff_term_formula(b.standoff_model) << YAML::Key << "standoff_coefficients"
    << YAML::Value << YAML::Flow << b.standoff_coefficients;
  if (!b.standoff_left_out_rms.empty()) {
    e << YAML::Key << "standoff_left_out_rms" << YAML::Value << YAML::Flow << YAML::BeginMap;
    for (const auto& [name, rms] : b.standoff_left_out_rms)
      e << YAML::Key << name << YAML::Value << rms;
    e << YAML::EndMap;
  }
  e << YAML::Key << "bodies" << YAML::Value << YAML::BeginSeq;
  for (const auto& r : b.bodies) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "body" << YAML::Value << r.body;
    number("mach", r.mach);
    e << YAML::Key << "stations" << YAML::Value << r.stations << YAML::Key << "runs" << YAML::Value
      << r.runs;
    number("mean", r.mean);
    number("rms", r.rms);
    number("standoff", r.standoff);
    number("loo_mean", r.loo_mean);
    number("loo_rms", r.loo_rms);
    number("loo_standoff", r.loo_standoff);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::EndMap;
}

void write_fit(YAML::Emitter& e, const RestitutionFit& f) {
  e << YAML::Flow << YAML::BeginMap << YAML::Key << "model" << YAML::Value << model_key(f.model)
    << YAML::Key << "formula" << YAML::Value << YAML::DoubleQuoted << model_formula(f.model)
    << YAML::Key << "coefficients" << YAML::Value << YAML::Flow << f.coefficients << YAML::Key
    << "residual_sd" << YAML::Value << f.residual_sd << YAML::Key << "loo_rms" << YAML::Value
    << f.loo_rms << YAML::EndMap;
}

void write_shape_fit(YAML::Emitter& e, const BowShapeFit& f) {
  const auto number = [&e](const char* key, double v) { write_finite(e, key, v); };
  e << YAML::BeginMap << YAML::Key << "shape" << YAML::Value << f.shape << YAML::Key << "formula"
    << YAML::Value << YAML::DoubleQuoted << "e = c0 + c1/M^2" << YAML::Key << "coefficients"
    << YAML::Value << YAML::Flow << f.coefficients << YAML::Key << "relative_rms" << YAML::Value
    << f.relative_rms << YAML::Key << "points" << YAML::Value << YAML::BeginSeq;
  for (const auto& p : f.points) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "body" << YAML::Value << p.body;
    number("mach", p.mach);
    number("restitution", p.restitution);
    number("restitution_ci", p.restitution_ci);
    number("loo_restitution", p.loo_restitution);
    number("loo_mean", p.loo_mean);
    number("loo_rms", p.loo_rms);
    number("loo_standoff", p.loo_standoff);
    e << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::EndMap;
}
}  // namespace

const RestitutionFit* CalibrationTable::fit(RestitutionModel m) const {
  const auto it =
      std::find_if(fits.begin(), fits.end(), [m](const RestitutionFit& f) { return f.model == m; });
  return it == fits.end() ? nullptr : &*it;
}

namespace {
// A value as the table file holds it (kEntryDigits significant digits).
double as_written(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", kEntryDigits, x);
  return std::strtod(buf, nullptr);
}

// The chosen fit's correction from its residuals at the entries as the
// table file holds them.
LocalCorrection correction_at_entries(const CalibrationTable& t, double h_log_mach,
                                      double h_angle_deg, double loo_rms) {
  const RestitutionFit* fit = t.model ? t.fit(*t.model) : nullptr;
  if (!fit) throw std::logic_error("local correction: the table has no chosen fit");
  std::vector<RestitutionPoint> pts;
  for (const auto& c : t.entries)
    pts.push_back({c.mach, c.angle_deg, as_written(c.restitution), as_written(c.restitution_ci)});
  LocalCorrection lc = local_correction(pts, *fit, h_log_mach, h_angle_deg);
  lc.loo_rms = loo_rms;
  return lc;
}

// The bandwidths are stored; the residuals are the chosen fit's at the
// entries, so they are rebuilt here rather than written twice.
LocalCorrection read_local(const std::string& path, const YAML::Node& n,
                           const CalibrationTable& t) {
  const std::string key = "local_correction";
  if (!n.IsMap() || !n["h_log_mach"] || !n["h_angle_deg"])
    bad(path, n, key, "expected a map {h_log_mach, h_angle_deg, loo_rms}");
  if (!t.model || !uses_angle(*t.model))
    bad(path, n, key, "needs a chosen model in the deflection (model)");
  if (t.entries.empty()) bad(path, n, key, "needs the training entries its residuals come from");
  const double hm = n["h_log_mach"].as<double>(), ht = n["h_angle_deg"].as<double>();
  if (!(std::isfinite(hm) && hm > 0))
    bad(path, n["h_log_mach"], key + ".h_log_mach", "expected a number > 0");
  if (!(std::isfinite(ht) && ht > 0))
    bad(path, n["h_angle_deg"], key + ".h_angle_deg", "expected a number > 0");
  return correction_at_entries(t, hm, ht, optional_number(n, "loo_rms", kNaN));
}
}  // namespace

void attach_local_correction(CalibrationTable& t, double h_log_mach, double h_angle_deg,
                             double loo_rms) {
  t.local_correction = correction_at_entries(t, h_log_mach, h_angle_deg, loo_rms);
}

std::optional<LocalCorrection> keep_local_correction(CalibrationTable& t,
                                                     std::span<const RestitutionPoint> points,
                                                     const std::optional<CorrectionWidths>& held) {
  const RestitutionFit* fit = t.model ? t.fit(*t.model) : nullptr;
  auto kept = fit ? choose_local_correction(points, *fit, held) : std::nullopt;
  if (kept)
    attach_local_correction(t, kept->bandwidth_log_mach, kept->bandwidth_angle_deg, kept->loo_rms);
  return kept;
}

CalibrationTable read_calibration(const std::string& path) {
  CalibrationTable t;
  YAML::Node root;
  try {
    // A malformed table must be an input error, never a parser hang.
    if (std::filesystem::is_regular_file(path))
      scene::check_yaml_text(scene::read_file(path), path);
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw scene::InputError(path + ": calibration table not found");
  } catch (const YAML::Exception& e) {
    throw scene::InputError(path + ":" + std::to_string(e.mark.line + 1) +
                            ": malformed calibration table: " + e.msg);
  }
  try {
    if (root["gamma"]) t.gamma = root["gamma"].as<double>();
    t.cpu_seconds = optional_number(root, "cpu_seconds", kNaN);
    if (std::isfinite(t.cpu_seconds) && t.cpu_seconds < 0)
      bad(path, root["cpu_seconds"], "cpu_seconds", "negative");
    for (const auto& n : root["entries"]) {
      CalibrationEntry e;
      e.mach = n["mach"].as<double>();
      e.angle_deg = n["angle_deg"].as<double>();
      e.restitution = n["restitution"].as<double>();
      e.restitution_ci = optional_number(n, "restitution_ci", 0.0);
      e.gas_angle_deg = optional_number(n, "gas_angle_deg", kNaN);
      e.granular_angle_deg = optional_number(n, "granular_angle_deg", kNaN);
      e.granular_angle_ci_deg = optional_number(n, "granular_angle_ci_deg", kNaN);
      e.loo_restitution = optional_number(n, "loo_restitution", kNaN);
      if (!(e.restitution > 0 && e.restitution <= 1))
        bad(path, n, "entries.restitution", "outside (0, 1]");
      t.entries.push_back(e);
    }
    if (const auto fits = root["fits"]) {
      if (!fits.IsSequence()) bad(path, fits, "fits", "expected a list of fits");
      for (std::size_t i = 0; i < fits.size(); ++i)
        t.fits.push_back(read_fit(path, fits[i], "fits[" + std::to_string(i) + "]"));
    }
    if (const auto model = root["model"]) {
      t.model = model_from_key(model.as<std::string>());
      if (!t.model) bad(path, model, "model", "unknown model '" + model.as<std::string>() + "'");
      if (!t.fit(*t.model))
        bad(path, model, "fits", "no fit for the chosen model " + model_key(*t.model));
      // Blunt bodies have no wedge angle: they need the Mach-only model.
      if (uses_angle(*t.model) && !t.fit(RestitutionModel::inverse_mach2))
        bad(path, model, "fits", "no inverse_mach2 fit for bodies without a wedge angle");
    } else if (!t.fits.empty()) {
      bad(path, root["fits"], "model", "fits given but no chosen model");
    }
    if (const auto lc = root["local_correction"]) t.local_correction = read_local(path, lc, t);
    if (const auto b = root["bow_shock"]) {
      if (!b.IsMap() || !b["relative_rms"])
        bad(path, b, "bow_shock", "expected a map {relative_rms, bodies, stations}");
      BowShockScatter w;
      w.relative_rms = b["relative_rms"].as<double>();
      if (!(std::isfinite(w.relative_rms) && w.relative_rms >= 0))
        bad(path, b["relative_rms"], "bow_shock.relative_rms", "expected a finite number >= 0");
      if (const auto names = b["bodies"]) w.bodies = names.as<std::vector<std::string>>();
      if (const auto machs = b["machs"]) {
        if (!machs.IsSequence() || machs.size() != w.bodies.size())
          bad(path, machs, "bow_shock.machs", "expected one Mach number per body");
        w.machs = machs.as<std::vector<double>>();
        for (const double m : w.machs)
          if (!(std::isfinite(m) && m > 0))
            bad(path, machs, "bow_shock.machs", "expected finite Mach numbers > 0");
      }
      w.stations = b["stations"] ? b["stations"].as<int>() : 0;
      w.cpu_seconds = optional_number(b, "cpu_seconds", kNaN);
      if (const auto shapes = b["shapes"]) {
        if (!shapes.IsSequence())
          bad(path, shapes, "bow_shock.shapes", "expected a list of shape fits");
        for (std::size_t i = 0; i < shapes.size(); ++i)
          w.shapes.push_back(
              read_shape_fit(path, shapes[i], "bow_shock.shapes[" + std::to_string(i) + "]"));
      }
      if (const auto biases = b["station_bias"]) {
        if (!biases.IsSequence())
          bad(path, biases, "bow_shock.station_bias", "expected a list of station biases");
        for (std::size_t i = 0; i < biases.size(); ++i) {
          w.station_biases.push_back(read_station_bias(
              path, biases[i], "bow_shock.station_bias[" + std::to_string(i) + "]"));
          if (w.shape(w.station_biases.back().shape))
            bad(path, biases[i], "bow_shock.station_bias",
                "the " + w.station_biases.back().shape +
                    " shape has its own e fit: its bodies do not run at the law the bias was "
                    "measured under");
        }
      }
      if (const auto law = b["restitution_law"]) {
        w.restitution_law = read_fit(path, law, "bow_shock.restitution_law");
        if (uses_angle(w.restitution_law->model))
          bad(path, law, "bow_shock.restitution_law",
              "blunt bodies have no wedge angle: expected a Mach-only model");
      }
      t.bow_shock = w;
    }
    const auto read_scatter = [&](const char* key) -> std::optional<AngleScatter> {
      const auto a = root[key];
      if (!a) return std::nullopt;
      const std::string k = key;
      if (!a.IsMap() || !a["deg"])
        bad(path, a, k, "expected a map {deg, rms_deg, flow_throughs, runs, wedges}");
      AngleScatter w;
      w.deg = a["deg"].as<double>();
      if (!(std::isfinite(w.deg) && w.deg >= 0))
        bad(path, a["deg"], k + ".deg", "expected a finite number >= 0");
      w.rms_deg = optional_number(a, "rms_deg", kNaN);
      w.flow_throughs = optional_number(a, "flow_throughs", kNaN);
      w.runs = a["runs"] ? a["runs"].as<int>() : 0;
      w.wedges = a["wedges"] ? a["wedges"].as<int>() : 0;
      w.mach_low = optional_number(a, "mach_low", kNaN);
      w.mach_high = optional_number(a, "mach_high", kNaN);
      return w;
    };
    t.angle_scatter = read_scatter("angle_scatter");
    t.angle_scatter_beyond = read_scatter("angle_scatter_beyond_mach");
    if (t.angle_scatter_beyond) {
      const auto& b = *t.angle_scatter_beyond;
      const auto range = scatter_mach_range(t);
      const bool one_side = range && b.mach_low <= b.mach_high &&
                            (b.mach_low > range->high || b.mach_high < range->low);
      if (!one_side)
        bad(path, root["angle_scatter_beyond_mach"], "angle_scatter_beyond_mach",
            "expected mach_low <= mach_high, both on one side of the Mach range the inside "
            "angle_scatter was measured on (else the training Mach range)");
    }
    if (const auto tp = root["training_points"]) {
      if (!tp.IsSequence() || tp.size() != t.entries.size())
        bad(path, tp, "training_points", "expected one [mach, angle_deg] per entry");
      for (std::size_t i = 0; i < tp.size(); ++i) {
        if (!tp[i].IsSequence() || tp[i].size() != 2 ||
            std::abs(tp[i][0].as<double>() - t.entries[i].mach) > kTrainingPointMatch ||
            std::abs(tp[i][1].as<double>() - t.entries[i].angle_deg) > kTrainingPointMatch)
          bad(path, tp[i], "training_points", "does not match entry " + std::to_string(i));
      }
    }
  } catch (const YAML::Exception& e) {
    throw scene::InputError(path + ":" + std::to_string(e.mark.line + 1) +
                            ": calibration table: " + e.msg);
  }
  return t;
}

void write_calibration(const CalibrationTable& t, const std::string& path) {
  YAML::Emitter e;
  e.SetDoublePrecision(kEntryDigits);
  e << YAML::BeginMap << YAML::Key << "gamma" << YAML::Value << t.gamma;
  if (std::isfinite(t.cpu_seconds)) e << YAML::Key << "cpu_seconds" << YAML::Value << t.cpu_seconds;
  e.SetDoublePrecision(kCoefficientDigits);
  if (t.model) {
    e << YAML::Key << "model" << YAML::Value << model_key(*t.model);
    e << YAML::Key << "fits" << YAML::Value << YAML::BeginSeq;
    for (const auto& f : t.fits) write_fit(e, f);
    e << YAML::EndSeq;
    if (const auto& lc = t.local_correction)
      e << YAML::Key << "local_correction" << YAML::Value << YAML::Flow << YAML::BeginMap
        << YAML::Key << "formula" << YAML::Value << kLocalFormula << YAML::Key << "h_log_mach"
        << YAML::Value << lc->bandwidth_log_mach << YAML::Key << "h_angle_deg" << YAML::Value
        << lc->bandwidth_angle_deg << YAML::Key << "loo_rms" << YAML::Value << lc->loo_rms
        << YAML::EndMap;
  }
  e.SetDoublePrecision(kEntryDigits);
  if (t.model) {
    e << YAML::Key << "training_points" << YAML::Value << YAML::BeginSeq;
    for (const auto& c : t.entries)
      e << YAML::Flow << YAML::BeginSeq << c.mach << c.angle_deg << YAML::EndSeq;
    e << YAML::EndSeq;
  }
  if (t.bow_shock) {
    e.SetDoublePrecision(kCoefficientDigits);
    e << YAML::Key << "bow_shock" << YAML::Value << YAML::BeginMap << YAML::Key << "relative_rms"
      << YAML::Value << t.bow_shock->relative_rms << YAML::Key << "bodies" << YAML::Value
      << YAML::Flow << t.bow_shock->bodies;
    if (!t.bow_shock->machs.empty() &&
        std::all_of(t.bow_shock->machs.begin(), t.bow_shock->machs.end(),
                    [](double m) { return std::isfinite(m); }))
      e << YAML::Key << "machs" << YAML::Value << YAML::Flow << t.bow_shock->machs;
    e << YAML::Key << "stations" << YAML::Value << t.bow_shock->stations;
    if (std::isfinite(t.bow_shock->cpu_seconds))
      e << YAML::Key << "cpu_seconds" << YAML::Value << t.bow_shock->cpu_seconds;
    if (const auto& law = t.bow_shock->restitution_law) {
      e << YAML::Key << "restitution_law" << YAML::Value;
      write_fit(e, *law);
    }
    if (!t.bow_shock->shapes.empty()) {
      e << YAML::Key << "shapes" << YAML::Value << YAML::BeginSeq;
      for (const auto& f : t.bow_shock->shapes) write_shape_fit(e, f);
      e << YAML::EndSeq;
    }
    if (!t.bow_shock->station_biases.empty()) {
      e << YAML::Key << "station_bias" << YAML::Value << YAML::BeginSeq;
      for (const auto& b : t.bow_shock->station_biases) write_station_bias(e, b);
      e << YAML::EndSeq;
    }
    e << YAML::EndMap;
    e.SetDoublePrecision(kEntryDigits);
  }
  const auto write_scatter = [&](const char* key, const AngleScatter& a) {
    e.SetDoublePrecision(kCoefficientDigits);
    e << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginMap << YAML::Key << "deg"
      << YAML::Value << a.deg;
    if (std::isfinite(a.rms_deg)) e << YAML::Key << "rms_deg" << YAML::Value << a.rms_deg;
    if (std::isfinite(a.flow_throughs))
      e << YAML::Key << "flow_throughs" << YAML::Value << a.flow_throughs;
    e << YAML::Key << "runs" << YAML::Value << a.runs << YAML::Key << "wedges" << YAML::Value
      << a.wedges;
    if (std::isfinite(a.mach_low) && std::isfinite(a.mach_high))
      e << YAML::Key << "mach_low" << YAML::Value << a.mach_low << YAML::Key << "mach_high"
        << YAML::Value << a.mach_high;
    e << YAML::EndMap;
    e.SetDoublePrecision(kEntryDigits);
  };
  if (t.angle_scatter) write_scatter("angle_scatter", *t.angle_scatter);
  if (t.angle_scatter_beyond) write_scatter("angle_scatter_beyond_mach", *t.angle_scatter_beyond);
  e << YAML::Key << "entries" << YAML::Value << YAML::BeginSeq;
  for (const auto& c : t.entries) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "mach" << YAML::Value << c.mach << YAML::Key
      << "angle_deg" << YAML::Value << c.angle_deg << YAML::Key << "restitution" << YAML::Value
      << c.restitution << YAML::Key << "restitution_ci" << YAML::Value << c.restitution_ci
      << YAML::Key << "gas_angle_deg" << YAML::Value << c.gas_angle_deg << YAML::Key
      << "granular_angle_deg" << YAML::Value << c.granular_angle_deg << YAML::Key
      << "granular_angle_ci_deg" << YAML::Value << c.granular_angle_ci_deg;
    if (t.model) e << YAML::Key << "loo_restitution" << YAML::Value << c.loo_restitution;
    e << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::EndMap;
  const std::string header =
      t.model
          ? "# Written by `pipeline calibrate` (docs/calibration.md): restitution e(M[, theta])\n"
            "# fitted to training wedges at which the granular shock angle equals the ideal-gas\n"
            "# theta-beta-Mach angle. `pipeline run` evaluates `model` (blunt bodies: the\n"
            "# bow_shock.restitution_law, else a Mach-only fit); entries are the training\n"
            "# points (crossing e, 95% half-width), granular_angle_deg measured at\n"
            "# loo_restitution, the leave-one-out prediction.\n"
            "# bow_shock (if present): the granular bow shock's out-of-sample relative\n"
            "# error under its restitution_law, from `pipeline calibrate --bow-shock-runs`;\n"
            "# it widens bow-shock bands. bow_shock.shapes (if present): a blunt shape's own\n"
            "# e = c0 + c1/M^2 and its left-out relative error (`--fit-shapes`); bodies of\n"
            "# that shape use it. bow_shock.station_bias (if present): a shape's fold under\n"
            "# the law, r = relative distance error by body-normal inclination (and Mach),\n"
            "# fitted and left-out-checked by `--bow-shock-runs ... --station-bias`; bodies\n"
            "# of that shape have it taken out of their stations and standoff.\n"
            "# angle_scatter (if present): the table's own angle error on unseen wedges at\n"
            "# the default averaging, from `pipeline calibrate --angle-check-runs`; it widens\n"
            "# attached bands in place of the leave-one-out estimate.\n"
            "# angle_scatter_beyond_mach (if present): the same error on unseen wedges\n"
            "# beyond the Mach numbers angle_scatter was measured on (training wedges\n"
            "# added there, or e(M) extrapolated); attached wedges on that side take it.\n"
          : "# Written by `pipeline calibrate`: restitution e at which the granular\n"
            "# shock angle equals the ideal-gas theta-beta-Mach angle.\n";
  scene::write_file_atomic(path, header + e.c_str() + "\n");
}

namespace {
// An entry whose granular angle was measured at its leave-one-out e: a new
// table's out-of-sample run (an old table's reruns are in sample).
bool measured_out_of_sample(const CalibrationEntry& e) {
  return std::isfinite(e.loo_restitution) && std::isfinite(e.granular_angle_deg - e.gas_angle_deg);
}
}  // namespace

double out_of_sample_angle_rms_deg(const CalibrationTable& t) {
  double ss = 0;
  int n = 0;
  for (const auto& e : t.entries) {
    if (!measured_out_of_sample(e)) continue;
    const double err = e.granular_angle_deg - e.gas_angle_deg;
    ss += err * err;
    ++n;
  }
  return n >= 2 ? std::sqrt(ss / n) : kNaN;
}

std::optional<MachRange> scatter_mach_range(const CalibrationTable& t) {
  if (t.angle_scatter && std::isfinite(t.angle_scatter->mach_low) &&
      std::isfinite(t.angle_scatter->mach_high))
    return MachRange{t.angle_scatter->mach_low, t.angle_scatter->mach_high};
  return training_mach_range(t);
}

bool beyond_scatter_applies(const CalibrationTable& t, double mach) {
  if (!t.angle_scatter_beyond) return false;
  const auto range = scatter_mach_range(t);
  if (!range || range->contains(mach)) return false;
  const bool measured_above = t.angle_scatter_beyond->mach_low > range->high;
  return measured_above == (mach > range->high);
}

double table_angle_scatter_deg(const CalibrationTable& t, double mach) {
  const double inside = table_angle_scatter_deg(t);
  if (!beyond_scatter_applies(t, mach)) return inside;
  const double beyond = t.angle_scatter_beyond->deg;
  return std::isfinite(inside) ? std::max(inside, beyond) : beyond;
}

double table_angle_scatter_deg(const CalibrationTable& t) {
  if (t.angle_scatter) return t.angle_scatter->deg;
  const double rms = out_of_sample_angle_rms_deg(t);
  if (!std::isfinite(rms)) return kNaN;
  double noise = 0;
  int n = 0;
  for (const auto& e : t.entries) {
    if (!measured_out_of_sample(e)) continue;
    // A run without an interval counts as noiseless: the scatter then errs wide.
    const double sd = std::isfinite(e.granular_angle_ci_deg)
                          ? e.granular_angle_ci_deg / shockfit::kNormal95
                          : 0.0;
    noise += sd * sd;
    ++n;
  }
  return std::sqrt(std::max(0.0, rms * rms - noise / n));
}

std::optional<BowShockScatter> bow_shock_kept_by_wedge_fit(const CalibrationTable& old) {
  if (old.bow_shock && old.bow_shock->restitution_law) return old.bow_shock;
  return std::nullopt;
}

std::optional<BowShockScatter> bow_shock_kept_by_wedge_fit(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) return std::nullopt;
  return bow_shock_kept_by_wedge_fit(read_calibration(path));
}

const RestitutionFit* blunt_restitution_law(const CalibrationTable& t) {
  if (!t.model) return nullptr;
  if (t.bow_shock && t.bow_shock->restitution_law) return &*t.bow_shock->restitution_law;
  return t.fit(uses_angle(*t.model) ? RestitutionModel::inverse_mach2 : *t.model);
}

std::optional<double> interpolate_restitution(const CalibrationTable& t, double mach,
                                              double angle_deg) {
  if (t.model) {
    const RestitutionFit* f = std::isnan(angle_deg) ? blunt_restitution_law(t) : t.fit(*t.model);
    if (!f) return std::nullopt;  // read_calibration refuses such a table
    double e = f->evaluate(mach, angle_deg);
    if (!std::isnan(angle_deg) && t.local_correction)
      e += t.local_correction->evaluate(mach, angle_deg);
    return std::min(e, kMaxRestitution);
  }
  if (t.entries.empty()) return std::nullopt;
  double wsum = 0, esum = 0;
  for (const auto& c : t.entries) {
    const double d = std::isnan(angle_deg)
                         ? std::abs(c.mach - mach)
                         : std::hypot(c.mach - mach, (c.angle_deg - angle_deg) / kAngleScaleDeg);
    if (d < kExactMatch) return c.restitution;
    const double w = 1.0 / (d * d);
    wsum += w;
    esum += w * c.restitution;
  }
  return esum / wsum;
}

double BowShapeFit::evaluate(double mach) const {
  return std::min(coefficients.at(0) + coefficients.at(1) / (mach * mach), kMaxRestitution);
}

const BowShapeFit* BowShockScatter::shape(const std::string& name) const {
  for (const auto& f : shapes)
    if (f.shape == name) return &f;
  return nullptr;
}

const BowStationBias* BowShockScatter::station_bias(const std::string& name) const {
  for (const auto& b : station_biases)
    if (b.shape == name) return &b;
  return nullptr;
}

MachRange training_mach_range(const BowShapeFit& f) {
  MachRange r{f.points.front().mach, f.points.front().mach};
  for (const auto& p : f.points) {
    r.low = std::min(r.low, p.mach);
    r.high = std::max(r.high, p.mach);
  }
  return r;
}

std::optional<MachRange> training_mach_range(const BowShockScatter& w) {
  if (w.machs.empty()) return std::nullopt;
  const auto [lo, hi] = std::minmax_element(w.machs.begin(), w.machs.end());
  return MachRange{*lo, *hi};
}

namespace {

// The smallest and largest of one coordinate over the training entries.
std::optional<MachRange> entry_range(const CalibrationTable& t,
                                     double CalibrationEntry::*coordinate) {
  if (t.entries.empty()) return std::nullopt;
  MachRange r{t.entries.front().*coordinate, t.entries.front().*coordinate};
  for (const auto& c : t.entries) {
    r.low = std::min(r.low, c.*coordinate);
    r.high = std::max(r.high, c.*coordinate);
  }
  return r;
}

}  // namespace

std::optional<MachRange> training_angle_range(const CalibrationTable& t) {
  return entry_range(t, &CalibrationEntry::angle_deg);
}

std::optional<MachRange> training_mach_range(const CalibrationTable& t) {
  return entry_range(t, &CalibrationEntry::mach);
}

}  // namespace pipeline
