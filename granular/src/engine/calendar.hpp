#pragma once
// Event calendar: a bounded priority queue with O(1) amortised cost per
// event (docs/granular_engine.md, "Event calendar").
//
// Time is cut into buckets of width w; a ring of buckets covers the near
// future, each an unsorted list of fixed-size chunks, so a push is one
// write at the tail of a short list. A ring entry holds only the slot and
// its version (8 bytes): when its bucket is reached, the live entries get
// their time back from the owner (the slot's scheduled time, which cannot
// have changed while the version did not), and the stale ones are dropped
// there, in one pass whose lookups overlap, instead of one by one as they
// come up. The bucket being processed (the "batch") is then sorted once, by
// a distribution sort that costs O(1) per entry, and read in order; the
// rare push into the batch's own time span goes to a small heap merged with
// it, and pushes beyond the ring to a "far" heap drained into the ring as
// it turns (both keep the time with the entry). Superseded
// entries are not searched for: each carries its slot's version, and an
// entry whose version is no longer the slot's is dropped when it comes up
// (lazy invalidation).
//
// Because the batch is sorted, the next events are known in advance: the
// engine prefetches the memory they will touch (each_ahead()), which keeps
// the cost per event nearly flat in N once the system outgrows the caches.
//
// Order: lexicographic (time, slot), exactly, whatever the bucket width, so
// equal-time events are ordered by slot and runs are deterministic and
// independent of how the calendar was tuned or rebuilt.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "huge_alloc.hpp"

namespace granular::detail {

class Calendar {
 public:
  struct Entry {
    double t;
    std::uint32_t slot;
    std::uint32_t ver;
  };

 private:
  // Entries per chunk of bucket storage (256 B): small, so that the
  // partly filled tail chunks of a small system's ring cost little memory.
  static constexpr std::uint32_t kChunk = 32;
  struct Bucket {  // a list of chunks; the tail chunk is filled first
    std::uint32_t head = 0, tail = 0, count = 0;
  };
  struct RingEntry {  // the time is the slot's, looked up when the bucket is taken
    std::uint32_t slot;
    std::uint32_t ver;
  };
  struct Chunk {
    RingEntry e[kChunk];
  };

 public:
  // Entries per bucket aimed at in large systems: sorting costs O(1) per
  // entry, and few buckets keep the ring's tails in cache.
  static constexpr double kTargetBatch = 4096.0;
  // Smallest batch aimed at; systems under 16 x this use fewer, smaller
  // buckets (about N / 16 entries each).
  static constexpr double kMinBatch = 32.0;
  // The ring spans this many pops per live slot ahead: predictions further
  // out than that go to the far heap.
  static constexpr double kHorizonPerSlot = 16.0;
  // Mean batch this many times off target (over 64 batches) asks for a
  // re-tune of w.
  static constexpr double kRetuneFactor = 4.0;
  // Batches smaller than this are sorted by comparison.
  static constexpr std::size_t kSmallBatch = 64;
  // Bucket counts beyond this re-base the calendar instead (exactly
  // representable in a double and far from the int64 limit).
  static constexpr double kMaxBucket = 4.0e18;
  // Far-heap size always tolerated before asking for a rebuild.
  static constexpr std::size_t kFarMin = 4096;
  // Look-ahead cursors available to each_ahead().
  static constexpr std::size_t kStages = 4;

  // Empties the calendar and sizes it for `live` scheduled slots that pop
  // about `rate` entries per unit time, starting at time `now`.
  void reset(double now, std::size_t live, double rate) {
    live_ = live;
    const double n = static_cast<double>(std::max<std::size_t>(live, 1));
    const double batch = std::clamp(n / 16.0, kMinBatch, kTargetBatch);
    target_ = batch;
    const double r = rate > 0.0 && std::isfinite(rate) ? rate : n;
    w_ = batch / r;
    inv_w_ = 1.0 / w_;
    std::size_t nb = 16;
    while (static_cast<double>(nb) * batch < kHorizonPerSlot * n && nb < (std::size_t{1} << 24)) nb <<= 1;
    nb_ = nb;
    ring_.assign(nb_, Bucket{});
    chunks_.clear();
    chunk_next_.clear();
    free_chunks_.clear();
    origin_ = now;
    reset_time_ = now;
    cur_ = 0;
    in_ring_ = 0;
    batch_.clear();
    pos_ = 0;
    cursor_.fill(0);
    heap_.clear();
    far_.clear();
    popped_ = 0;
    batches_ = 0;
    sum_batch_ = 0.0;
    retune_ = false;
  }

