#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "params_parse.hpp"
#include "scene/body.hpp"
#include "scene/body_traits.hpp"
#include "scene/errors.hpp"
#include "scene/gasdynamics.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"
#include "yaml_structure.hpp"

namespace scene {

namespace {

// contract: box particles and packing_fraction must agree within 0.5%.
constexpr double kPackingAgreement = 0.005;
// Disk area in units of the diameter squared.
// Free-stream Mach ceiling: beyond it the perfect-gas references are
// meaningless and the granular inflow's event rate (which grows with Mach)
// makes a run take forever; Mach 1e308 overflowed into a hang.
constexpr double kMaxMach = 50.0;
// Body sizes and domain coordinates, in scene units: every stage works in
// body lengths, so only the ratio matters; the bounds keep products such as
// width x height far from overflow.
constexpr double kMinBodySize = 1e-6;
constexpr double kMaxBodySize = 1e6;
constexpr double kMaxCoordinate = 1e9;
// Box sides in particle diameters (a 1e7 x 1e7 box already holds ~1e14 disks,
// far beyond any memory; the particle budget refuses it with an estimate).
constexpr double kMaxBoxSide = 1e7;

// A value already checked for its lower bound (> 0) that must also stay
// <= hi: a separate check so that the lower-bound message stays as it was.
double at_most(Section& s, const std::string& key, double v, double hi) {
  if (v > hi) {
    std::ostringstream os;
    os << "expected a number in (0, " << hi << "], got " << v;
    s.fail(key, os.str());
  }
  return v;
}

// The name becomes a folder name (pipeline studies) and a plot title: it
// must not climb out of the output folder or carry control characters.
constexpr std::size_t kMaxNameLength = 200;
void check_name(Section& top, const std::string& name) {
  const bool bad_char = std::any_of(name.begin(), name.end(), [](char c) {
    return c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  });
  if (name.empty() || name == "." || name == ".." || bad_char || name.size() > kMaxNameLength)
    top.fail("name", "expected a plain name (no '/', '\\', control characters, '.' or '..'; at most " +
                         std::to_string(kMaxNameLength) + " characters)");
}

BodySpec parse_body(Section& s) {
  BodySpec b;
  const std::string kind = s.string("kind", "", {"wedge", "disc", "apollo", "polygon"});
  if (kind.empty()) s.fail("kind", "required: one of wedge | disc | apollo | polygon");
  b.curve_tolerance = s.number("curve_tolerance", b.curve_tolerance, {0.0, 0.1, true, false});
  if (kind == "wedge") {
    b.kind = BodyKind::wedge;
    b.angle_deg = s.number("angle_deg", b.angle_deg, {0.0, 60.0, true, true});
    b.length = s.number("length", b.length, {kMinBodySize, kMaxBodySize});
  } else if (kind == "disc") {
    b.kind = BodyKind::disc;
    b.radius = s.number("radius", b.radius, {kMinBodySize, kMaxBodySize});
  } else if (kind == "apollo") {
    b.kind = BodyKind::apollo;
    b.diameter = s.number("diameter", b.diameter, {kMinBodySize, kMaxBodySize});
  } else {
    b.kind = BodyKind::polygon;
    b.points = s.points("points");
    for (const Vec2 q : b.points)
      if (std::abs(q.x) > kMaxCoordinate || std::abs(q.y) > kMaxCoordinate) {
        std::ostringstream os;
        os << "expected coordinates within +-" << kMaxCoordinate << ", got [" << q.x << ", " << q.y << "]";
        s.fail("points", os.str());
      }
  }
  s.finish();
  if (b.kind == BodyKind::polygon) {
    try {
      b.points = validated_polygon(b.points);
    } catch (const InputError& e) {
      s.fail("points", e.what());
    }
  }
  return b;
}

Domain parse_domain(Section& s) {
  Domain d;
  for (const char* k : {"xmin", "xmax", "ymin", "ymax"})
    if (!s.has(k)) s.fail(k, "required in a domain: section (xmin, xmax, ymin, ymax)");
  const Range coordinate{-kMaxCoordinate, kMaxCoordinate};
  d.xmin = s.number("xmin", 0, coordinate);
  d.xmax = s.number("xmax", 0, coordinate);
  d.ymin = s.number("ymin", 0, coordinate);
  d.ymax = s.number("ymax", 0, coordinate);
  d.symmetric = s.boolean("symmetric", false);
  s.finish();
  if (!(d.xmax > d.xmin)) s.fail("xmax", "must exceed xmin");
  if (!(d.ymax > d.ymin)) s.fail("ymax", "must exceed ymin");
  if (d.symmetric && d.ymin != 0.0) s.fail("ymin", "must be 0 for a symmetric domain");
  return d;
}

Box parse_box(Section& s) {
  Box b;
  b.width = at_most(s, "width", s.number("width", b.width, positive()), kMaxBoxSide);
  b.height = at_most(s, "height", s.number("height", b.height, positive()), kMaxBoxSide);
  b.periodic = s.boolean("periodic", b.periodic);
  s.finish();
  return b;
}

void resolve_box_particles(Scene& sc, Section& gran) {
  auto& g = sc.granular;
  const double area = sc.box->width * sc.box->height;
  if (g.particles && g.packing_fraction) {
    const double nu = static_cast<double>(*g.particles) * kDiskArea / area;
    if (std::abs(nu - *g.packing_fraction) > kPackingAgreement * *g.packing_fraction)
      gran.fail("packing_fraction",
                "particles " + std::to_string(*g.particles) + " give packing fraction " +
                    std::to_string(nu) + ", which disagrees with packing_fraction " +
                    std::to_string(*g.packing_fraction) + " by more than 0.5%");
  } else if (g.packing_fraction) {
    g.particles = static_cast<std::int64_t>(std::llround(*g.packing_fraction * area / kDiskArea));
  } else if (g.particles) {
    g.packing_fraction = static_cast<double>(*g.particles) * kDiskArea / area;
  } else {
    gran.fail("particles", "a box scene needs particles or packing_fraction");
  }
}

// cfd.end_time when the scene gives none and the flow can leave the domain
// subsonic (near-sonic bodies, outflow_can_be_subsonic): the bow shock's
// subsonic region reaches the far field and the shock settles slowly (the
// Mach 1.3 disc passes the shock-drift gate at 29 flow-throughs on a 1 R
// grid, ~20 on a 0.5 R grid; at the default 10 it still crept 0.04-0.08 R
// per flow-through).
constexpr double kSubsonicOutflowEndTime = 40.0;
// cfd.end_time when the scene gives none and the shock may stand off the
// body: its steady rule waits for the standoff to hold still to 0.2% per
// flow-through (cfd_cases/src/steady_state.cpp), which discs at Mach 3-6 on
// their reference grids reach at 9.4-13.4 flow-throughs, past the default
// 10; a bow shock that moves on at 30 is not steady.
constexpr double kBowShockEndTime = 30.0;

Scene parse_root(const YAML::Node& root, const std::string& origin) {
  Section top(root, origin, "");
  if (!root || !root.IsMap()) throw InputError(origin + ": expected a YAML mapping at the top level");
  Scene sc;
  sc.source_file = origin;
  const auto schema = top.opt_integer("schema", 1, 1000);
  if (schema && *schema != kSchemaVersion)
    top.fail("schema", "this build reads schema " + std::to_string(kSchemaVersion) + ", got " +
                           std::to_string(*schema));
  sc.name = top.string("name", std::filesystem::path(origin).stem().string());
  if (top.has("name")) check_name(top, sc.name);
  const bool has_body = top.has("body"), has_box = top.has("box");
  {
    Section s = top.child("body");
    if (has_body) sc.body = parse_body(s);
  }
  {
    Section s = top.child("box");
    if (has_box) sc.box = parse_box(s);
  }
  if (has_body && has_box) top.fail("box", "a scene has either a body or a box, not both");
  if (!has_body && !has_box) top.fail("body", "required: a body (or a box for validation scenes)");
  {
    Section s = top.child("freestream");
    if (has_body && !s.has("mach")) top.fail("freestream", "required: freestream.mach");
    sc.freestream.mach = at_most(s, "mach", s.number("mach", sc.freestream.mach, positive()), kMaxMach);
    sc.freestream.gamma = s.number("gamma", sc.freestream.gamma, {1.0, 5.0 / 3.0, true, false});
    s.finish();
  }
  {
    Section s = top.child("domain");
    if (top.has("domain")) sc.domain_override = parse_domain(s);
  }
  Section gran = top.child("granular");
  sc.granular = parse_granular(gran);
  gran.finish();
  if (sc.box) resolve_box_particles(sc, gran);
  {
    Section s = top.child("shockfit");
    sc.shockfit = parse_shockfit(s);
    s.finish();
  }
  {
    Section s = top.child("mesh");
    sc.mesh = parse_mesh(s);
    s.finish();
  }
  bool end_time_given = false;
  {
    Section s = top.child("cfd");
    sc.cfd = parse_cfd(s);
    end_time_given = s.has("end_time");
    s.finish();
  }
  {
    Section s = top.child("pipeline");
    sc.pipeline = parse_pipeline(s);
    s.finish();
  }
  top.finish();
  if (sc.body) {
    const BodyGeometry g = make_body(*sc.body);  // validates geometry early
    (void)g;
    (void)scene_domain(sc);  // validates an override against the body
    if (!end_time_given && shock_may_stand_off(sc)) sc.cfd.end_time = kBowShockEndTime;
    if (!end_time_given && outflow_can_be_subsonic(sc)) sc.cfd.end_time = kSubsonicOutflowEndTime;
    const bool attached = attached_shock_beta(sc).has_value();
    if (!sc.granular.averaging_given && attached) sc.granular.averaging = kAttachedShockAveraging;
    if (!sc.granular.replicas_given && !attached) sc.granular.replicas = kBowShockReplicas;
  }
  return sc;
}

}  // namespace

Scene parse_scene(const std::string& yaml_text, const std::string& origin) {
  return parse_root(load_single_document(yaml_text, origin), origin);
}

Scene load_scene(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path + ": scene file not found");
  return parse_scene(read_file(path), path);
}

