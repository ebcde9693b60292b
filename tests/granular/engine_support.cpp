#include "engine_support.hpp"

#include <cmath>
#include <numbers>

#include "granular/box_setup.hpp"

namespace granular::test {

EngineConfig open_space(double size) {
  EngineConfig c;
  c.xmin = 0; c.xmax = size; c.ymin = 0; c.ymax = size;
  return c;
}

EngineConfig walled_box(double size, double e_wall) {
  EngineConfig c = open_space(size);
  c.left = c.right = c.bottom = c.top = Face::closed;
  c.species = {Species{0.5, 1.0, e_wall, e_wall}};
  const Vec2 p0{0, 0}, p1{size, 0}, p2{size, size}, p3{0, size};
  c.walls = {{p0, p1, -1.0}, {p1, p2, -1.0}, {p2, p3, -1.0}, {p3, p0, -1.0}};
  return c;
}

std::vector<State> snapshot(const Engine& e) {
  std::vector<State> out;
  e.for_each_particle([&](Vec2 r, Vec2 v) { out.push_back({r, v}); });
  return out;
}

double kinetic_energy(const Engine& e) {
  double k = 0;
  e.for_each_particle([&](Vec2, Vec2 v) { k += 0.5 * norm2(v); });
  return k;
}

Vec2 momentum(const Engine& e) {
  Vec2 p{0, 0};
  e.for_each_particle([&](Vec2, Vec2 v) { p += v; });
  return p;
}

Engine melted_box(int n, double nu, double melt, std::uint64_t seed, double restitution, double tc) {
  BoxSetup b;
  b.particles = n;
  b.width = b.height = std::sqrt(n * std::numbers::pi / 4.0 / nu);
  b.packing_fraction = nu;
  b.seed = seed;
  b.restitution = restitution;
  b.restitution_wall = restitution;
  b.tc = tc;
  Engine e = make_box_engine(b);
  e.run_collisions(static_cast<std::uint64_t>(melt * n));
  return e;
}

}  // namespace granular::test
