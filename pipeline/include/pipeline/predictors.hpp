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

}  // namespace pipeline
