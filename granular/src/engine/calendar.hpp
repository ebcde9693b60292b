#pragma once
// Event calendar: a complete binary (tournament) tree over particle slots.
// Each slot holds only its earliest event time; every node holds the
// (time, slot) that wins its subtree, so a comparison reads the two sibling
// nodes, which share a cache line. Updating a slot walks towards the root
// and stops as soon as a node comes out unchanged (its ancestors then are
// too): most updates stop after a few levels. Ties go to the lower slot
// index, so the order of equal-time events is deterministic.
#include <cstdint>
#include <limits>
#include <vector>

#include "huge_alloc.hpp"

namespace granular::detail {

class Calendar {
 public:
  // Any leaf count works: in the implicit layout (leaves at
  // [leaves, 2 leaves)) every leaf has a path to the root, so node 1 is the
  // minimum of all of them.
  void resize(std::size_t slots) {
    const std::size_t p = slots < 1 ? 1 : slots;
    leaves_ = p;
    node_.assign(2 * p, Node{std::numeric_limits<double>::infinity(), 0});
    for (std::size_t i = 0; i < p; ++i) node_[p + i].slot = static_cast<std::uint32_t>(i);
    rebuild();
  }
  std::size_t capacity() const { return leaves_; }
  // Grows to hold `slots`, keeping every key.
  void grow(std::size_t slots) {
    if (slots <= leaves_) return;
    const std::size_t old = leaves_;
    std::vector<Node> keep(node_.begin() + static_cast<std::ptrdiff_t>(old), node_.end());
    resize(slots < 2 * old ? 2 * old : slots);  // doubling: amortised O(1) per added slot
    for (std::size_t i = 0; i < old; ++i) node_[leaves_ + i].key = keep[i].key;
    rebuild();
  }
  void rebuild() {
    for (std::size_t k = leaves_ - 1; k >= 1 && k < leaves_; --k) node_[k] = best(node_[2 * k], node_[2 * k + 1]);
  }
  void set(std::size_t slot, double t) {
    std::size_t k = slot + leaves_;
    node_[k].key = t;
    for (k >>= 1; k >= 1; k >>= 1) {
      const Node w = best(node_[2 * k], node_[2 * k + 1]);
      if (w.key == node_[k].key && w.slot == node_[k].slot) break;  // ancestors unchanged
      node_[k] = w;
    }
  }
  // Starts loading the slot's path to the root (the levels that do not stay
  // in cache for large systems), so that set() later finds it in cache.
  void prefetch(std::size_t slot) const {
    std::size_t k = slot + leaves_;
    for (int level = 0; level < kPrefetchLevels && k >= 1; ++level, k >>= 1)
      __builtin_prefetch(&node_[k & ~std::size_t{1}]);
  }
  // Sets without re-ranking (bulk load; call rebuild() after).
  void set_quiet(std::size_t slot, double t) { node_[slot + leaves_].key = t; }
  std::uint32_t top() const { return node_[1].slot; }
  double top_time() const { return node_[1].key; }
  double key(std::size_t slot) const { return node_[slot + leaves_].key; }
  double bytes() const { return static_cast<double>(node_.size() * sizeof(Node)); }

 private:
  struct Node {
    double key;
    std::uint32_t slot;
  };
  static Node best(const Node& a, const Node& b) {
    return (a.key < b.key || (a.key == b.key && a.slot < b.slot)) ? a : b;
  }

  static constexpr int kPrefetchLevels = 8;
  std::size_t leaves_ = 1;
  std::vector<Node, HugeAlloc<Node>> node_{Node{std::numeric_limits<double>::infinity(), 0},
                          Node{std::numeric_limits<double>::infinity(), 0}};
};

}  // namespace granular::detail
