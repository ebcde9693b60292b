#pragma once
// Body geometry: every body becomes an oriented closed outline, counter-
// clockwise, so the outward normal of an edge with unit tangent t is
// (t.y, -t.x). It is built from exact pieces (segments, circular arcs) and
// their polyline; CGAL checks simplicity and orientation of the polyline.
#include <vector>

#include "scene/scene.hpp"
#include "scene/vec2.hpp"

namespace scene {

// One exact piece of the outline, traversed from `a` to `b`.
// line: straight segment. arc: circular arc about `center`, counter-clockwise
// when ccw is true.
struct BodyPiece {
  enum class Kind { line, arc } kind = Kind::line;
  Vec2 a, b;
  Vec2 center;
  double radius = 0.0;
  bool ccw = true;
};

struct BodyGeometry {
  std::vector<BodyPiece> pieces;   // exact outline, closed, counter-clockwise
  std::vector<Vec2> polyline;      // vertices of the closed CCW polygon (no repeat of the first)
  double length = 1.0;             // body length for nondimensionalising standoff
  bool symmetric = false;          // mirror-symmetric about y = 0
  Vec2 nose;                       // most upstream point on the symmetry line (stagnation/apex)
};

// Builds and validates the geometry (InputError on an open, self-intersecting
// or degenerate polygon, naming the offending edge).
BodyGeometry make_body(const BodySpec& spec);

// Validates a raw polygon and returns it counter-clockwise.
std::vector<Vec2> validated_polygon(const std::vector<Vec2>& pts);

bool point_in_body(const BodyGeometry& g, Vec2 p);
// Negative inside the body, positive outside.
double signed_distance(const BodyGeometry& g, Vec2 p);

// x of the body's widest section: the most upstream outline vertex of
// largest |y|. A blunt body's forebody lies ahead of it, its wake behind.
double widest_section_x(const BodyGeometry& g);

// Outward unit normal of polyline edge i (from vertex i to i+1).
Vec2 edge_normal(const BodyGeometry& g, std::size_t i);

struct Station {
  Vec2 point;      // on the surface
  Vec2 normal;     // outward unit normal
  double s = 0.0;  // arc length from the nose along the upper surface
};

// `count` stations equally spaced in arc length along the upstream-facing
// surface (for symmetric bodies: the upper half, from the nose), each with
// its outward normal. Stations at sharp corners take the mean normal.
std::vector<Station> surface_stations(const BodyGeometry& g, int count);

// Part of the outline inside the domain as one polyline, traversed clockwise
// (body on the right, outward normal on the left of travel): for symmetric
// domains from the nose over the upper surface to where it meets a boundary;
// otherwise from the lower cut through the nose to the upper cut. A body
// wholly inside the domain gives the closed loop (first point repeated).
std::vector<Vec2> clipped_outline(const BodyGeometry& g, const Domain& d);

}  // namespace scene
