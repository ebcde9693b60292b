#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "pipeline/calibration.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/yaml_text.hpp"

namespace pipeline {

namespace {
// Distances in the table: one Mach number counts as much as 5 deg of wedge angle.
constexpr double kAngleScaleDeg = 5.0;
constexpr double kExactMatch = 1e-9;
}  // namespace

CalibrationTable read_calibration(const std::string& path) {
  CalibrationTable t;
  YAML::Node root;
  try {
    // A malformed table must be an input error, never a parser hang.
    if (std::filesystem::is_regular_file(path)) scene::check_yaml_text(scene::read_file(path), path);
    root = YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw scene::InputError(path + ": calibration table not found");
  } catch (const YAML::Exception& e) {
    throw scene::InputError(path + ":" + std::to_string(e.mark.line + 1) + ": malformed calibration table: " + e.msg);
  }
  try {
    if (root["gamma"]) t.gamma = root["gamma"].as<double>();
    for (const auto& n : root["entries"]) {
      CalibrationEntry e;
      e.mach = n["mach"].as<double>();
      e.angle_deg = n["angle_deg"].as<double>();
      e.restitution = n["restitution"].as<double>();
      e.restitution_ci = n["restitution_ci"] ? n["restitution_ci"].as<double>() : 0.0;
      e.gas_angle_deg = n["gas_angle_deg"] ? n["gas_angle_deg"].as<double>() : NAN;
      e.granular_angle_deg = n["granular_angle_deg"] ? n["granular_angle_deg"].as<double>() : NAN;
      e.granular_angle_ci_deg = n["granular_angle_ci_deg"] ? n["granular_angle_ci_deg"].as<double>() : NAN;
      if (!(e.restitution > 0 && e.restitution <= 1))
        throw scene::InputError(path + ": restitution outside (0, 1] in an entry");
      t.entries.push_back(e);
    }
  } catch (const YAML::Exception& e) {
    throw scene::InputError(path + ":" + std::to_string(e.mark.line + 1) + ": calibration table: " + e.msg);
  }
  return t;
}

void write_calibration(const CalibrationTable& t, const std::string& path) {
  YAML::Emitter e;
  e.SetDoublePrecision(6);  // e to 1e-6 is far below its uncertainty
  e << YAML::BeginMap << YAML::Key << "gamma" << YAML::Value << t.gamma;
  e << YAML::Key << "entries" << YAML::Value << YAML::BeginSeq;
  for (const auto& c : t.entries) {
    e << YAML::Flow << YAML::BeginMap << YAML::Key << "mach" << YAML::Value << c.mach << YAML::Key
      << "angle_deg" << YAML::Value << c.angle_deg << YAML::Key << "restitution" << YAML::Value
      << c.restitution << YAML::Key << "restitution_ci" << YAML::Value << c.restitution_ci
      << YAML::Key << "gas_angle_deg" << YAML::Value << c.gas_angle_deg << YAML::Key
      << "granular_angle_deg" << YAML::Value << c.granular_angle_deg << YAML::Key
      << "granular_angle_ci_deg" << YAML::Value << c.granular_angle_ci_deg << YAML::EndMap;
  }
  e << YAML::EndSeq << YAML::EndMap;
  scene::write_file_atomic(path, std::string("# Written by `pipeline calibrate`: restitution e at which the granular\n"
                                             "# shock angle equals the ideal-gas theta-beta-Mach angle.\n") +
                                     e.c_str() + "\n");
}

std::optional<double> interpolate_restitution(const CalibrationTable& t, double mach, double angle_deg) {
  if (t.entries.empty()) return std::nullopt;
  double wsum = 0, esum = 0;
  for (const auto& c : t.entries) {
    const double d = std::isnan(angle_deg) ? std::abs(c.mach - mach)
                                           : std::hypot(c.mach - mach, (c.angle_deg - angle_deg) / kAngleScaleDeg);
    if (d < kExactMatch) return c.restitution;
    const double w = 1.0 / (d * d);
    wsum += w;
    esum += w * c.restitution;
  }
  return esum / wsum;
}

}  // namespace pipeline
