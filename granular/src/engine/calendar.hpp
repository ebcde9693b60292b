#pragma once
// Event calendar: a complete binary (tournament) tree over particle slots.
// Each slot holds only its earliest event time; inner nodes hold the slot
// that wins their subtree. Updating one slot is log2(capacity) comparisons
// with no allocation; the minimum is at the root. Ties go to the lower slot
// index, so the order of equal-time events is deterministic.
#include <cstdint>
#include <limits>
#include <vector>

namespace granular::detail {

class Calendar {
 public:
  void resize(std::size_t slots) {
    std::size_t p = 1;
    while (p < slots) p <<= 1;
    leaves_ = p;
    key_.assign(p, std::numeric_limits<double>::infinity());
    node_.assign(p, 0);
    for (std::size_t k = p - 1; k >= 1; --k) node_[k] = winner_of(k);
  }
  std::size_t capacity() const { return leaves_; }
  // Grows to hold `slots`, keeping every key.
  void grow(std::size_t slots) {
    if (slots <= leaves_) return;
    std::vector<double> keys = key_;
    resize(slots);
    for (std::size_t i = 0; i < keys.size(); ++i) key_[i] = keys[i];
    rebuild();
  }
  void rebuild() {
    for (std::size_t k = leaves_ - 1; k >= 1; --k) node_[k] = winner_of(k);
  }
  void set(std::size_t slot, double t) {
    key_[slot] = t;
    for (std::size_t k = (slot + leaves_) >> 1; k >= 1; k >>= 1) node_[k] = winner_of(k);
  }
  // Sets without re-ranking (bulk load; call rebuild() after).
  void set_quiet(std::size_t slot, double t) { key_[slot] = t; }
  std::uint32_t top() const { return leaves_ > 1 ? node_[1] : 0; }
  double top_time() const { return key_[top()]; }
  double key(std::size_t slot) const { return key_[slot]; }
  double bytes() const { return static_cast<double>(key_.size() * sizeof(double) + node_.size() * sizeof(std::uint32_t)); }

 private:
  std::uint32_t child_winner(std::size_t k) const {
    return k >= leaves_ ? static_cast<std::uint32_t>(k - leaves_) : node_[k];
  }
  std::uint32_t winner_of(std::size_t k) const {
    const std::uint32_t a = child_winner(2 * k), b = child_winner(2 * k + 1);
    return key_[a] <= key_[b] ? a : b;
  }

  std::size_t leaves_ = 1;
  std::vector<double> key_{std::numeric_limits<double>::infinity()};
  std::vector<std::uint32_t> node_{0};
};

}  // namespace granular::detail
