#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "plot.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/progress.hpp"
#include "scene/shock_csv.hpp"
#include "shockfit/locate.hpp"

namespace shockfit {

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::stringstream ss(line);
  while (std::getline(ss, cell, ',')) {
    const auto b = cell.find_first_not_of(" \t\r"), e = cell.find_last_not_of(" \t\r");
    out.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

}  // namespace

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

std::vector<StationFit> read_shock_csv(const std::string& path) {
  const std::string text = scene::read_file(path);
  std::istringstream in(text);
  std::string line;
  auto bad = [&](const std::string& what) { return scene::InputError(path + ": not a shock.csv file: " + what); };
  if (!std::getline(in, line) || split_csv(line).empty() || line.find_first_not_of(" \t\r") == std::string::npos)
    throw bad("file is empty");
  const std::vector<std::string> header = split_csv(line);
  std::map<std::string, std::size_t> col;
  for (std::size_t c = 0; c < header.size(); ++c) col[header[c]] = c;
  for (const char* need : {"shock_x", "shock_y", "accepted"})
    if (!col.count(need)) throw bad(std::string("no column '") + need + "' in the header");
  std::vector<StationFit> out;
  int lineno = 1;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> cells = split_csv(line);
    if (cells.size() != header.size())
      throw bad("line " + std::to_string(lineno) + " has " + std::to_string(cells.size()) + " fields, the header " +
                std::to_string(header.size()));
    auto get = [&](const char* name, double def) {
      const auto it = col.find(name);
      if (it == col.end()) return def;
      const std::string& c = cells[it->second];
      if (c == "nan" || c == "NaN" || c.empty()) return std::nan("");
      try {
        std::size_t used = 0;
        const double v = std::stod(c, &used);
        if (used != c.size()) throw std::invalid_argument(c);
        return v;
      } catch (const std::exception&) {
        throw bad("line " + std::to_string(lineno) + ", column '" + name + "': '" + c + "' is not a number");
      }
    };
    StationFit f;
    f.station = static_cast<int>(get("station", static_cast<double>(out.size())));
    f.surface = {get("surface_x", std::nan("")), get("surface_y", std::nan(""))};
    f.normal = {get("normal_x", std::nan("")), get("normal_y", std::nan(""))};
    f.shock = {get("shock_x", std::nan("")), get("shock_y", std::nan(""))};
    f.distance = get("distance", std::nan(""));
    f.ci = get("ci", std::nan(""));
    f.fit_error = get("fit_error", std::nan(""));
    const double acc = get("accepted", 0.0);
    if (!(acc == 0.0 || acc == 1.0))
      throw bad("line " + std::to_string(lineno) + ", column 'accepted': expected 1 or 0");
    f.accepted = acc == 1.0;
    if (f.accepted && !(std::isfinite(f.shock.x) && std::isfinite(f.shock.y)))
      throw bad("line " + std::to_string(lineno) + ": an accepted row needs a finite shock_x, shock_y");
    out.push_back(f);
  }
  if (out.empty()) throw bad("no data rows");
  return out;
}

}  // namespace shockfit
