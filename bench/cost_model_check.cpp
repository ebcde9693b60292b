// The dry-run cost model (pipeline/src/cost_estimate.cpp) against recorded
// `pipeline run` / `pipeline studies` outputs: for every grid that reached a
// steady state time-accurately, the model's cells, solver steps and CPU
// seconds beside the measured ones, and the fitted figures the model's
// constants come from.
//
//   cost_model_check [--fit] RUNDIR...
//
// RUNDIR: a `pipeline run` output (scene.resolved.yaml, cfd/, meshgen/) or a
// folder of them (a `pipeline studies` output). --fit prints, from these
// runs, the solver's CPU per step and per cell-step (least squares on
// relative residuals: timing noise is multiplicative), and per body class the
// median flow-throughs to steady and the median effective time-step fraction
// f in dt = max_co f h / (M + 2). Without --fit: the model's out-of-sample
// check (ratio measured / estimated, its median, log standard deviation and
// the share within the model's stated +-50%).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "pipeline/cost_estimate.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/scene.hpp"

namespace fs = std::filesystem;

namespace {

struct Run {
  std::string label;        // case/grid
  bool attached = false;    // attached-shock wedge (else a bow shock)
  double cells = 0, steps = 0, flow_throughs = 0, cfd_cpu = 0, mesh_cpu = 0;
  double step_fraction = 0;  // f in dt = max_co f h / (M + 2)
  pipeline::GridEstimate estimate;
};

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in, nullptr, false);
}

double level_of(const std::string& grid) {
  const auto at = grid.rfind("_h");
  return at == std::string::npos ? std::nan("") : std::atof(grid.c_str() + at + 2);
}

void collect_case(const fs::path& dir, std::vector<Run>& runs) {
  const scene::Scene s = scene::load_scene((dir / "scene.resolved.yaml").string());
  const std::string predictor = "granular";
  // The band the run's prediction carried: its calibration scatter, as recorded.
  const nlohmann::json run = read_json(dir / "summary.json");
  const auto recorded = [&](const char* key) {
    const nlohmann::json::json_pointer at("/prediction/details/" + std::string(key));
    return run.is_object() && run.contains(at) && run.at(at).is_number() ? run.at(at).get<double>()
                                                                         : scene::kNaN;
  };
  const pipeline::RunEstimate est = pipeline::estimate_run(
      s, predictor,
      {recorded("calibration_angle_scatter_deg"), recorded("calibration_bow_shock_relative_rms")});
  const double L = scene::body_length(*s.body);
  for (const auto& g : est.grids) {
    const nlohmann::json cfd = read_json(dir / "cfd" / g.name / "summary.json");
    const nlohmann::json mesh = read_json(dir / "meshgen" / g.name / "summary.json");
    if (cfd.is_discarded() || !cfd.value("steady_state_reached", false) || cfd.value("local_time_stepping", false))
      continue;
    Run r;
    r.label = dir.filename().string() + "/" + g.name;
    r.attached = scene::attached_shock_beta(s).has_value();
    r.cells = cfd.value("cells", 0.0);
    r.steps = cfd.value("steps", 0.0);
    r.flow_throughs = cfd.value("flow_throughs", 0.0);
    r.cfd_cpu = cfd.value("cpu_seconds", 0.0);
    r.mesh_cpu = mesh.is_discarded() ? 0.0 : mesh.value("cpu_seconds", 0.0);
    const double h = s.mesh.h_min * L * level_of(g.name);
    const double dt = cfd.value("sim_time", 0.0) / std::max(1.0, r.steps);
    r.step_fraction = dt * (s.freestream.mach + 2.0) / (s.cfd.max_co * h);
    r.estimate = g;
    runs.push_back(r);
  }
}

