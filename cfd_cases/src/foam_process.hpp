#pragma once
// cfd's OpenFOAM launcher is the shared one (scene/foam.hpp, which meshgen
// uses too); these names keep cfd's code as it reads.
#include "scene/foam.hpp"
#include "scene/process.hpp"

namespace cfd {

using scene::foam_bashrc;
using scene::FoamProcess;
using scene::log_tail;
using scene::run_foam;

}  // namespace cfd
