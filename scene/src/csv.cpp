#include "scene/csv.hpp"

#include <sstream>

namespace scene {

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

}  // namespace scene
