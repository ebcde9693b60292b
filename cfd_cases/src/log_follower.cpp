#include "log_follower.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>

namespace cfd {
namespace {
// Written times and logged step times are both printed with timePrecision
// digits; this slack treats them as equal.
constexpr double kTimeSlack = 1e-9;
}  // namespace

void LogFollower::update() {
  std::ifstream in(path_, std::ios::binary);
  if (!in) return;
  in.seekg(static_cast<std::streamoff>(offset_));
  std::string chunk((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  offset_ += chunk.size();
  partial_ += chunk;
  std::size_t start = 0;
  for (std::size_t nl; (nl = partial_.find('\n', start)) != std::string::npos; start = nl + 1) {
    const std::string line = partial_.substr(start, nl - start);
    if (line.rfind("Time = ", 0) == 0) {
      times_.push_back(std::strtod(line.c_str() + 7, nullptr));
    } else if (divergence_.empty() && (line.rfind("Mean and max Courant", 0) == 0 || line.rfind("deltaT = ", 0) == 0)) {
      std::string low = line;
      std::transform(low.begin(), low.end(), low.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      if (low.find("nan") != std::string::npos || low.find("inf") != std::string::npos) divergence_ = line;
    }
  }
  partial_.erase(0, start);
}

long LogFollower::steps_upto(double t) const {
  const double lim = t + kTimeSlack * std::max(1.0, std::abs(t));
  return static_cast<long>(std::upper_bound(times_.begin(), times_.end(), lim) - times_.begin());
}

}  // namespace cfd