  void push(const Entry& e) {
    const double x = (e.t - origin_) * inv_w_;
    if (x < static_cast<double>(cur_ + 1)) {
      heap_.push_back(e);
      std::push_heap(heap_.begin(), heap_.end(), Later{});
    } else if (x < static_cast<double>(cur_ + static_cast<std::int64_t>(nb_))) {
      append(ring_[static_cast<std::size_t>(static_cast<std::int64_t>(x)) & (nb_ - 1)], {e.slot, e.ver});
      ++in_ring_;
    } else {
      far_.push_back(e);
      std::push_heap(far_.begin(), far_.end(), Later{});
      // Superseded far entries wait for their (far) time to be dropped; a
      // disk that keeps predicting far-off events would pile them up.
      if (far_.size() > std::max(kFarMin, live_)) retune_ = true;
    }
  }

  // The earliest entry for which valid(entry) holds, dropping the stale
  // ones on the way; nullptr when the calendar is empty. time_of(slot) is
  // the time the slot is scheduled for (read for entries whose version is
  // still the slot's).
  template <class Valid, class TimeOf>
  const Entry* top(Valid&& valid, TimeOf&& time_of) {
    while (true) {
      const Entry* e = peek();
      if (!e) {
        if (!advance(valid, time_of)) return nullptr;
        continue;
      }
      if (valid(*e)) return e;
      pop();
    }
  }

  // Removes the entry top() returned.
  void pop() {
    ++popped_;
    const bool from_heap =
        !heap_.empty() && (pos_ >= batch_.size() || later(batch_[pos_], heap_.front()));
    if (from_heap) {
      std::pop_heap(heap_.begin(), heap_.end(), Later{});
      heap_.pop_back();
    } else {
      ++pos_;
    }
  }

  // Calls f(entry) once for every entry of the sorted batch up to `dist`
  // places after the current one that this `stage` has not been shown yet
  // (stale entries included): a look-ahead of what is about to be
  // processed, for prefetching in stages.
  template <class F>
  void each_ahead(std::size_t stage, std::size_t dist, F&& f) {
    std::size_t& c = cursor_[stage];
    if (c < pos_) c = pos_;
    const std::size_t end = std::min(pos_ + dist + 1, batch_.size());
    for (; c < end; ++c) f(batch_[c]);
  }

  // True once the bucket width is far off the observed batch size, or the
  // far heap holds more entries than there were live slots: the owner
  // should reset() (with measured_rate()) and push the live entries again
  // at its convenience.
  bool wants_retune() const { return retune_; }
  // Entries popped per unit time since reset() (0 before any).
  double measured_rate(double now) const {
    return popped_ > 0 && now > reset_time_ ? static_cast<double>(popped_) / (now - reset_time_) : 0.0;
  }

  double bytes() const {
    const std::size_t n = batch_.capacity() + scratch_.capacity() + heap_.capacity() + far_.capacity();
    return static_cast<double>(n * sizeof(Entry) + chunks_.capacity() * sizeof(Chunk) +
                               (chunk_next_.capacity() + free_chunks_.capacity() + bin_.capacity() +
                                start_.capacity()) * sizeof(std::uint32_t) +
                               ring_.capacity() * sizeof(Bucket));
  }

 private:
  static bool later(const Entry& a, const Entry& b) {
    return a.t > b.t || (a.t == b.t && a.slot > b.slot);
  }
  struct Later {  // types, not function pointers: the std algorithms inline them
    bool operator()(const Entry& a, const Entry& b) const { return later(a, b); }
  };
  struct Earlier {
    bool operator()(const Entry& a, const Entry& b) const { return later(b, a); }
  };

  const Entry* peek() const {
    const Entry* b = pos_ < batch_.size() ? &batch_[pos_] : nullptr;
    if (heap_.empty()) return b;
    if (!b || later(*b, heap_.front())) return &heap_.front();
    return b;
  }

  // Moves to the next non-empty bucket: returns false when nothing is left.
  template <class Valid, class TimeOf>
  bool advance(Valid& valid, TimeOf& time_of) {
    if (in_ring_ == 0 && far_.empty()) return false;
    if (pos_ > 0) note_batch(static_cast<double>(pos_));
    batch_.clear();
    pos_ = 0;
    cursor_.fill(0);
    if (in_ring_ == 0) {
      // Only far entries left: jump the ring to the earliest, re-basing the
      // bucket count on it where the jump would not fit the counter (times
      // like 1e300, from a nearly stopped disk, overflow (t - origin) / w).
      const double x = (far_.front().t - origin_) * inv_w_;
      if (x < kMaxBucket) {
        cur_ = std::max(cur_ + 1, static_cast<std::int64_t>(x));
      } else {
        origin_ = far_.front().t;
        cur_ = 0;
      }
    } else {
      ++cur_;
    }
    drain_far();
    take(ring_[static_cast<std::size_t>(cur_) & (nb_ - 1)], valid, time_of);
    sort_batch();
    return true;
  }

