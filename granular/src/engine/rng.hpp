#pragma once
// Small deterministic generator (xoshiro256**, seeded by splitmix64) with
// its own normal sampler, so a seed gives the same run with any standard
// library, and the state is four integers a checkpoint can hold.
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>

namespace granular::detail {

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 1) {
    std::uint64_t z = seed;
    for (auto& w : s_) {
      z += 0x9E3779B97F4A7C15ULL;
      std::uint64_t x = z;
      x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
      x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
      w = x ^ (x >> 31);
    }
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform in (0, 1]: safe under a logarithm.
  double uniform_open0() { return 1.0 - uniform(); }
  // Standard normal (Box-Muller; the second value is discarded so the
  // state is only the four words).
  double normal() {
    const double u = uniform_open0(), v = uniform();
    return std::sqrt(-2.0 * std::log(u)) * std::cos(2.0 * std::numbers::pi * v);
  }
  std::array<std::uint64_t, 4> state() const { return s_; }
  void set_state(const std::array<std::uint64_t, 4>& s) { s_ = s; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::array<std::uint64_t, 4> s_{};
};

}  // namespace granular::detail
