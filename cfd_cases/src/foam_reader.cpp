#include "cfd/foam_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>

#include "scene/errors.hpp"
#include "scene/io.hpp"

namespace cfd {
namespace {

namespace fs = std::filesystem;
using scene::InputError;
using scene::Vec2;

// Cursor over one OpenFOAM file with comments skipped.
class Cursor {
 public:
  Cursor(std::string text, std::string path) : t_(std::move(text)), path_(std::move(path)) {}

  void skip() {
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
        ++i_;
      } else if (c == '/' && i_ + 1 < t_.size() && t_[i_ + 1] == '/') {
        while (i_ < t_.size() && t_[i_] != '\n') ++i_;
      } else if (c == '/' && i_ + 1 < t_.size() && t_[i_ + 1] == '*') {
        const auto e = t_.find("*/", i_ + 2);
        i_ = e == std::string::npos ? t_.size() : e + 2;
      } else {
        return;
      }
    }
  }
  char peek() {
    skip();
    return i_ < t_.size() ? t_[i_] : '\0';
  }
  void expect(char c) {
    if (peek() != c) fail(std::string("expected '") + c + "'");
    ++i_;
  }
  bool accept(char c) {
    if (peek() != c) return false;
    ++i_;
    return true;
  }
  long label() {
    skip();
    long v = 0;
    const auto r = std::from_chars(t_.data() + i_, t_.data() + t_.size(), v);
    if (r.ec != std::errc()) fail("expected an integer");
    i_ = static_cast<std::size_t>(r.ptr - t_.data());
    return v;
  }
  double number() {
    skip();
    double v = 0;
    const char* b = t_.data() + i_;
    const char* e = t_.data() + t_.size();
    // from_chars rejects a leading '+' and writes "-nan" as a valid NaN.
    if (b < e && *b == '+') ++b;
    const auto r = std::from_chars(b, e, v);
    if (r.ec != std::errc()) fail("expected a number");
    i_ = static_cast<std::size_t>(r.ptr - t_.data());
    return v;
  }
  std::string word() {
    skip();
    const std::size_t b = i_;
    while (i_ < t_.size() && !std::isspace(static_cast<unsigned char>(t_[i_])) && t_[i_] != ';' &&
           t_[i_] != '{' && t_[i_] != '}' && t_[i_] != '(' && t_[i_] != ')')
      ++i_;
    if (b == i_) fail("expected a word");
    return t_.substr(b, i_ - b);
  }
  // Positions the cursor after the first occurrence of `key` as a whole
  // token at or after the current position.
  bool seek_token(const std::string& key) {
    std::size_t p = i_;
    while ((p = t_.find(key, p)) != std::string::npos) {
      const bool left = p == 0 || std::isspace(static_cast<unsigned char>(t_[p - 1]));
      const std::size_t e = p + key.size();
      const bool right = e < t_.size() && std::isspace(static_cast<unsigned char>(t_[e]));
      if (left && right) {
        i_ = e;
        return true;
      }
      p = e;
    }
    return false;
  }
  // Skips the FoamFile header, checking the format.
  void header() {
    if (!seek_token("FoamFile")) fail("no FoamFile header");
    expect('{');
    const std::size_t e = t_.find('}', i_);
    if (e == std::string::npos) fail("unterminated FoamFile header");
    const std::string h = t_.substr(i_, e - i_);
    if (h.find("binary") != std::string::npos)
      fail("binary format; run foamFormatConvert with writeFormat ascii");
    i_ = e + 1;
  }
  [[noreturn]] void fail(const std::string& what) const {
    // Line number for the message.
    const long line = 1 + std::count(t_.begin(), t_.begin() + static_cast<long>(std::min(i_, t_.size())), '\n');
    throw InputError(path_ + ":" + std::to_string(line) + ": " + what);
  }

 private:
  std::string t_;
  std::string path_;
  std::size_t i_ = 0;
};

Cursor open(const std::string& path) {
  if (!fs::exists(path) && fs::exists(path + ".gz"))
    throw InputError(path + ".gz: compressed OpenFOAM file; use writeCompression off");
  Cursor c(scene::read_file(path), path);
  c.header();
  return c;
}

struct P3 {
  double x, y, z;
};

std::vector<P3> read_points(const std::string& path) {
  Cursor c = open(path);
  const long n = c.label();
  std::vector<P3> pts(static_cast<std::size_t>(n));
  c.expect('(');
  for (auto& p : pts) {
    c.expect('(');
    p.x = c.number();
    p.y = c.number();
    p.z = c.number();
    c.expect(')');
  }
  c.expect(')');
  return pts;
}