  // Distribution sort of the batch: entries binned by time within the
  // bucket (about one per bin; the bin index is monotone in time, so bins
  // come in order), then insertion sort, which only moves entries within a
  // bin. O(1) per entry, where a comparison sort costs log2(batch).
  void sort_batch() {
    const std::size_t n = batch_.size();
    if (n < kSmallBatch) {
      std::sort(batch_.begin(), batch_.end(), Earlier{});
      return;
    }
    const double bins = static_cast<double>(n);
    const double base = static_cast<double>(cur_);
    start_.assign(n + 1, 0);
    bin_.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      const double f = ((batch_[k].t - origin_) * inv_w_ - base) * bins;
      const std::uint32_t b = f <= 0.0  ? 0
                              : f >= bins ? static_cast<std::uint32_t>(n - 1)
                                          : static_cast<std::uint32_t>(f);
      bin_[k] = b;
      ++start_[b + 1];
    }
    for (std::size_t b = 0; b < n; ++b) start_[b + 1] += start_[b];
    scratch_.resize(n);
    for (std::size_t k = 0; k < n; ++k) scratch_[start_[bin_[k]]++] = batch_[k];
    for (std::size_t k = 1; k < n; ++k) {
      const Entry e = scratch_[k];
      std::size_t j = k;
      for (; j > 0 && later(scratch_[j - 1], e); --j) scratch_[j] = scratch_[j - 1];
      scratch_[j] = e;
    }
    batch_.swap(scratch_);
  }

  // Appends to a bucket's tail chunk, taking a chunk from the shared pool
  // when it is full (recently freed chunks first: they are in cache).
  void append(Bucket& b, const RingEntry& e) {
    const std::uint32_t at = b.count % kChunk;
    if (at == 0) {
      std::uint32_t c;
      if (!free_chunks_.empty()) {
        c = free_chunks_.back();
        free_chunks_.pop_back();
      } else {
        c = static_cast<std::uint32_t>(chunks_.size());
        chunks_.emplace_back();
        chunk_next_.push_back(0);
      }
      if (b.count == 0) b.head = c;
      else chunk_next_[b.tail] = c;
      b.tail = c;
    }
    chunks_[b.tail].e[at] = e;
    ++b.count;
  }

  // Moves a bucket's live entries into the batch, with their times, and
  // returns its chunks. Branch-free, so that the lookups of successive
  // entries (mostly cache misses in a large system) overlap.
  template <class Valid, class TimeOf>
  void take(Bucket& b, Valid& valid, TimeOf& time_of) {
    in_ring_ -= b.count;
    batch_.resize(b.count);
    std::uint32_t left = b.count;
    std::size_t out = 0;
    for (std::uint32_t c = b.head; left > 0; c = chunk_next_[c]) {
      const std::uint32_t n = std::min<std::uint32_t>(left, kChunk);
      for (std::uint32_t k = 0; k < n; ++k) {
        const RingEntry r = chunks_[c].e[k];
        const Entry e{time_of(r.slot), r.slot, r.ver};
        batch_[out] = e;
        out += valid(e) ? 1 : 0;
      }
      left -= n;
      free_chunks_.push_back(c);
    }
    batch_.resize(out);
    b = Bucket{};
  }

  // Far entries that now fall inside the ring (or the current batch).
  void drain_far() {
    const double end = static_cast<double>(cur_ + static_cast<std::int64_t>(nb_));
    while (!far_.empty() && (far_.front().t - origin_) * inv_w_ < end) {
      const Entry e = far_.front();
      std::pop_heap(far_.begin(), far_.end(), Later{});
      far_.pop_back();
      push(e);
    }
  }

  void note_batch(double size) {
    sum_batch_ += size;
    if (++batches_ < 64) return;
    const double mean = sum_batch_ / static_cast<double>(batches_);
    if (mean > kRetuneFactor * target_ || mean * kRetuneFactor < target_) retune_ = true;
    batches_ = 0;
    sum_batch_ = 0.0;
  }

  double target_ = kMinBatch;
  double w_ = 1.0, inv_w_ = 1.0;
  double origin_ = 0.0;      // time of bucket 0 (moved by a re-basing jump)
  double reset_time_ = 0.0;  // time of reset(), for measured_rate()
  std::size_t nb_ = 16;
  std::size_t live_ = 0;  // live slots at reset()
  std::int64_t cur_ = 0;  // bucket index (from origin_) of the batch
  std::size_t in_ring_ = 0;
  std::vector<Bucket> ring_;
  std::vector<Chunk, HugeAlloc<Chunk>> chunks_;  // pool shared by the buckets
  std::vector<std::uint32_t> chunk_next_, free_chunks_;
  std::vector<Entry> batch_;                     // the current bucket, sorted
  std::size_t pos_ = 0;
  std::array<std::size_t, kStages> cursor_{};
  std::vector<Entry> scratch_;                   // sort_batch() work space
  std::vector<std::uint32_t> bin_, start_;
  std::vector<Entry> heap_;  // entries in the batch's span pushed after it was sorted
  std::vector<Entry> far_;   // beyond the ring
  std::uint64_t popped_ = 0;
  std::uint64_t batches_ = 0;
  double sum_batch_ = 0.0;
  bool retune_ = false;
};

}  // namespace granular::detail
