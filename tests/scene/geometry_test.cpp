// Body geometry: orientation, normals, signed distance, Apollo dimensions,
// stations and clipping.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/body.hpp"
#include "scene/errors.hpp"
#include "scene/scene.hpp"
#include "scene/units.hpp"

using scene::BodyKind;
using scene::BodySpec;
using scene::Vec2;

namespace {
constexpr double kTight = 1e-12;
using scene::kDeg;

BodySpec wedge(double deg) {
  BodySpec b;
  b.kind = BodyKind::wedge;
  b.angle_deg = deg;
  return b;
}

double signed_area(const std::vector<Vec2>& p) {
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i) a += scene::cross(p[i], p[(i + 1) % p.size()]);
  return 0.5 * a;
}
}  // namespace

TEST(Geometry, WedgeIsCounterClockwiseWithOutwardNormals) {
  const auto g = scene::make_body(wedge(10));
  ASSERT_EQ(g.polyline.size(), 3u);
  EXPECT_GT(signed_area(g.polyline), 0.0);
  EXPECT_TRUE(g.symmetric);
  EXPECT_EQ(g.nose, (Vec2{0, 0}));
  // Every edge normal points away from the centroid.
  Vec2 c{};
  for (const Vec2 p : g.polyline) c += p / 3.0;
  for (std::size_t i = 0; i < 3; ++i) {
    const Vec2 mid = 0.5 * (g.polyline[i] + g.polyline[(i + 1) % 3]);
    EXPECT_GT(scene::dot(scene::edge_normal(g, i), mid - c), 0.0);
  }
}

TEST(Geometry, ClockwisePolygonIsReoriented) {
  BodySpec b;
  b.kind = BodyKind::polygon;
  b.points = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};  // clockwise
  const auto g = scene::make_body(b);
  EXPECT_NEAR(signed_area(g.polyline), 1.0, kTight);
}

TEST(Geometry, SignedDistanceAndInside) {
  BodySpec b;
  b.kind = BodyKind::disc;
  b.radius = 1.0;
  b.curve_tolerance = 1e-4;
  const auto g = scene::make_body(b);
  EXPECT_TRUE(scene::point_in_body(g, {0.2, 0.3}));
  EXPECT_FALSE(scene::point_in_body(g, {1.5, 0}));
  // Polyline within curve_tolerance of the exact circle.
  EXPECT_NEAR(scene::signed_distance(g, {3, 0}), 2.0, 1e-4);
  EXPECT_NEAR(scene::signed_distance(g, {0, 0}), -1.0, 1e-4);
  for (const Vec2 p : g.polyline) EXPECT_NEAR(scene::norm(p), 1.0, kTight);
}

TEST(Geometry, CurveToleranceBoundsTheSagitta) {
  BodySpec b;
  b.kind = BodyKind::disc;
  b.radius = 1.0;
  b.curve_tolerance = 1e-3;
  const auto g = scene::make_body(b);
  for (std::size_t i = 0; i < g.polyline.size(); ++i) {
    const Vec2 mid = 0.5 * (g.polyline[i] + g.polyline[(i + 1) % g.polyline.size()]);
    EXPECT_LE(1.0 - scene::norm(mid), 1e-3 + kTight);
  }
}

TEST(Geometry, ApolloDimensions) {
  BodySpec b;
  b.kind = BodyKind::apollo;
  b.diameter = 2.0;
  const auto g = scene::make_body(b);
  double xmin = 1e9, xmax = -1e9, ymax = -1e9;
  for (const Vec2 p : g.polyline) {
    xmin = std::min(xmin, p.x);
    xmax = std::max(xmax, p.x);
    ymax = std::max(ymax, p.y);
  }
  EXPECT_NEAR(xmin, 0.0, kTight);              // stagnation point at the origin
  EXPECT_NEAR(ymax, 1.0, 1e-3 * 2.0);          // maximum radius D/2 (shoulder top, polyline)
  EXPECT_NEAR(xmax, 0.826 * 2.0, kTight);      // height 0.826 D
  EXPECT_TRUE(g.symmetric);
  EXPECT_DOUBLE_EQ(g.length, 2.0);
  // Heat shield: points near the nose lie on the sphere of radius 1.2 D about (1.2 D, 0).
  for (const Vec2 p : g.polyline) {
    if (p.x < 0.05 && p.x > 0) {
      EXPECT_NEAR(scene::norm(p - Vec2{2.4, 0}), 2.4, 1e-9);
    }
  }
  // Afterbody cone at 33 deg: the long straight upper edge.
  bool found_cone = false;
  for (std::size_t i = 0; i < g.polyline.size(); ++i) {
    const Vec2 a = g.polyline[i], c = g.polyline[(i + 1) % g.polyline.size()];
    if (scene::norm(c - a) > 0.5 && a.y > 0) {
      EXPECT_NEAR(std::atan2(c.y - a.y, a.x - c.x) / kDeg, 33.0, 1e-9);  // CCW: runs forward and up
      found_cone = true;
    }
  }
  EXPECT_TRUE(found_cone);
}

