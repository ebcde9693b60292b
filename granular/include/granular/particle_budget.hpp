#pragma once
// How many disks a run may hold: refused up front (InputError, exit 2)
// with the estimate, rather than failing with std::bad_alloc or swapping
// for hours once the engine allocates.
#include <string>

namespace granular {

// Engine memory per disk: the particle (one 64-byte cache line), its
// prediction record, its calendar entries and cell-list share, measured by
// Engine::bytes_per_particle() at ~320 bytes in a small box; rounded up.
inline constexpr double kBytesPerParticle = 384.0;
// Disks per engine: 5e7 disks take ~13 GB, which is more than the machines
// this runs on give one run, and weeks of simulated time at ~1e7 events/s.
inline constexpr double kMaxParticles = 5e7;

// Throws InputError "WHERE...: about N disks ... (~X GB) ..." when
// `particles` (per engine) times `engines` (run at once) exceeds the limits
// or is not a finite count.
void check_particle_budget(double particles, int engines, const std::string& where);

}  // namespace granular