std::vector<Run> collect(const std::vector<std::string>& roots) {
  std::vector<Run> runs;
  for (const auto& root : roots) {
    if (fs::exists(fs::path(root) / "scene.resolved.yaml")) {
      collect_case(root, runs);
      continue;
    }
    std::vector<fs::path> cases;
    for (const auto& e : fs::directory_iterator(root))
      if (fs::exists(e.path() / "scene.resolved.yaml")) cases.push_back(e.path());
    std::sort(cases.begin(), cases.end());
    for (const auto& c : cases) collect_case(c, runs);
  }
  return runs;
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void fit(const std::vector<Run>& runs) {
  // cpu = steps (a + b cells), residuals relative to cpu.
  double s11 = 0, s12 = 0, s22 = 0, t1 = 0, t2 = 0;
  for (const auto& r : runs) {
    const double x1 = r.steps / r.cfd_cpu, x2 = r.steps * r.cells / r.cfd_cpu;
    s11 += x1 * x1, s12 += x1 * x2, s22 += x2 * x2, t1 += x1, t2 += x2;
  }
  const double det = s11 * s22 - s12 * s12;
  const double a = (t1 * s22 - t2 * s12) / det, b = (s11 * t2 - s12 * t1) / det;
  double ss = 0;
  for (const auto& r : runs) ss += std::pow(std::log(r.cfd_cpu / (r.steps * (a + b * r.cells))), 2);
  std::printf("runs %zu: CPU per step %.3g s, per cell-step %.3g s (log sd of one timing %.2f)\n", runs.size(), a, b,
              std::sqrt(ss / static_cast<double>(runs.size())));
  for (const bool attached : {true, false})
    for (const char* family : {"", "uniform", "clustered"}) {
      std::vector<double> ft, f;
      for (const auto& r : runs)
        if (r.attached == attached && r.label.find(family) != std::string::npos)
          ft.push_back(r.flow_throughs), f.push_back(r.step_fraction);
      if (ft.empty()) continue;
      std::printf(
          "%-9s %-9s %3zu runs: flow-throughs to steady median %.2f (max %.2f); step fraction "
          "median %.2f "
          "(%.2f-%.2f)\n",
          attached ? "attached" : "bow shock", *family ? family : "all", ft.size(), median(ft),
          *std::max_element(ft.begin(), ft.end()), median(f), *std::min_element(f.begin(), f.end()),
          *std::max_element(f.begin(), f.end()));
    }
}

void check(const std::vector<Run>& runs) {
  std::printf("%-36s %9s %9s %9s %9s %10s %10s %7s\n", "grid", "cells", "est", "steps", "est", "CPU s", "est",
              "ratio");
  std::vector<double> log_ratio;
  int within = 0;
  double total = 0, total_est = 0;
  for (const auto& r : runs) {
    const double cpu = r.cfd_cpu + r.mesh_cpu, ratio = cpu / r.estimate.cpu_seconds;
    std::printf("%-36s %9.0f %9.0f %9.0f %9.0f %10.1f %10.1f %7.2f\n", r.label.c_str(), r.cells, r.estimate.cells,
                r.steps, r.estimate.steps, cpu, r.estimate.cpu_seconds, ratio);
    log_ratio.push_back(std::log(ratio));
    constexpr double kStatedBand = 1.5;  // the model's stated +-50%
    within += ratio <= kStatedBand && ratio >= 1.0 / kStatedBand;
    total += cpu, total_est += r.estimate.cpu_seconds;
  }
  double mean = 0, ss = 0;
  for (const double x : log_ratio) mean += x / static_cast<double>(log_ratio.size());
  for (const double x : log_ratio) ss += (x - mean) * (x - mean) / static_cast<double>(log_ratio.size());
  std::printf("grids %zu: measured / estimated CPU median %.2f, log sd %.2f, within +-50%%: %d; sum %.0f s vs %.0f s estimated (%.2f)\n",
              runs.size(), std::exp(median(log_ratio)), std::sqrt(ss), within, total, total_est, total / total_est);
}

}  // namespace

int main(int argc, char** argv) {
  bool do_fit = false;
  std::vector<std::string> roots;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--fit") do_fit = true;
    else roots.push_back(a);
  }
  if (roots.empty()) {
    std::fprintf(stderr, "usage: cost_model_check [--fit] RUNDIR...\n");
    return 2;
  }
  try {
    const std::vector<Run> runs = collect(roots);
    if (runs.empty()) {
      std::fprintf(stderr, "cost_model_check: no steady time-accurate grid runs under the given folders\n");
      return 1;
    }
    if (do_fit) fit(runs);
    else check(runs);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cost_model_check: %s\n", e.what());
    return 1;
  }
  return 0;
}