double body_length(const BodySpec& b) {
  switch (b.kind) {
    case BodyKind::wedge: return b.length;
    case BodyKind::disc: return b.radius;
    case BodyKind::apollo: return b.diameter;
    case BodyKind::polygon: {
      const auto [lo, hi] = std::minmax_element(b.points.begin(), b.points.end(),
                                                [](Vec2 a, Vec2 c) { return a.x < c.x; });
      return hi->x - lo->x;
    }
  }
  return 1.0;
}

namespace {

struct Bbox {
  double xmin, xmax, ymin, ymax;
};
Bbox bbox(const std::vector<Vec2>& p) {
  Bbox b{p[0].x, p[0].x, p[0].y, p[0].y};
  for (const Vec2 q : p) {
    b.xmin = std::min(b.xmin, q.x);
    b.xmax = std::max(b.xmax, q.x);
    b.ymin = std::min(b.ymin, q.y);
    b.ymax = std::max(b.ymax, q.y);
  }
  return b;
}

// Domain for a blunt body of half-height h whose front is at x = xfront and
// whose outflow boundary is at x = xout, using Billig's cylinder correlation
// with nose radius h as the shock estimate.
Domain blunt_domain(double mach, double xfront, double xout, double h, bool symmetric) {
  const double m = std::max(mach, 1.2);
  const double standoff = billig_standoff_cylinder(m) * h;
  Domain d;
  // Upstream: room for the standoff plus free stream, so the inflow boundary
  // never touches the shock. Granular bow shocks (e near 1) stand off about
  // twice as far as air's (a disc at Mach 4: 1.2 radii against Billig's 0.52),
  // hence kGranularStandoffFactor times Billig, and the side sized for a
  // shock whose vertex stands that far out.
  constexpr double kGranularStandoffFactor = 2.5;
  constexpr double kUpstreamMargin = 1.6;  // domain edge beyond the granular shock vertex
  const double vertex = kGranularStandoffFactor * standoff;
  d.xmin = xfront - std::max(kUpstreamMargin * vertex, 0.8 * h);
  d.xmax = xout;
  const double shock_h = billig_shock_y(m, h, d.xmax - (xfront - vertex));
  d.ymax = std::max(1.1 * shock_h, 2.0 * h);
  d.ymin = symmetric ? 0.0 : -d.ymax;
  d.symmetric = symmetric;
  return d;
}

}  // namespace

