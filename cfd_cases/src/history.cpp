#include "cfd/history.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "scene/errors.hpp"

namespace cfd {

namespace {
std::vector<std::string> split_row(const std::string& line) {
  std::vector<std::string> cols;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) cols.push_back(f);
  return cols;
}
}  // namespace

double last_history_value(const std::string& case_dir, const std::string& column) {
  const std::string path = case_dir + "/history.csv";
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line))
    throw scene::InputError(path + ": not found or empty (a finished CFD case expected)");
  const auto header = split_row(line);
  const auto it = std::find(header.begin(), header.end(), column);
  if (it == header.end()) throw scene::InputError(path + ": no column '" + column + "'");
  const auto k = static_cast<std::size_t>(it - header.begin());
  double last = std::nan("");
  while (std::getline(in, line)) {
    const auto cols = split_row(line);
    if (cols.size() <= k) continue;
    char* end = nullptr;
    const double v = std::strtod(cols[k].c_str(), &end);
    if (end != cols[k].c_str() && std::isfinite(v)) last = v;
  }
  if (!std::isfinite(last))
    throw scene::InputError(path + ": column '" + column + "' holds no finite value");
  return last;
}

}  // namespace cfd
