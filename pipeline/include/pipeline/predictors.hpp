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
