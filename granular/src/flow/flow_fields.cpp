#include "granular/flow_fields.hpp"

#include <cmath>

#include "scene/units.hpp"

namespace granular {

namespace {

using scene::kDiskArea;
using scene::kNaN;
// Sub-points per side to measure the part of a cell that disk centres can
// reach (a radius away from the body and the mirror plane): cells cut by a
// wall hold disks only there, so densities divide by that area.
constexpr int kCellSubSamples = 6;
// Fewest samples for a velocity/temperature value: the temperature is a
// variance, which needs two.
constexpr double kMinSamples = 2.0;
// Cells whose reachable part is this small give meaningless densities:
// their fields stay NaN (inside_body 0, as their centre is outside).
constexpr double kMinFluidFraction = 0.05;

struct CellValues {
  double nu = kNaN, n = kNaN, u = kNaN, v = kNaN, t = kNaN;
};

CellValues cell_values(const FieldSums& s, std::size_t c, double cell_area) {
  CellValues out;
  const double snaps = s.snapshots();
  if (!(snaps > 0) || !(cell_area > 0)) return out;
  const double cnt = s.at(FieldSums::count, c);
  out.n = cnt / (snaps * cell_area);
  out.nu = out.n * kDiskArea;
  if (cnt >= kMinSamples) {
    out.u = s.at(FieldSums::sum_u, c) / cnt;
    out.v = s.at(FieldSums::sum_v, c) / cnt;
    const double var = (s.at(FieldSums::sum_uu, c) + s.at(FieldSums::sum_vv, c)) / cnt -
                       out.u * out.u - out.v * out.v;
    // Two velocity components: T = m <|c|^2> / 2, with Bessel's correction.
    out.t = std::max(0.0, 0.5 * var * cnt / (cnt - 1.0));
  }
  return out;
}

// Standard error of the mean over blocks of one cell quantity (NaN if fewer
// than two blocks have it).
double standard_error(const std::vector<double>& x) {
  double sum = 0, sum2 = 0;
  int k = 0;
  for (const double a : x)
    if (std::isfinite(a)) {
      sum += a;
      sum2 += a * a;
      ++k;
    }
  if (k < 2) return kNaN;
  const double mean = sum / k;
  const double var = std::max(0.0, (sum2 - k * mean * mean) / (k - 1));
  return std::sqrt(var / k);
}

}  // namespace

scene::Lattice flow_lattice(const FlowSetup& f, int nx, int ny) {
  return scene::domain_lattice(f.domain, nx, ny);
}

Binner::Binner(const FlowSetup& f, const scene::Lattice& g)
    : inv_scale_(1.0 / f.scale), x0_(g.x0), y0_(g.y0), inv_dx_(1.0 / g.dx), inv_dy_(1.0 / g.dy),
      nx_(g.nx), ny_(g.ny) {}

scene::Lattice make_fields(const FlowSetup& f, const scene::Lattice& geometry,
                           const std::vector<FieldSums>& blocks) {
  scene::Lattice lat = geometry;
  const std::size_t ncell = static_cast<std::size_t>(lat.nx) * static_cast<std::size_t>(lat.ny);
  auto& nu = lat.add("volume_fraction", kNaN);
  auto& n = lat.add("number_density", kNaN);
  auto& u = lat.add("u", kNaN);
  auto& v = lat.add("v", kNaN);
  auto& t = lat.add("temperature", kNaN);
  auto& p = lat.add("pressure", kNaN);
  auto& mach = lat.add("mach", kNaN);
  auto& samples = lat.add("samples", kNaN);
  auto& inside = lat.add("inside_body", 0.0);
  auto& nu_se = lat.add("volume_fraction_se", kNaN);
  auto& u_se = lat.add("u_se", kNaN);
  auto& v_se = lat.add("v_se", kNaN);

  FieldSums pooled(ncell);
  for (const FieldSums& b : blocks) pooled += b;
  const double cell_area_d2 = lat.dx * lat.dy * f.scale * f.scale;
  std::vector<double> bnu(blocks.size()), bu(blocks.size()), bv(blocks.size());
  const double radius = f.config.radius / f.scale;  // scene units
  const double half_diag = 0.5 * std::hypot(lat.dx, lat.dy);
  auto reachable = [&](scene::Vec2 q) {
    return scene::signed_distance(f.body, q) > radius && (!f.domain.symmetric || q.y > f.domain.ymin + radius);
  };
  for (int j = 0; j < lat.ny; ++j)
    for (int i = 0; i < lat.nx; ++i) {
      const std::size_t c = lat.index(i, j);
      // Disk centres stay a radius away from walls and the mirror plane, so
      // a cell's density is per unit of the area its centres can reach.
      const scene::Vec2 centre{lat.xc(i), lat.yc(j)};
      const double dist = scene::signed_distance(f.body, centre);
      if (dist < 0.0) {
        inside[c] = 1.0;
        continue;
      }
      double fluid_fraction = 1.0;
      if (dist < half_diag + radius || (f.domain.symmetric && centre.y - f.domain.ymin < half_diag + radius)) {
        int fluid = 0;
        for (int b = 0; b < kCellSubSamples; ++b)
          for (int a = 0; a < kCellSubSamples; ++a) {
            const scene::Vec2 q{lat.x0 + (i + (a + 0.5) / kCellSubSamples) * lat.dx,
                                lat.y0 + (j + (b + 0.5) / kCellSubSamples) * lat.dy};
            if (reachable(q)) ++fluid;
          }
        fluid_fraction = static_cast<double>(fluid) / (kCellSubSamples * kCellSubSamples);
      }
      if (fluid_fraction < kMinFluidFraction) continue;  // NaN: a sliver only centres at the wall reach
      const double area = cell_area_d2 * fluid_fraction;
      const CellValues cv = cell_values(pooled, c, area);
      samples[c] = pooled.at(FieldSums::count, c);
      nu[c] = cv.nu;
      n[c] = cv.n;
      u[c] = cv.u;
      v[c] = cv.v;
      t[c] = cv.t;
      if (std::isfinite(cv.t)) {
        p[c] = cv.n * cv.t * henderson_z(cv.nu);
        const double cs = sound_speed(cv.nu, cv.t);
        mach[c] = cs > 0 ? std::hypot(cv.u, cv.v) / cs : kNaN;
      }
      for (std::size_t b = 0; b < blocks.size(); ++b) {
        const CellValues bc = cell_values(blocks[b], c, area);
        bnu[b] = bc.nu;
        bu[b] = bc.u;
        bv[b] = bc.v;
      }
      nu_se[c] = standard_error(bnu);
      u_se[c] = standard_error(bu);
      v_se[c] = standard_error(bv);
    }
  return lat;
}

std::vector<scene::Lattice> make_group_fields(const scene::Lattice& fields,
                                              const std::vector<FieldSums>& groups) {
  std::vector<scene::Lattice> out;
  if (groups.size() < 2) return out;
  // The pooled counts are the fields' own samples (integers, exact in any
  // order of summation): no second pooling of the groups.
  const auto& nu = fields.field("volume_fraction");
  const auto& samples = fields.field("samples");
  const auto& inside = fields.field("inside_body");
  double snapshots = 0.0;
  for (const FieldSums& g : groups) snapshots += g.snapshots();
  const double per_total = snapshots > 0 ? 1.0 / snapshots : 0.0;
  for (const FieldSums& g : groups) {
    scene::Lattice lat(fields.nx, fields.ny, fields.x0, fields.y0, fields.dx, fields.dy);
    lat.fields["inside_body"] = inside;
    auto& gnu = lat.add("volume_fraction", kNaN);
    auto& gv = lat.add("v", kNaN);
    auto& gs = lat.add("samples", kNaN);
    const double per_group = g.snapshots() > 0 ? 1.0 / g.snapshots() : 0.0;
    for (std::size_t c = 0; c < g.cells(); ++c) {
      if (!std::isfinite(nu[c])) continue;
      // The same cell area as the pooled fields': the group's volume
      // fraction is the pooled one scaled by its disks per snapshot.
      const double n_all = samples[c] * per_total;
      const double n = g.at(FieldSums::count, c);
      // The pooled count: a locator's sample gate then picks the cells it
      // picks in the pooled fields, and only the data differ.
      gs[c] = samples[c];
      gnu[c] = n_all > 0 ? nu[c] * n * per_group / n_all : 0.0;
      if (n > 0) gv[c] = g.at(FieldSums::sum_v, c) / n;
    }
    out.push_back(std::move(lat));
  }
  return out;
}

}  // namespace granular
