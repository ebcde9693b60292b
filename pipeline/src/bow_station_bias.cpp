#include "pipeline/bow_station_bias.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <stdexcept>

#include "scene/units.hpp"

namespace pipeline {

namespace {
using scene::kNaN;

// Inclinations are scaled by the quarter turn, so b1 is the fold from the
// stagnation line to where the body runs parallel to the stream.
constexpr double kQuarterTurnDeg = 90.0;
// A richer model must lower the left-out RMS by more than this to be chosen.
constexpr double kLooTie = 1e-12;
// Where a model's distances are checked to stay positive: enough points
// across the inclinations to catch a quadratic's turning point.
constexpr int kPositivityChecks = 16;

// The candidate models, simplest first, each its terms at s (the scaled
// inclination) and 1/M^2. The quadratic lets the fold flatten near the
// stagnation line, where the training discs' stations do.
struct Model {
  const char* name;
  const char* formula;
  std::vector<double> (*terms)(double s, double inverse_mach2);
  bool mach_term;
};
constexpr std::array<Model, 3> kModels{{
    {"inclination", "r = b0 + b1*s, s = inclination/90deg",
     [](double s, double) {
       return std::vector<double>{1.0, s};
     },
     false},
    {"inclination_mach", "r = b0 + b1*s + b2/M^2, s = inclination/90deg",
     [](double s, double m2) {
       return std::vector<double>{1.0, s, m2};
     },
     true},
    {"inclination2_mach", "r = b0 + b1*s + b2*s^2 + b3/M^2, s = inclination/90deg",
     [](double s, double m2) {
       return std::vector<double>{1.0, s, s * s, m2};
     },
     true},
}};

// A row of a model table by name (nullptr when unknown), and the table's
// names, for errors.
template <class Table>
auto find_named(const Table& table, const std::string& name) -> decltype(&table[0]) {
  for (const auto& m : table)
    if (name == m.name) return &m;
  return nullptr;
}
template <class Table>
std::string joined_names(const Table& table) {
  std::string out;
  for (const auto& m : table) out += (out.empty() ? "" : ", ") + std::string(m.name);
  return out;
}

const Model* find_model(const std::string& name) {
  return find_named(kModels, name);
}

// The standoff's own term q(M) on top of the fold, simplest first, each its
// terms at 1/M^2: none, a constant, a constant and 1/M^2 (the gas's density
// ratio across a normal shock moves with 1/M^2).
struct StandoffModel {
  const char* name;
  const char* formula;
  std::vector<double> (*terms)(double inverse_mach2);
};
constexpr std::array<StandoffModel, 3> kStandoffModels{{
    {"none", "q = 0", [](double) { return std::vector<double>{}; }},
    {"constant", "q = a0", [](double) { return std::vector<double>{1.0}; }},
    {"inverse_mach2", "q = a0 + a1/M^2",
     [](double m2) {
       return std::vector<double>{1.0, m2};
     }},
}};

const StandoffModel* find_standoff_model(const std::string& name) {
  return find_named(kStandoffModels, name);
}

double dot(const std::vector<double>& row, const std::vector<double>& c) {
  double v = 0;
  for (std::size_t j = 0; j < row.size(); ++j) v += c.at(j) * row[j];
  return v;
}

std::vector<double> standoff_basis(const std::string& model, double mach) {
  const StandoffModel* m = find_standoff_model(model);
  if (!m) throw std::invalid_argument("station bias: unknown standoff model '" + model + "'");
  return m->terms(1.0 / (mach * mach));
}

double standoff_term(const std::string& model, const std::vector<double>& a, double mach) {
  return dot(standoff_basis(model, mach), a);
}

// The table reader refuses unknown names, so one here is a caller's bug.
std::vector<double> basis(const std::string& model, double mach, double inclination) {
  const Model* m = find_model(model);
  if (!m) throw std::invalid_argument("station bias: unknown model '" + model + "'");
  return m->terms(inclination / kQuarterTurnDeg, 1.0 / (mach * mach));
}

double evaluate(const std::string& model, const std::vector<double>& c, double mach,
                double inclination) {
  return dot(basis(model, mach, inclination), c);
}

// The coefficients c minimising |rows c - rhs|; nullopt where the rows do not
// determine all p of them.
std::optional<std::vector<double>> least_squares(const std::vector<std::vector<double>>& rows,
                                                 const std::vector<double>& rhs, std::size_t p) {
  if (rows.size() < p) return std::nullopt;
  Eigen::MatrixXd a(rows.size(), p);
  Eigen::VectorXd y(rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (std::size_t j = 0; j < p; ++j)
      a(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rows[i][j];
    y(static_cast<Eigen::Index>(i)) = rhs[i];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a);
  if (qr.rank() < static_cast<Eigen::Index>(p)) return std::nullopt;
  const Eigen::VectorXd c = qr.solve(y);
  return std::vector<double>(c.data(), c.data() + c.size());
}

// Each body's stations weigh 1 / n_i on their squared residuals, so a body
// with many accepted stations counts once, like every other (a body's
// stations move together: they share its run). `skip` is left out.
std::optional<std::vector<double>> solve(const std::string& model,
                                         const std::vector<StationErrors>& bodies,
                                         std::size_t skip) {
  const std::size_t p = station_bias_coefficients(model);
  std::vector<std::vector<double>> rows;
  std::vector<double> rhs;
  std::set<double> machs;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (i == skip) continue;
    const auto& b = bodies[i];
    const double w = 1.0 / std::sqrt(static_cast<double>(b.relative.size()));
    machs.insert(b.mach);
    for (std::size_t k = 0; k < b.relative.size(); ++k) {
      auto row = basis(model, b.mach, b.inclination_deg[k]);
      for (auto& x : row) x *= w;
      rows.push_back(row);
      rhs.push_back(w * b.relative[k]);
    }
  }
  // A Mach term needs two Mach numbers in what it is fitted on.
  if (find_model(model)->mach_term && machs.size() < 2) return std::nullopt;
  return least_squares(rows, rhs, p);
}

// One body's standoff corrected by the fold's coefficients c (its value at
// the stagnation line).
double corrected_standoff(const std::string& model, const std::vector<double>& c,
                          const StationErrors& b) {
  return (1.0 + b.standoff_relative) / (1.0 + evaluate(model, c, b.mach, 0.0)) - 1.0;
}

// One body's stations and standoff corrected by coefficients c.
struct Corrected {
  double mean = 0, rms = 0, standoff = kNaN;
};
Corrected corrected(const std::string& model, const std::vector<double>& c,
                    const StationErrors& b) {
  Corrected out;
  double ss = 0;
  for (std::size_t k = 0; k < b.relative.size(); ++k) {
    const double e =
        (1.0 + b.relative[k]) / (1.0 + evaluate(model, c, b.mach, b.inclination_deg[k])) - 1.0;
    out.mean += e;
    ss += e * e;
  }
  const double n = static_cast<double>(b.relative.size());
  out.mean /= n;
  out.rms = std::sqrt(ss / n);
  out.standoff = corrected_standoff(model, c, b);
  return out;
}

// The bodies' standoff errors left after a fold with coefficients c, and
// their Mach numbers; `skip` left out.
struct StandoffSample {
  std::vector<double> error, mach;
};
StandoffSample standoff_sample(const std::string& model, const std::vector<double>& c,
                               const std::vector<StationErrors>& bodies, std::size_t skip) {
  StandoffSample out;
  for (std::size_t j = 0; j < bodies.size(); ++j) {
    if (j == skip) continue;
    out.error.push_back(corrected_standoff(model, c, bodies[j]));
    out.mach.push_back(bodies[j].mach);
  }
  return out;
}

// Least squares of a standoff term on the sample (each body once); nullopt
// where the bodies cannot determine it.
std::optional<std::vector<double>> solve_standoff(const std::string& model,
                                                  const StandoffSample& sample) {
  const std::size_t p = standoff_basis(model, 1.0).size();
  if (p == 0) return std::vector<double>{};
  // As many Mach numbers as terms, or the Mach term is not determined.
  if (std::set<double>(sample.mach.begin(), sample.mach.end()).size() < p) return std::nullopt;
  std::vector<std::vector<double>> rows;
  for (const double m : sample.mach) rows.push_back(standoff_basis(model, m));
  return least_squares(rows, sample.error, p);
}

// Chooses the standoff term by the bodies' left-out standoff RMS (each body
// left out of the fold and of the term alike; the simpler on a tie), fits it
// on every body and rewrites each body's left-out standoff with it.
void choose_standoff_term(BowStationBias& b, const std::vector<StationErrors>& bodies) {
  const std::size_t n = bodies.size();
  // Per left-out body, what every candidate term is fitted on (the others'
  // errors under the fold made without it) and its own error under that fold.
  std::vector<StandoffSample> others;
  std::vector<double> own;
  for (std::size_t i = 0; i < n; ++i) {
    const std::vector<double> fold = *solve(b.model, bodies, i);
    others.push_back(standoff_sample(b.model, fold, bodies, i));
    own.push_back(corrected_standoff(b.model, fold, bodies[i]));
  }
  const StandoffSample all = standoff_sample(b.model, b.coefficients, bodies, n);
  double best_rms = kNaN;
  std::vector<double> best_loo;
  b.standoff_left_out_rms.clear();
  for (const auto& m : kStandoffModels) {
    std::vector<double> loo;
    for (std::size_t i = 0; i < n; ++i) {
      const auto a = solve_standoff(m.name, others[i]);
      if (!a) break;
      // At the left-out body's own Mach number, extrapolated where it is an
      // end, as the fold's left-out check is.
      const double q = standoff_term(m.name, *a, bodies[i].mach);
      loo.push_back((1.0 + own[i]) / (1.0 + q) - 1.0);
    }
    if (loo.size() < n) continue;
    const auto a = solve_standoff(m.name, all);
    if (!a) continue;
    // The corrected standoff must stay positive wherever the term is held.
    if (!(1.0 + standoff_term(m.name, *a, b.mach_low) > kMinBiasDenominator &&
          1.0 + standoff_term(m.name, *a, b.mach_high) > kMinBiasDenominator))
      continue;
    double ss = 0;
    for (const double e : loo) ss += e * e;
    const double rms = std::sqrt(ss / static_cast<double>(n));
    b.standoff_left_out_rms.emplace_back(m.name, rms);
    if (std::isnan(best_rms) || rms < best_rms - kLooTie) {
      best_rms = rms;
      best_loo = loo;
      b.standoff_model = m.name;
      b.standoff_coefficients = *a;
    }
  }
  for (std::size_t i = 0; i < n && i < best_loo.size(); ++i) b.bodies[i].loo_standoff = best_loo[i];
}

// Several runs of one body (same name and Mach number: other seeds) are one
// body: their stations pooled, their standoff errors averaged, so that
// leaving the body out leaves all of them out.
std::vector<StationErrors> pooled_by_body(const std::vector<StationErrors>& runs,
                                          std::vector<int>& run_counts) {
  std::vector<StationErrors> out;
  run_counts.clear();
  for (const auto& r : runs) {
    const auto same = std::find_if(out.begin(), out.end(), [&](const StationErrors& b) {
      return b.body == r.body && b.mach == r.mach;
    });
    if (same == out.end()) {
      out.push_back(r);
      run_counts.push_back(1);
      continue;
    }
    int& n = run_counts[static_cast<std::size_t>(same - out.begin())];
    same->relative.insert(same->relative.end(), r.relative.begin(), r.relative.end());
    same->inclination_deg.insert(same->inclination_deg.end(), r.inclination_deg.begin(),
                                 r.inclination_deg.end());
    same->standoff_relative = (same->standoff_relative * n + r.standoff_relative) / (n + 1);
    same->cpu_seconds += r.cpu_seconds;
    ++n;
  }
  for (auto& b : out) set_mean_and_rms(b);
  return out;
}

bool usable(const StationErrors& b) {
  if (b.relative.empty() || b.inclination_deg.size() != b.relative.size()) return false;
  if (!std::isfinite(b.standoff_relative) || !(b.mach > 0)) return false;
  return std::all_of(b.inclination_deg.begin(), b.inclination_deg.end(),
                     [](double x) { return std::isfinite(x); });
}
}  // namespace

std::size_t station_bias_coefficients(const std::string& model) {
  const Model* m = find_model(model);
  return m ? m->terms(0.0, 0.0).size() : 0;
}

std::string station_bias_formula(const std::string& model) {
  const Model* m = find_model(model);
  return m ? m->formula : "";
}

std::string standoff_term_formula(const std::string& model) {
  const StandoffModel* m = find_standoff_model(model);
  return m ? m->formula : "";
}

std::size_t standoff_term_coefficients(const std::string& model) {
  const StandoffModel* m = find_standoff_model(model);
  return m ? m->terms(0.0).size() : kUnknownStandoffModel;
}

std::string standoff_term_models() {
  return joined_names(kStandoffModels);
}

std::string station_bias_models() {
  return joined_names(kModels);
}

double inclination_deg(scene::Vec2 normal) {
  if (!std::isfinite(normal.x) || !std::isfinite(normal.y)) return kNaN;
  return std::atan2(std::abs(normal.y), -normal.x) / scene::kDeg;
}

double BowStationBias::relative_error(double mach, double inclination) const {
  const double m = std::clamp(mach, mach_low, mach_high);
  const double s = std::clamp(inclination, 0.0, max_inclination_deg);
  return evaluate(model, coefficients, m, s);
}

double BowStationBias::standoff_error(double mach) const {
  return standoff_term(standoff_model, standoff_coefficients,
                       std::clamp(mach, mach_low, mach_high));
}

std::optional<BowStationBias> fit_station_bias(const std::string& shape,
                                               const std::vector<StationErrors>& runs) {
  std::vector<int> run_counts;
  const std::vector<StationErrors> bodies = pooled_by_body(runs, run_counts);
  if (bodies.size() < kMinBiasBodies) return std::nullopt;
  if (!std::all_of(bodies.begin(), bodies.end(), usable)) return std::nullopt;
  std::optional<BowStationBias> best;
  for (const auto& spec : kModels) {
    const std::string model = spec.name;
    const auto c = solve(model, bodies, bodies.size());
    if (!c) continue;
    BowStationBias b;
    b.shape = shape;
    b.model = model;
    b.coefficients = *c;
    b.max_inclination_deg = 0;
    b.mach_low = b.mach_high = bodies.front().mach;
    b.cpu_seconds = 0.0;
    for (const auto& body : bodies) {
      b.cpu_seconds += body.cpu_seconds;  // NaN when a run did not record it
      b.mach_low = std::min(b.mach_low, body.mach);
      b.mach_high = std::max(b.mach_high, body.mach);
      for (const double x : body.inclination_deg)
        b.max_inclination_deg = std::max(b.max_inclination_deg, x);
    }
    // Distances must stay positive wherever the model is held: monotone in
    // 1/M^2, so the Mach ends; across the inclinations, checked point by point.
    bool positive = true;
    for (const double m : {b.mach_low, b.mach_high})
      for (int k = 0; k <= kPositivityChecks; ++k)
        positive =
            positive && 1.0 + b.relative_error(m, b.max_inclination_deg * k / kPositivityChecks) >
                            kMinBiasDenominator;
    if (!positive) continue;
    double ss = 0, ss0 = 0;
    bool all_left_out = true;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const auto& body = bodies[i];
      const auto loo = solve(model, bodies, i);
      if (!loo) {
        all_left_out = false;
        break;
      }
      const Corrected k = corrected(model, *loo, body);
      BowStationBiasBody r;
      r.body = body.body;
      r.mach = body.mach;
      r.stations = static_cast<int>(body.relative.size());
      r.runs = run_counts[i];
      r.mean = body.mean;
      r.rms = body.rms;
      r.standoff = body.standoff_relative;
      r.loo_mean = k.mean;
      r.loo_rms = k.rms;
      r.loo_standoff = k.standoff;
      b.bodies.push_back(r);
      ss += k.rms * k.rms;
      ss0 += body.rms * body.rms;
    }
    if (!all_left_out) continue;
    const double n = static_cast<double>(bodies.size());
    b.relative_rms = std::sqrt(ss / n);
    b.uncorrected_rms = std::sqrt(ss0 / n);
    if (!best || b.relative_rms < best->relative_rms - kLooTie) best = b;
  }
  if (best) choose_standoff_term(*best, bodies);
  return best;
}

std::vector<scene::ShockCsvRow> unbiased_stations(const std::vector<scene::ShockCsvRow>& rows,
                                                  const BowStationBias& b, double mach) {
  std::vector<scene::ShockCsvRow> out = rows;
  for (auto& r : out) {
    const double inc = inclination_deg(r.normal);
    if (!std::isfinite(inc) || !std::isfinite(r.distance) || !std::isfinite(r.surface.x)) continue;
    const double f = 1.0 / (1.0 + b.relative_error(mach, inc));
    r.distance *= f;
    if (std::isfinite(r.ci)) r.ci *= f;
    r.shock = r.surface + r.distance * r.normal;
  }
  return out;
}

double left_out_standoff_rms(const BowStationBias& b) {
  double ss = 0;
  for (const auto& r : b.bodies) ss += r.loo_standoff * r.loo_standoff;
  return b.bodies.empty() ? kNaN : std::sqrt(ss / static_cast<double>(b.bodies.size()));
}

double unbiased_standoff_factor(const BowStationBias& b, double mach) {
  return 1.0 / ((1.0 + b.relative_error(mach, 0.0)) * (1.0 + b.standoff_error(mach)));
}

}  // namespace pipeline
