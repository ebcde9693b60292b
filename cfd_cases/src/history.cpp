#include "cfd/history.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "scene/csv.hpp"
#include "scene/errors.hpp"

namespace cfd {

double last_history_value(const std::string& case_dir, const std::string& column) {
  const std::string path = case_dir + "/history.csv";
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line))
    throw scene::InputError(path + ": not found or empty (a finished CFD case expected)");
  const auto header = scene::split_csv(line);
  const auto it = std::find(header.begin(), header.end(), column);
  if (it == header.end()) throw scene::InputError(path + ": no column '" + column + "'");
  const auto k = static_cast<std::size_t>(it - header.begin());
  double last = std::nan("");
  while (std::getline(in, line)) {
    const auto cols = scene::split_csv(line);
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
