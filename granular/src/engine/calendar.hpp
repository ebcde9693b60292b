#pragma once
// Event calendar: each disk slot holds only its earliest event time. Slots
// are grouped in blocks of kBlock consecutive keys; each block keeps its
// minimum, and a complete binary (tournament) tree ranks the blocks. An
// update that neither lowers its block's minimum nor changes the block's
// winner touches one key and nothing else; otherwise the block is rescanned
// (kBlock contiguous doubles) and the small block tree updated, stopping at
// the first unchanged node. The block tree of a million-disk system is
// 500 kB and stays in cache, unlike a tree over every slot. The global
// minimum is the lexicographic (time, slot) minimum, so equal-time events
// are ordered by slot: deterministic.
#include <cstdint>
#include <limits>
#include <vector>

#include "huge_alloc.hpp"

namespace granular::detail {

class Calendar {
 public:
  static constexpr std::size_t kBlock = 32;

  void resize(std::size_t slots) {
    const std::size_t nb = slots < 1 ? 1 : (slots + kBlock - 1) / kBlock;
    blocks_ = nb;
    key_.assign(nb * kBlock, kInf);
    node_.assign(2 * nb, Node{kInf, 0});
    for (std::size_t b = 0; b < nb; ++b) node_[nb + b].slot = static_cast<std::uint32_t>(b * kBlock);
    rebuild_tree();
  }
  std::size_t capacity() const { return key_.size(); }
  // Grows to hold `slots`, keeping every key (doubling: amortised O(1)).
  void grow(std::size_t slots) {
    if (slots <= key_.size()) return;
    std::vector<double, HugeAlloc<double>> keep = key_;
    resize(slots < 2 * keep.size() ? 2 * keep.size() : slots);
    for (std::size_t i = 0; i < keep.size(); ++i) key_[i] = keep[i];
    rebuild();
  }
  void rebuild() {
    for (std::size_t b = 0; b < blocks_; ++b) node_[blocks_ + b] = scan(b);
    rebuild_tree();
  }
  void set(std::size_t slot, double t) {
    key_[slot] = t;
    const std::size_t b = slot / kBlock;
    Node& leaf = node_[blocks_ + b];
    const auto s = static_cast<std::uint32_t>(slot);
    if (t < leaf.key || (t == leaf.key && s < leaf.slot)) {
      leaf = Node{t, s};
    } else if (leaf.slot == s) {
      leaf = scan(b);  // the block's winner got later: find the new one
    } else {
      return;  // neither the block minimum nor its winner: nothing ranks differently
    }
    for (std::size_t k = (blocks_ + b) >> 1; k >= 1; k >>= 1) {
      const Node w = best(node_[2 * k], node_[2 * k + 1]);
      if (w.key == node_[k].key && w.slot == node_[k].slot) break;  // ancestors unchanged
      node_[k] = w;
    }
  }
  // Sets without re-ranking (bulk load; call rebuild() after).
  void set_quiet(std::size_t slot, double t) { key_[slot] = t; }
  std::uint32_t top() const { return node_[1].slot; }
  double top_time() const { return node_[1].key; }
  double key(std::size_t slot) const { return key_[slot]; }
  void prefetch(std::size_t slot) const { __builtin_prefetch(&key_[slot]); }
  double bytes() const {
    return static_cast<double>(key_.size() * sizeof(double) + node_.size() * sizeof(Node));
  }

 private:
  struct Node {
    double key;
    std::uint32_t slot;
  };
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  static Node best(const Node& a, const Node& b) {
    return (a.key < b.key || (a.key == b.key && a.slot < b.slot)) ? a : b;
  }
  Node scan(std::size_t b) const {
    const std::size_t first = b * kBlock;
    std::size_t arg = first;
    double m = key_[first];
    for (std::size_t i = first + 1; i < first + kBlock; ++i)
      if (key_[i] < m) { m = key_[i]; arg = i; }  // strict: lowest slot wins ties
    return Node{m, static_cast<std::uint32_t>(arg)};
  }
  void rebuild_tree() {
    for (std::size_t k = blocks_ - 1; k >= 1 && k < blocks_; --k) node_[k] = best(node_[2 * k], node_[2 * k + 1]);
  }

  std::size_t blocks_ = 1;
  std::vector<double, HugeAlloc<double>> key_ = std::vector<double, HugeAlloc<double>>(kBlock, kInf);
  std::vector<Node, HugeAlloc<Node>> node_{Node{kInf, 0}, Node{kInf, 0}};
};

}  // namespace granular::detail
