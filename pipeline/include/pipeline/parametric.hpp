#pragma once
// `pipeline parametric`: granular parameter studies that show where the
// granular analog tracks the gas (docs/parametric.md). Wedges: shock angle
// against deflection; discs: standoff against size in particle diameters;
// Mach sensitivity and the restitution at which the granular shock angle
// equals the gas's. Every point is one run_prediction directory (cached).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace pipeline {

// One granular run: a body in a granular stream. A point may belong to
// several panels; identical points run once.
struct ParametricPoint {
  std::string body = "wedge";  // wedge or disc
  double mach = 3;             // gas Mach number (freestream.mach)
  double granular_mach = 3;    // granular Mach: the inflow temperature at fixed speed
  double theta_deg = 10;       // wedge half-angle (deflection)
  double radius_d = 60;        // disc radius in particle diameters
  double restitution = 1;
  double packing = 0.1;  // inflow packing fraction
  // Smaller and shorter than granular's defaults (9200 disks, 4 flow-through
  // times) so that the full study fits about ten CPU minutes.
  int particles = 3000;  // wedge scale (disks in the domain)
  double averaging = 2;  // flow-through times averaged
};

struct ParametricPanel {
  std::string id;  // file stem of its figure
  std::string title;
  std::string kind;  // theta_beta, standoff, mach_beta
  std::vector<ParametricPoint> points;
};

enum class ParametricGrid { quick, full };
std::vector<ParametricPanel> parametric_panels(ParametricGrid grid);

// Directory name of a point: every parameter, so a changed grid reuses what
// it shares with the old one.
std::string point_key(const ParametricPoint& p);
scene::Scene point_scene(const ParametricPoint& p);
// The wedge case studies (M3/10, M4/15, M5/20): never calibration training data.
bool is_case_study(const ParametricPoint& p);

struct ParametricOptions {
  std::string out_dir;
  bool quick = false;
  double budget_cpu_seconds = 1200;
  int jobs = 1;
  std::string docs_page;    // "" = <source>/docs/parametric.md; "-" = write none
  std::string figures_dir;  // "" = <source>/docs/figures/parametric (with docs_page "-": out_dir)
  std::vector<ParametricPanel> panels;  // overrides the grid (tests)
};

// Runs the study and writes parametric.csv, parametric.json,
// parametric_calibration.json, one PNG per panel and the page. Returns the rows.
nlohmann::json run_parametric(const ParametricOptions& o);

// The rows' analysis, from parametric.json alone (no runs).
struct Crossing {
  double mach = 0, theta_deg = 0, restitution = 0, ci = 0;
  bool found = false;
  std::string note;  // why none was found
};
// Restitution at which the granular angle equals the gamma = 1.4 angle, by
// linear interpolation between the bracketing e values with the 95%
// half-widths propagated.
std::vector<Crossing> calibration_crossings(const nlohmann::json& rows);
void write_parametric_outputs(const nlohmann::json& rows,
                              const std::vector<ParametricPanel>& panels,
                              const nlohmann::json& cost, const std::string& out_dir,
                              const std::string& figures_dir, const std::string& docs_page);

}  // namespace pipeline