Domain scene_domain(const Scene& s) {
  if (!s.body) throw InputError(s.source_file + ": scene has no body, so no flow domain");
  const BodyGeometry g = make_body(*s.body);
  const Bbox bb = bbox(g.polyline);
  const double mach = s.freestream.mach;
  Domain d;
  if (s.domain_override) {
    d = *s.domain_override;
  } else if (s.body->kind == BodyKind::wedge) {
    const double th = s.body->angle_deg * kDeg;
    const double xe = s.body->length * std::cos(th), ye = s.body->length * std::sin(th);
    const auto beta = oblique_shock_beta(mach, th, s.freestream.gamma);
    if (beta) {
      // Attached: the shock leaves through the top no later than x = xe; keep
      // 10 deg of slack for granular shocks, which stand at larger angles.
      d.xmin = -0.2 * s.body->length;
      d.xmax = xe;
      d.ymin = 0.0;
      d.ymax = std::max(xe * std::tan(std::min(*beta + 10 * kDeg, 80 * kDeg)), 1.5 * ye);
      d.symmetric = true;
    } else {
      // Detached: the flow behind the shock turns sonic at the base corner.
      // Cut there, the outflow leaves subsonic between body and shock, where
      // no outflow condition holds the shock (it crept upstream by 0.014-0.033
      // body lengths per flow-through at Mach 2, 30 deg). Past the base the
      // flow turns supersonic round the corner and the base's dead-water
      // region closes within about one base height.
      constexpr double kWakeBaseHeights = 1.0;
      d = blunt_domain(mach, 0.0, xe + kWakeBaseHeights * 2.0 * ye, ye, true);
    }
  } else {
    const double h = g.symmetric ? bb.ymax : 0.5 * (bb.ymax - bb.ymin);
    d = blunt_domain(mach, bb.xmin, bb.xmax, h, g.symmetric);
    if (!g.symmetric) {
      const double yc = 0.5 * (bb.ymax + bb.ymin);
      d.ymin += yc;
      d.ymax += yc;
    }
  }
  // The body may run out through the outflow boundary (the domain cuts it
  // there), but must clear the inflow boundary and the sides.
  const std::string where = s.source_file + ": domain: ";
  if (!(bb.xmin > d.xmin)) throw InputError(where + "the body touches or crosses the inflow boundary x = xmin");
  if (!(bb.xmin < d.xmax)) throw InputError(where + "the body lies downstream of the outflow boundary x = xmax");
  if (!(bb.ymax < d.ymax)) throw InputError(where + "the body touches or crosses the side boundary y = ymax");
  if (!d.symmetric && !(bb.ymin > d.ymin))
    throw InputError(where + "the body touches or crosses the side boundary y = ymin");
  if (d.symmetric && !g.symmetric)
    throw InputError(where + "symmetric domain, but the body is not symmetric about y = 0");
  return d;
}

