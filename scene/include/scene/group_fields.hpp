#pragma once
// The fields of each averaging group of a granular run on its own (the
// groups' spread gives the shock position's interval, docs/shockfit.md
// "Interval coverage"), in one file: each group's fields under the prefix
// "group_<k>/", the body mask once. Only the fields a shock locator reads
// are kept.
#include <string>
#include <vector>

#include "scene/lattice.hpp"

namespace scene {

// The fields a group keeps, where present: the densities, the velocity
// normal to the free stream and the sample counts.
inline const char* const kGroupFields[] = {"volume_fraction", "rho", "number_density", "v",
                                           "samples"};

// One lattice holding every group (all of one geometry; none in, an empty
// lattice out).
Lattice pack_groups(const std::vector<Lattice>& groups);
// The groups back, each with the body mask. InputError naming `what` when
// the lattice holds fewer than two or the groups hold different fields.
std::vector<Lattice> unpack_groups(const Lattice& packed, const std::string& what);

}  // namespace scene
