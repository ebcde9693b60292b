#include <sys/wait.h>
#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "json_fields.hpp"
#include "pipeline/plot.hpp"
#include "pipeline/process_pool.hpp"
#include "pipeline/run.hpp"
#include "pipeline/studies.hpp"
#include "scene/cli.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"
#include "scene/yaml_text.hpp"
#include "scene/progress.hpp"

namespace pipeline {

namespace fs = std::filesystem;

Vary parse_vary(const std::string& arg) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 >= arg.size())
    throw scene::InputError("--vary '" + arg + "': expected KEY=v1,v2,... (e.g. granular.restitution=0.8,0.9)");
  Vary v;
  v.key = arg.substr(0, eq);
  std::stringstream ss(arg.substr(eq + 1));
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) v.values.push_back(item);
  if (v.values.empty()) throw scene::InputError("--vary '" + arg + "': no values");
  return v;
}

scene::Scene scene_with(const std::string& scene_path,
                        const std::vector<std::pair<std::string, std::string>>& sets) {
  YAML::Node root;
  try {
    // A malformed scene must be an input error, never a parser hang.
    if (std::filesystem::is_regular_file(scene_path)) scene::check_yaml_text(scene::read_file(scene_path), scene_path);
    root = YAML::LoadFile(scene_path);
  } catch (const YAML::BadFile&) {
    throw scene::InputError(scene_path + ": scene file not found");
  } catch (const YAML::Exception& e) {
    throw scene::InputError(scene_path + ":" + std::to_string(e.mark.line + 1) + ": malformed YAML: " + e.msg);
  }
  for (const auto& [key, value] : sets) {
    std::vector<std::string> parts;
    std::stringstream ss(key);
    std::string p;
    while (std::getline(ss, p, '.')) parts.push_back(p);
    // Walk with explicit node handles: yaml-cpp's operator[] on a temporary
    // would rebind, so keep the chain in a vector.
    std::vector<YAML::Node> chain{root};
    for (std::size_t k = 0; k + 1 < parts.size(); ++k) {
      YAML::Node next = chain.back()[parts[k]];
      if (!next.IsDefined() || next.IsNull()) {
        chain.back()[parts[k]] = YAML::Node(YAML::NodeType::Map);
        next = chain.back()[parts[k]];
      }
      chain.push_back(next);
    }
    chain.back()[parts.back()] = YAML::Load(value);
  }
  YAML::Emitter e;
  e << root;
  scene::Scene s = scene::parse_scene(e.c_str(), scene_path);
  s.name = fs::path(scene_path).stem().string();
  return s;
}

void for_each_in_processes(int n, int jobs, const std::function<int(int)>& work) {
  if (jobs <= 1) {
    for (int k = 0; k < n && !scene::interrupted(); ++k) work(k);
    return;
  }
  int running = 0, next = 0, failed = 0;
  while (next < n || running > 0) {
    while (running < jobs && next < n && !scene::interrupted()) {
      const pid_t pid = ::fork();
      if (pid == 0) std::_Exit(scene::run_guarded("pipeline", [&] { return work(next); }));
      if (pid < 0) throw scene::RunError("fork failed");
      ++running;
      ++next;
    }
    int status = 0;
    if (::wait(&status) > 0) {
      --running;
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) ++failed;
    } else {
      break;
    }
  }
  if (failed) scene::log_line("pipeline: " + std::to_string(failed) + " sweep case(s) failed; see their directories", true);
}

nlohmann::json run_sweep(const std::string& scene_path, const std::vector<Vary>& vary, const SweepOptions& o) {
  // Cartesian product of the values, first key slowest.
  std::vector<std::vector<std::pair<std::string, std::string>>> cases{{}};
  for (const auto& v : vary) {
    std::vector<std::vector<std::pair<std::string, std::string>>> next;
    for (const auto& c : cases)
      for (const auto& val : v.values) {
        auto cc = c;
        cc.emplace_back(v.key, val);
        next.push_back(cc);
      }
    cases = next;
  }
  // Validate every case before running any.
  for (const auto& c : cases) (void)scene_with(scene_path, c);
  scene::make_dirs(o.out_dir);
  auto case_dir = [&](int k) { return o.out_dir + "/case_" + std::to_string(k); };
  scene::Progress progress("sweep", static_cast<double>(cases.size()), "cases");
  for_each_in_processes(static_cast<int>(cases.size()), o.jobs, [&](int k) {
    const auto s = scene_with(scene_path, cases[k]);
    const auto r = run_prediction(s, case_dir(k), o.np);
    scene::write_json_atomic(case_dir(k) + "/prediction.json", r);
    progress.update(k + 1);
    return 0;
  });
  progress.finish();
  nlohmann::json rows = nlohmann::json::array();
  std::ostringstream csv;
  for (const auto& v : vary) csv << v.key << ",";
  csv << "shock,shock_angle_deg,shock_angle_ci_deg,standoff,standoff_ci,granular_wall_seconds\n";
  for (std::size_t k = 0; k < cases.size(); ++k) {
    nlohmann::json row;
    for (const auto& [key, val] : cases[k]) {
      row[key] = val;
      csv << val << ",";
    }
    nlohmann::json pred;
    try {
      pred = nlohmann::json::parse(scene::read_file(case_dir(static_cast<int>(k)) + "/prediction.json"));
    } catch (const std::exception&) {
      pred = {{"shock", "failed"}};
    }
    row["prediction"] = pred;
    rows.push_back(row);
    csv << pred.value("shock", "failed") << "," << number_or_nan(pred, "shock_angle_deg") << "," << number_or_nan(pred, "shock_angle_ci_deg")
        << "," << number_or_nan(pred, "standoff") << "," << number_or_nan(pred, "standoff_ci") << "," << number_or_nan(pred, "granular_wall_seconds") << "\n";
  }
  scene::write_file_atomic(o.out_dir + "/sweep.csv", csv.str());
  scene::write_json_atomic(o.out_dir + "/sweep.json", rows);
  // Shock angle (or standoff) against the first key, a series per value of the second.
  if (!vary.empty()) {
    std::map<std::string, Series> series;
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const auto& pred = rows[k]["prediction"];
      double y = number_or_nan(pred, "shock_angle_deg");
      if (!std::isfinite(y)) y = number_or_nan(pred, "standoff");
      if (!std::isfinite(y)) continue;
      const std::string label = cases[k].size() > 1 ? cases[k][1].first + " = " + cases[k][1].second : "granular";
      auto& s = series[label];
      s.title = label;
      try {
        s.x.push_back(std::stod(cases[k][0].second));
        s.y.push_back(y);
      } catch (const std::exception&) {
        // non-numeric values: the table still lists them; the plot skips them
      }
    }
    PlotSpec spec{"Granular shock over the sweep", vary[0].key, "shock angle (deg) or standoff (body lengths)", false, false, {}, {}};
    for (auto& [k, s] : series) spec.series.push_back(s);
    plot_png(spec, o.out_dir + "/sweep.png");
  }
  return rows;
}

}  // namespace pipeline