void require_supersonic(const Scene& s, const std::string& stage) {
  if (s.freestream.mach > 1.0) return;
  std::ostringstream os;
  os << s.source_file << ": key 'freestream.mach': " << stage
     << " needs a supersonic free stream (Mach > 1, up to " << kMaxMach << ") to have a shock, got "
     << s.freestream.mach;
  throw InputError(os.str());
}

std::string to_yaml(const Scene& s) {
  YAML::Emitter e;
  // Doubles go through emit_value (the shortest exact decimal); this
  // precision serves only what the emitter formats itself.
  e.SetDoublePrecision(17);
  e.SetFloatPrecision(7);
  e << YAML::BeginMap;
  emit_kv(e, "schema", kSchemaVersion);
  emit_kv(e, "name", s.name);
  if (s.body) {
    const BodySpec& b = *s.body;
    e << YAML::Key << "body" << YAML::Value << YAML::BeginMap;
    switch (b.kind) {
      case BodyKind::wedge:
        emit_kv(e, "kind", "wedge");
        emit_kv(e, "angle_deg", b.angle_deg);
        emit_kv(e, "length", b.length);
        break;
      case BodyKind::disc:
        emit_kv(e, "kind", "disc");
        emit_kv(e, "radius", b.radius);
        break;
      case BodyKind::apollo:
        emit_kv(e, "kind", "apollo");
        emit_kv(e, "diameter", b.diameter);
        break;
      case BodyKind::polygon:
        emit_kv(e, "kind", "polygon");
        e << YAML::Key << "points" << YAML::Value << YAML::Flow << YAML::BeginSeq;
        for (const Vec2 p : b.points) emit_pair(e, p);
        e << YAML::EndSeq;
        break;
    }
    emit_kv(e, "curve_tolerance", b.curve_tolerance);
    e << YAML::EndMap;
  }
  if (s.box) {
    e << YAML::Key << "box" << YAML::Value << YAML::BeginMap;
    emit_kv(e, "width", s.box->width);
    emit_kv(e, "height", s.box->height);
    emit_kv(e, "periodic", s.box->periodic);
    e << YAML::EndMap;
  }
  e << YAML::Key << "freestream" << YAML::Value << YAML::BeginMap;
  emit_kv(e, "mach", s.freestream.mach);
  emit_kv(e, "gamma", s.freestream.gamma);
  e << YAML::EndMap;
  if (s.body) {
    const Domain d = scene_domain(s);
    e << YAML::Key << "domain" << YAML::Value << YAML::BeginMap;
    emit_kv(e, "xmin", d.xmin);
    emit_kv(e, "xmax", d.xmax);
    emit_kv(e, "ymin", d.ymin);
    emit_kv(e, "ymax", d.ymax);
    emit_kv(e, "symmetric", d.symmetric);
    e << YAML::EndMap;
  }
  e << YAML::Key << "granular" << YAML::Value;
  emit_granular(e, s.granular);
  e << YAML::Key << "shockfit" << YAML::Value;
  emit_shockfit(e, s.shockfit);
  e << YAML::Key << "mesh" << YAML::Value;
  emit_mesh(e, s.mesh);
  e << YAML::Key << "cfd" << YAML::Value;
  emit_cfd(e, s.cfd);
  e << YAML::Key << "pipeline" << YAML::Value;
  emit_pipeline(e, s.pipeline);
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

std::string section_yaml(const Scene& s, const std::string& section) {
  const YAML::Node root = YAML::Load(to_yaml(s));
  const YAML::Node n = root[section];
  if (!n.IsDefined() || n.IsNull()) return "";
  YAML::Emitter e;
  e << n;
  return e.c_str();
}

}  // namespace scene
