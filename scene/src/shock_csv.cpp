#include "scene/shock_csv.hpp"

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "scene/csv.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"

namespace scene {

namespace {

// Enough digits that a round trip through the file changes nothing that
// matters (the fit's own uncertainty is far larger).
constexpr int kDigits = 12;

bool skipped(const std::string& line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string::npos || line[first] == '#';
}

double parse_number(const std::string& text, const std::string& where, const std::string& column) {
  if (text == "nan" || text == "NaN" || text.empty()) return kNaN;
  std::size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size())
    throw InputError(where + ": column '" + column + "': expected a number, got '" + text + "'");
  return v;
}

std::string num(double v) {
  if (!std::isfinite(v)) return "nan";
  std::ostringstream os;
  os.precision(kDigits);
  os << v;
  return os.str();
}

}  // namespace

const std::vector<std::string>& shock_csv_columns() {
  static const std::vector<std::string> columns{"station",  "surface_x", "surface_y", "normal_x",
                                                "normal_y", "shock_x",   "shock_y",   "distance",
                                                "ci",       "fit_error", "accepted"};
  return columns;
}

void write_shock_csv(const std::string& path, const std::vector<ShockCsvRow>& rows) {
  write_stream_atomic(path, [&](std::ostream& o) {
    const auto& columns = shock_csv_columns();
    for (std::size_t c = 0; c < columns.size(); ++c) o << (c ? "," : "") << columns[c];
    o << '\n';
    for (const ShockCsvRow& r : rows)
      o << r.station << ',' << num(r.surface.x) << ',' << num(r.surface.y) << ',' << num(r.normal.x)
        << ',' << num(r.normal.y) << ',' << num(r.shock.x) << ',' << num(r.shock.y) << ','
        << num(r.distance) << ',' << num(r.ci) << ',' << num(r.fit_error) << ','
        << (r.accepted ? 1 : 0) << '\n';
  });
}

ShockCsv read_shock_csv(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw InputError(path + ": shock file not found");
  std::istringstream in(read_file(path));
  std::string line;
  std::size_t line_no = 0;
  std::vector<std::string> header;
  while (header.empty() && std::getline(in, line)) {
    ++line_no;
    if (!skipped(line)) header = split_csv(line);
  }
  if (header.empty())
    throw InputError(
        path + ": shock file is empty (expected a header row with shock_x, shock_y, accepted)");
  std::map<std::string, std::size_t> column;
  for (std::size_t i = 0; i < header.size(); ++i) column.emplace(header[i], i);
  for (const char* required : {"shock_x", "shock_y", "accepted"})
    if (!column.count(required))
      throw InputError(path + ":" + std::to_string(line_no) + ": missing column '" + required +
                       "'");

  ShockCsv out;
  out.has_ci = column.count("ci") > 0;
  std::size_t accepted = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (skipped(line)) continue;
    const std::vector<std::string> fields = split_csv(line);
    const std::string where = path + ":" + std::to_string(line_no);
    const auto get = [&](const std::string& name) {
      const auto it = column.find(name);
      if (it == column.end()) return kNaN;
      if (it->second >= fields.size())
        throw InputError(where + ": no field for column '" + name + "' (" +
                         std::to_string(fields.size()) + " fields, the header has " +
                         std::to_string(header.size()) + ")");
      return parse_number(fields[it->second], where, name);
    };
    ShockCsvRow r;
    const double station = get("station");
    r.station =
        std::isfinite(station) ? static_cast<int>(station) : static_cast<int>(out.rows.size());
    r.surface = {get("surface_x"), get("surface_y")};
    r.normal = {get("normal_x"), get("normal_y")};
    r.shock = {get("shock_x"), get("shock_y")};
    r.distance = get("distance");
    r.ci = get("ci");
    r.fit_error = get("fit_error");
    const double acc = get("accepted");
    if (!(acc == 0.0 || acc == 1.0))
      throw InputError(where + ": column 'accepted': expected 1 or 0, got '" +
                       fields[column.at("accepted")] + "'");
    r.accepted = acc == 1.0;
    if (r.accepted && !(std::isfinite(r.shock.x) && std::isfinite(r.shock.y)))
      throw InputError(where + ": accepted row with a non-finite shock_x or shock_y");
    accepted += r.accepted ? 1 : 0;
    out.rows.push_back(r);
  }
  if (out.rows.empty()) throw InputError(path + ": shock file has a header but no rows");
  if (accepted == 0)
    throw InputError(path + ": no accepted rows (accepted == 1) among " +
                     std::to_string(out.rows.size()));
  if (accepted < kMinShockCurvePoints)
    throw InputError(path + ": only " + std::to_string(accepted) +
                     " accepted row (accepted == 1) among " + std::to_string(out.rows.size()) +
                     "; a shock curve needs at least " + std::to_string(kMinShockCurvePoints));
  return out;
}

}  // namespace scene
