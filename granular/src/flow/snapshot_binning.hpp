#pragma once
// One snapshot of the stream binned into an averaging group's sums.
//
// Binning waits on one cache miss per disk: the lattice's sums (200 x 200
// cells x 5 sums, 1.6 MB a group) outgrow the cache, and binning every
// snapshot was an eighth of a stream run's CPU. Each disk's sums are
// prefetched kBinLookahead disks before they are added; the additions keep
// the disks' order, so the sums are bit for bit those of a plain loop.
#include <array>
#include <cstddef>

#include "../engine/prefetch.hpp"
#include "granular/flow_fields.hpp"
#include "scene/vec2.hpp"

namespace granular {

inline constexpr std::size_t kBinLookahead = 16;

// `for_each_disk(f)` calls f(r_engine, v) once per disk. The disks inside
// the lattice go into `sums` as one snapshot; returns how many disks there
// were, inside the lattice or not.
template <class ForEachDisk>
std::size_t bin_snapshot(const Binner& binner, FieldSums& sums, ForEachDisk&& for_each_disk) {
  struct Pending {
    std::size_t cell;
    scene::Vec2 v;
  };
  std::array<Pending, kBinLookahead> ring{};
  std::size_t queued = 0, disks = 0;
  for_each_disk([&](scene::Vec2 r, scene::Vec2 v) {
    ++disks;
    const std::size_t c = binner.cell_of(r);
    if (c == Binner::npos) return;
    const double* cell_sums = sums.cell_data(c);
    detail::prefetch(cell_sums);
    detail::prefetch(cell_sums + FieldSums::kArrays - 1);
    Pending& slot = ring[queued % kBinLookahead];
    if (queued >= kBinLookahead) sums.add(slot.cell, slot.v);
    slot = {c, v};
    ++queued;
  });
  for (std::size_t k = queued > kBinLookahead ? queued - kBinLookahead : 0; k < queued; ++k)
    sums.add(ring[k % kBinLookahead].cell, ring[k % kBinLookahead].v);
  sums.end_snapshot();
  return disks;
}

}  // namespace granular
