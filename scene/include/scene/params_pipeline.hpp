#pragma once
#include <string>
#include <vector>

namespace scene {

// `pipeline:` section: the clustered-vs-uniform comparison.
struct PipelineParams {
  // Refinement levels: each family is meshed at h_min x level (and h_max x
  // level), coarse to fine, e.g. h = 4, 2, 1 x h_min.
  std::vector<double> levels{4.0, 2.0, 1.0};
  // Restitution table written by `pipeline calibrate`; used when the scene
  // does not set granular.restitution. "" = the built-in pipeline/calibration.yaml.
  std::string calibration;
  bool cfd = true;  // false: stop after meshing (granular + shockfit + meshgen only)
};

}  // namespace scene