std::vector<std::vector<long>> read_faces(const std::string& path) {
  Cursor c = open(path);
  const long n = c.label();
  std::vector<std::vector<long>> faces(static_cast<std::size_t>(n));
  c.expect('(');
  for (auto& f : faces) {
    const long k = c.label();
    f.resize(static_cast<std::size_t>(k));
    c.expect('(');
    for (auto& v : f) v = c.label();
    c.expect(')');
  }
  c.expect(')');
  return faces;
}

std::vector<long> read_labels(const std::string& path) {
  Cursor c = open(path);
  const long n = c.label();
  std::vector<long> v(static_cast<std::size_t>(n));
  if (c.accept('{')) {  // uniform list N{value}
    std::fill(v.begin(), v.end(), c.label());
    c.expect('}');
    return v;
  }
  c.expect('(');
  for (auto& x : v) x = c.label();
  c.expect(')');
  return v;
}

std::vector<PatchInfo> read_boundary(const std::string& path) {
  Cursor c = open(path);
  const long n = c.label();
  std::vector<PatchInfo> out;
  c.expect('(');
  for (long k = 0; k < n; ++k) {
    PatchInfo p;
    p.name = c.word();
    c.expect('{');
    int depth = 1;
    while (depth > 0) {
      if (c.accept('}')) {
        --depth;
        continue;
      }
      if (c.accept('{')) {
        ++depth;
        continue;
      }
      if (c.accept('(') || c.accept(')') || c.accept(';')) continue;
      const std::string w = c.word();
      if (depth != 1) continue;
      if (w == "type") p.type = c.word();
      else if (w == "startFace") p.start = c.label();
      else if (w == "nFaces") p.size = c.label();
    }
    out.push_back(p);
  }
  return out;
}

// Vector area of a planar polygon face (right-hand rule).
std::array<double, 3> face_area(const std::vector<long>& f, const std::vector<P3>& pts) {
  std::array<double, 3> s{0, 0, 0};
  const P3 o = pts[static_cast<std::size_t>(f[0])];
  for (std::size_t k = 1; k + 1 < f.size(); ++k) {
    const P3 a = pts[static_cast<std::size_t>(f[k])];
    const P3 b = pts[static_cast<std::size_t>(f[k + 1])];
    const double ax = a.x - o.x, ay = a.y - o.y, az = a.z - o.z;
    const double bx = b.x - o.x, by = b.y - o.y, bz = b.z - o.z;
    s[0] += 0.5 * (ay * bz - az * by);
    s[1] += 0.5 * (az * bx - ax * bz);
    s[2] += 0.5 * (ax * by - ay * bx);
  }
  return s;
}

double signed_area(const std::vector<Vec2>& poly) {
  double a = 0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
    a += 0.5 * (p.x * q.y - q.x * p.y);
  }
  return a;
}

Vec2 polygon_centroid(const std::vector<Vec2>& poly, double area) {
  double cx = 0, cy = 0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Vec2 p = poly[k], q = poly[(k + 1) % poly.size()];
    const double w = p.x * q.y - q.x * p.y;
    cx += (p.x + q.x) * w;
    cy += (p.y + q.y) * w;
  }
  return {cx / (6 * area), cy / (6 * area)};
}

// Internal field values: "uniform v" or "nonuniform List<T> N ( ... )".
template <class Read>
void read_internal(const std::string& path, std::size_t cells, std::size_t width, Read read_one) {
  Cursor c = open(path);
  if (!c.seek_token("internalField")) c.fail("no internalField");
  const std::string kind = c.word();
  if (kind == "uniform") {
    read_one(c, std::numeric_limits<std::size_t>::max());
    return;
  }
  if (kind != "nonuniform") c.fail("expected uniform or nonuniform");
  (void)c.word();  // List<scalar> / List<vector>
  const long n = c.label();
  if (static_cast<std::size_t>(n) != cells)
    c.fail("internalField has " + std::to_string(n) + " values, the mesh " + std::to_string(cells) + " cells");
  (void)width;
  if (c.accept('{')) {  // N{value}
    read_one(c, std::numeric_limits<std::size_t>::max());
    c.expect('}');
    return;
  }
  c.expect('(');
  for (std::size_t k = 0; k < cells; ++k) read_one(c, k);
  c.expect(')');
}

}  // namespace

