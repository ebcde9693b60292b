// shock.csv reader: a header row, columns by name (contract.md).
#include <cmath>
#include <filesystem>
#include <sstream>

#include "meshgen/mesh.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"

namespace meshgen {

namespace {

std::vector<std::string> split_csv(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  std::istringstream is(line);
  while (std::getline(is, field, ',')) {
    const auto b = field.find_first_not_of(" \t\r\"");
    const auto e = field.find_last_not_of(" \t\r\"");
    out.push_back(b == std::string::npos ? "" : field.substr(b, e - b + 1));
  }
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

double parse_number(const std::string& text, const std::string& where, const std::string& column) {
  if (text == "nan" || text == "NaN" || text.empty()) return std::nan("");
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size())
    throw scene::InputError(where + ": column '" + column + "': expected a number, got '" + text + "'");
  return v;
}

}  // namespace

MeshRequest request_from_shock_csv(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw scene::InputError(path + ": shock file not found");
  std::istringstream in(scene::read_file(path));
  std::string line;
  std::size_t line_no = 0;
  std::vector<std::string> header;
  while (header.empty() && std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") != std::string::npos && line[0] != '#') header = split_csv(line);
  }
  if (header.empty()) throw scene::InputError(path + ": shock file is empty (expected a header row with shock_x, shock_y, accepted)");
  const auto column = [&](const std::string& name, bool required) -> int {
    for (std::size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    if (required) throw scene::InputError(path + ":" + std::to_string(line_no) + ": missing column '" + name + "'");
    return -1;
  };
  const int cx = column("shock_x", true), cy = column("shock_y", true), ca = column("accepted", true);
  const int cci = column("ci", false);
  MeshRequest r;
  std::size_t rows = 0;
  bool any_ci = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos || line[0] == '#') continue;
    ++rows;
    const std::vector<std::string> f = split_csv(line);
    const std::string where = path + ":" + std::to_string(line_no);
    const int need = std::max({cx, cy, ca, cci});
    if (static_cast<int>(f.size()) <= need)
      throw scene::InputError(where + ": expected " + std::to_string(header.size()) + " fields, got " + std::to_string(f.size()));
    const double acc = parse_number(f[static_cast<std::size_t>(ca)], where, "accepted");
    if (!(acc == 1.0)) continue;
    const double x = parse_number(f[static_cast<std::size_t>(cx)], where, "shock_x");
    const double y = parse_number(f[static_cast<std::size_t>(cy)], where, "shock_y");
    if (!std::isfinite(x) || !std::isfinite(y))
      throw scene::InputError(where + ": accepted row with a non-finite shock_x or shock_y");
    double ci = std::nan("");
    if (cci >= 0) ci = parse_number(f[static_cast<std::size_t>(cci)], where, "ci");
    any_ci = any_ci || std::isfinite(ci);
    r.shock_curve.push_back({x, y});
    r.shock_ci.push_back(ci);
  }
  if (rows == 0) throw scene::InputError(path + ": shock file has a header but no rows");
  if (r.shock_curve.empty()) throw scene::InputError(path + ": no accepted rows (accepted == 1) among " + std::to_string(rows));
  if (!any_ci) r.shock_ci.clear();
  return r;
}

}  // namespace meshgen