TEST(Geometry, StationsFollowTheUpperSurfaceFromTheNose) {
  const auto g = scene::make_body(wedge(15));
  const auto st = scene::surface_stations(g, 11);
  ASSERT_EQ(st.size(), 11u);
  EXPECT_EQ(st.front().normal, (Vec2{-1, 0}));  // stagnation line at the apex
  const Vec2 n_face{-std::sin(15 * kDeg), std::cos(15 * kDeg)};
  for (std::size_t k = 1; k < st.size(); ++k) {
    EXPECT_NEAR(st[k].normal.x, n_face.x, kTight);
    EXPECT_NEAR(st[k].normal.y, n_face.y, kTight);
    EXPECT_NEAR(st[k].s, 0.1 * static_cast<double>(k), 1e-12);
  }
  EXPECT_NEAR(st.back().point.x, std::cos(15 * kDeg), kTight);
}

TEST(Geometry, DiscStationsCoverTheFrontQuarter) {
  BodySpec b;
  b.kind = BodyKind::disc;
  b.radius = 1.0;
  const auto st = scene::surface_stations(scene::make_body(b), 5);
  ASSERT_EQ(st.size(), 5u);
  EXPECT_NEAR(st.front().point.x, -1.0, kTight);
  for (const auto& s : st) {
    EXPECT_NEAR(scene::norm(s.normal), 1.0, kTight);
    EXPECT_LT(s.normal.x, 0.0);                                   // faces the flow
    EXPECT_GT(scene::dot(s.normal, s.point), 0.99);                // radial
  }
}

TEST(Geometry, ClippedOutlineOfSymmetricWedge) {
  const auto s = scene::parse_scene("body: {kind: wedge, angle_deg: 10}\nfreestream: {mach: 3}\n");
  const auto g = scene::make_body(*s.body);
  const auto d = scene::scene_domain(s);
  const auto c = scene::clipped_outline(g, d);
  ASSERT_EQ(c.size(), 2u);  // apex to the outlet
  EXPECT_EQ(c.front(), (Vec2{0, 0}));
  EXPECT_NEAR(c.back().x, d.xmax, kTight);
  EXPECT_GT(c.back().y, 0.0);
}

TEST(Geometry, ClippedOutlineOfAsymmetricBodyWraps) {
  BodySpec b;
  b.kind = BodyKind::polygon;
  b.points = {{0, 0}, {1, -0.2}, {1, 0.5}};
  const auto g = scene::make_body(b);
  EXPECT_FALSE(g.symmetric);
  scene::Domain d{-1, 2, -1, 1, false};
  const auto c = scene::clipped_outline(g, d);
  // Wholly inside: the closed loop, traversed clockwise (body on the right).
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c.front(), c.back());
  EXPECT_LT(signed_area({c.begin(), c.end() - 1}), 0.0);
}

TEST(Geometry, DomainsContainTheBodyAndTheExpectedShock) {
  for (const char* text : {"body: {kind: wedge, angle_deg: 20}\nfreestream: {mach: 5}\n",
                           "body: {kind: disc, radius: 0.5}\nfreestream: {mach: 4}\n",
                           "body: {kind: apollo}\nfreestream: {mach: 5}\n"}) {
    const auto s = scene::parse_scene(text);
    const auto d = scene::scene_domain(s);
    EXPECT_TRUE(d.symmetric);
    EXPECT_EQ(d.ymin, 0.0);
    EXPECT_LT(d.xmin, 0.0);
    EXPECT_GT(d.ymax, 0.0);
  }
  // Wedge M5/20: the exact shock (29.8 deg) leaves through the top before the outlet.
  const auto s = scene::parse_scene("body: {kind: wedge, angle_deg: 20}\nfreestream: {mach: 5}\n");
  const auto d = scene::scene_domain(s);
  EXPECT_GT(d.ymax, d.xmax * std::tan(29.8 * kDeg));
}

TEST(Geometry, SymmetricNoseLiesOnTheAxis) {
  // A notch facing the stream: the most upstream vertices are off the axis.
  BodySpec notch;
  notch.kind = BodyKind::polygon;
  notch.points = {{0, -1}, {1, -1}, {1, 1}, {0, 1}, {0.3, 0}};
  const auto g = scene::make_body(notch);
  EXPECT_TRUE(g.symmetric);
  EXPECT_EQ(g.nose, (Vec2{0.3, 0}));
  const auto c = scene::clipped_outline(g, {-1, 2, 0, 2, true});
  // From the notch bottom up its face, round the front corner, along the top.
  ASSERT_GE(c.size(), 3u);
  EXPECT_EQ(c[1], (Vec2{0, 1}));
  // A flat front has no vertex on the axis: one is inserted.
  BodySpec block;
  block.kind = BodyKind::polygon;
  block.points = {{0, -1}, {1, -1}, {1, 1}, {0, 1}};
  const auto b = scene::make_body(block);
  EXPECT_EQ(b.nose, (Vec2{0, 0}));
  EXPECT_EQ(b.polyline.size(), 5u);
}
