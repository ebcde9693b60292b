#pragma once
// The 2D flow region meshgen grids: the scene's CFD domain (scene_domain)
// with the body cut out, as closed loops of exact boundary curves (segments
// and circular arcs), each tagged with the OpenFOAM patch it belongs to.
#include <string>
#include <vector>

#include "scene/body.hpp"
#include "scene/scene.hpp"
#include "scene/vec2.hpp"

namespace meshgen {

enum class Patch { inlet, outlet, top, bottom, body };
std::string patch_name(Patch p);

// One boundary curve traversed from a to b: a segment, or a circular arc
// about `center` (ccw tells the sense), at most a quarter turn long so gmsh
// never has to guess which way round an arc goes.
struct BoundaryCurve {
  bool is_arc = false;
  scene::Vec2 a, b, center;
  bool ccw = true;
  Patch patch = Patch::body;
};

struct FluidRegion {
  scene::Domain domain;            // as meshed (outlet possibly moved, see below)
  scene::Domain scene_domain;      // as the scene defines it
  bool outlet_moved = false;       // true when the outflow plane was moved upstream
  std::vector<std::vector<BoundaryCurve>> loops;  // [0] outer, counter-clockwise; then holes
  scene::BodyGeometry body;
  double length_scale = 1.0;       // body length: mesh parameters are in these units
  // Strictly inside the rectangle and outside the body.
  bool contains(scene::Vec2 p) const;
  double area() const;  // quadrature-free: polygon area of a fine polyline
};

// Builds the region. Where the body meets the outflow plane at a grazing
// angle (the disc's rear point, tangent to x = xmax), the cell in that cusp
// could not be valid, so the outflow plane moves upstream to the body's
// thickest station (its highest point), where it meets the body square on.
// InputError when the scene has no body.
FluidRegion make_fluid_region(const scene::Scene& s);

// Points along a curve (arcs subdivided so no chord sags more than `sag`).
std::vector<scene::Vec2> sample_curve(const BoundaryCurve& c, double sag);

// Winding-number point-in-polygon test on a closed polyline (no repeat).
bool inside_polygon(const std::vector<scene::Vec2>& poly, scene::Vec2 p);

}  // namespace meshgen