Mesh2D read_mesh_2d(const std::string& dir) {
  const std::string pm = dir + "/constant/polyMesh/";
  const std::vector<P3> pts = read_points(pm + "points");
  const auto faces = read_faces(pm + "faces");
  const auto owner = read_labels(pm + "owner");
  const auto neighbour = read_labels(pm + "neighbour");
  Mesh2D m;
  m.patches = read_boundary(pm + "boundary");
  if (owner.size() != faces.size()) throw InputError(pm + "owner: size differs from faces");
  long ncells = 0;
  for (const long o : owner) ncells = std::max(ncells, o + 1);
  for (const long nb : neighbour) ncells = std::max(ncells, nb + 1);
  double zmin = std::numeric_limits<double>::infinity(), zmax = -zmin;
  for (const P3& p : pts) {
    zmin = std::min(zmin, p.z);
    zmax = std::max(zmax, p.z);
  }
  m.depth = zmax - zmin;
  if (!(m.depth > 0)) throw InputError(pm + "points: the mesh has no extent in z");
  const auto nc = static_cast<std::size_t>(ncells);
  m.cell_polygons.assign(nc, {});
  m.cell_edges.assign(nc, {});
  std::vector<char> is_empty_face(faces.size(), 0);
  for (const PatchInfo& p : m.patches)
    if (p.type == "empty")
      for (long f = p.start; f < p.start + p.size; ++f) is_empty_face[static_cast<std::size_t>(f)] = 1;
  const double zmid = 0.5 * (zmin + zmax);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const auto c = static_cast<std::size_t>(owner[f]);
    if (is_empty_face[f]) {
      // The front face (z = zmin) of its cell is the cell's polygon.
      if (pts[static_cast<std::size_t>(faces[f][0])].z > zmid) continue;
      std::vector<Vec2> poly;
      for (const long v : faces[f]) poly.push_back({pts[static_cast<std::size_t>(v)].x, pts[static_cast<std::size_t>(v)].y});
      if (signed_area(poly) < 0) std::reverse(poly.begin(), poly.end());
      m.cell_polygons[c] = std::move(poly);
      continue;
    }
    const auto s = face_area(faces[f], pts);
    const Vec2 sxy{s[0] / m.depth, s[1] / m.depth};
    const double len = std::hypot(sxy.x, sxy.y);
    const Vec2 n = len > 0 ? Vec2{sxy.x / len, sxy.y / len} : Vec2{0, 0};
    m.cell_edges[c].push_back({len, n});
    if (f < neighbour.size()) m.cell_edges[static_cast<std::size_t>(neighbour[f])].push_back({len, Vec2{-n.x, -n.y}});
  }
  m.cell_area.resize(nc);
  m.cell_centre.resize(nc);
  for (std::size_t c = 0; c < nc; ++c) {
    if (m.cell_polygons[c].size() < 3)
      throw InputError(pm + ": cell " + std::to_string(c) +
                       " has no face in an empty patch; cfd needs a 2D mesh one cell thick with frontAndBack empty");
    m.cell_area[c] = signed_area(m.cell_polygons[c]);
    m.cell_centre[c] = polygon_centroid(m.cell_polygons[c], m.cell_area[c]);
  }
  for (const PatchInfo& p : m.patches) {
    if (p.name != "body") continue;
    for (long f = p.start; f < p.start + p.size; ++f) {
      const auto& face = faces[static_cast<std::size_t>(f)];
      const auto s = face_area(face, pts);
      Vec2 ctr{0, 0};
      for (const long v : face) {
        ctr.x += pts[static_cast<std::size_t>(v)].x / static_cast<double>(face.size());
        ctr.y += pts[static_cast<std::size_t>(v)].y / static_cast<double>(face.size());
      }
      m.body.push_back({ctr, {s[0] / m.depth, s[1] / m.depth}, owner[static_cast<std::size_t>(f)]});
    }
  }
  return m;
}

std::vector<double> read_scalar_field(const std::string& path, std::size_t cells) {
  std::vector<double> v(cells);
  read_internal(path, cells, 1, [&](Cursor& c, std::size_t k) {
    const double x = c.number();
    if (k == std::numeric_limits<std::size_t>::max()) std::fill(v.begin(), v.end(), x);
    else v[k] = x;
  });
  return v;
}

std::vector<std::array<double, 3>> read_vector_field(const std::string& path, std::size_t cells) {
  std::vector<std::array<double, 3>> v(cells);
  read_internal(path, cells, 3, [&](Cursor& c, std::size_t k) {
    c.expect('(');
    const std::array<double, 3> x{c.number(), c.number(), c.number()};
    c.expect(')');
    if (k == std::numeric_limits<std::size_t>::max()) std::fill(v.begin(), v.end(), x);
    else v[k] = x;
  });
  return v;
}

std::vector<TimeDir> time_dirs(const std::string& dir, bool include_zero) {
  std::vector<TimeDir> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_directory()) continue;
    const std::string name = e.path().filename().string();
    double t = 0;
    const auto r = std::from_chars(name.data(), name.data() + name.size(), t);
    if (r.ec != std::errc() || r.ptr != name.data() + name.size()) continue;
    if (t == 0.0 && !include_zero) continue;
    out.push_back({t, name});
  }
  std::sort(out.begin(), out.end(), [](const TimeDir& a, const TimeDir& b) { return a.time < b.time; });
  return out;
}

}  // namespace cfd
