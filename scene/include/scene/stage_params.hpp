#pragma once
// Each stage's section of the scene file. One header per stage so that each
// stage's owner edits only its own file; defaults are documented in
// docs/scene.md and echoed by `to_yaml`.
#include "scene/params_cfd.hpp"
#include "scene/params_granular.hpp"
#include "scene/params_mesh.hpp"
#include "scene/params_pipeline.hpp"
#include "scene/params_shockfit.hpp"
