#pragma once
// The scene file (see ../shared/contract.md and docs/scene.md): plain value
// types that every stage reads. Parsing is strict: unknown keys, wrong types
// and out-of-range values are InputError naming the file, key and line.
#include <optional>
#include <string>
#include <vector>

#include "scene/stage_params.hpp"
#include "scene/vec2.hpp"

namespace scene {

inline constexpr int kSchemaVersion = 1;

enum class BodyKind { wedge, disc, apollo, polygon };

struct BodySpec {
  BodyKind kind = BodyKind::wedge;
  double angle_deg = 10.0;        // wedge: flow deflection (half-angle)
  double length = 1.0;            // wedge: inclined face length
  double radius = 0.25;           // disc
  double diameter = 1.0;          // apollo: maximum diameter D
  std::vector<Vec2> points;       // polygon, as written
  // Largest distance between a curved part and its polyline (sagitta), in
  // body lengths. Curves are exact in meshgen; this only affects polylines.
  double curve_tolerance = 1e-3;
};

struct Freestream {
  double mach = 3.0;
  double gamma = 1.4;
};

// Axis-aligned rectangle in scene coordinates. symmetric: only y >= 0 is
// modelled and y = ymin = 0 is a symmetry plane.
struct Domain {
  double xmin = 0, xmax = 0, ymin = 0, ymax = 0;
  bool symmetric = false;
  double width() const { return xmax - xmin; }
  double height() const { return ymax - ymin; }
};

// Closed validation box of the simulator (lengths in particle diameters).
struct Box {
  double width = 100.0;
  double height = 100.0;
  bool periodic = true;
};

struct Scene {
  std::string name;
  std::string source_file;          // path it was read from ("" for strings)
  std::optional<BodySpec> body;     // exactly one of body / box
  std::optional<Box> box;
  Freestream freestream;
  std::optional<Domain> domain_override;  // `domain:` section, if given
  GranularParams granular;
  ShockfitParams shockfit;
  MeshParams mesh;
  CfdParams cfd;
  PipelineParams pipeline;
};

// Parse a scene file. Throws InputError with "FILE:LINE: key 'k': ..." text.
Scene load_scene(const std::string& path);
// Parse from a string (tests); `origin` names it in messages.
Scene parse_scene(const std::string& yaml_text, const std::string& origin = "<string>");

// Body length used to nondimensionalise standoff: wedge length, disc radius,
// capsule diameter, polygon x-extent.
double body_length(const BodySpec& body);

// The free-stream domain for the scene's body (or its `domain:` override).
Domain scene_domain(const Scene& s);

// InputError "FILE: key 'freestream.mach': STAGE needs a supersonic free
// stream ..." when Mach <= 1: no shock to predict, cluster at or compute.
void require_supersonic(const Scene& s, const std::string& stage);

// Resolved scene echoed as YAML (every default filled in), for logs and caches.
std::string to_yaml(const Scene& s);
// One top-level section of the resolved scene as YAML text ("" if absent):
// what a stage's cache key hashes, so a change elsewhere does not rerun it.
std::string section_yaml(const Scene& s, const std::string& section);

}  // namespace scene
