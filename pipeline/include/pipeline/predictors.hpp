#pragma once
// The predictors of the registry (predictor.hpp): one class each.
#include "pipeline/predictor.hpp"

namespace pipeline {

class GranularPredictor final : public Predictor {
 public:
  std::string name() const override { return "granular"; }
  Prediction predict(const PredictContext& cx) const override;
};

class CorrelationPredictor final : public Predictor {
 public:
  std::string name() const override { return "correlation"; }
  Prediction predict(const PredictContext& cx) const override;
};

// The correlation's shock, without a run: the exact theta-beta-Mach ray
// (no band of its own) on attached wedges, else Billig's cylinder shock with
// a band of relative_half_width x its standoff. The dry run's estimate
// meshes round it too.
struct CorrelationShock {
  scene::ShockKind kind = scene::ShockKind::none;
  ShockCurve curve;
  double angle_deg = scene::kNaN;            // attached
  double relative_half_width = scene::kNaN;  // detached
  bool exact_shape = false;                  // a circular nose: Billig's shape is exact
};
CorrelationShock correlation_shock(const scene::Scene& s);

class CoarseCfdPredictor final : public Predictor {
 public:
  std::string name() const override { return "coarse_cfd"; }
  Prediction predict(const PredictContext& cx) const override;
};

// The coarse_cfd run, then one size field per level from the Hessian of its
// density (hessian_size.hpp); the coarse run's CPU and the fields' are its cost.
class AdaptPredictor final : public Predictor {
 public:
  std::string name() const override { return "adapt"; }
  Prediction predict(const PredictContext& cx) const override;
};

}  // namespace pipeline
