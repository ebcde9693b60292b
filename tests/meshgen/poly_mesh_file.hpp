#pragma once
// An ASCII constant/polyMesh read back for tests, with the geometry the
// comparisons need: cell volumes and patch areas from the faces alone
// (divergence theorem on planar faces), no OpenFOAM libraries.
#include <algorithm>
#include <array>
#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "scene/io.hpp"

namespace meshgen_test {

using Point3 = std::array<double, 3>;

struct PolyPatch {
  std::string name, type;
  long faces = 0, start = 0;
};

struct PolyMeshFile {
  std::vector<Point3> points;
  std::vector<std::vector<long>> faces;
  std::vector<long> owner, neighbour;
  std::vector<PolyPatch> patches;
  long cells = 0;
};

// The list body of an OpenFOAM ASCII file with '(' and ')' blanked out:
// the count, then the entries.
inline std::istringstream foam_list(const std::string& path) {
  std::string text = scene::read_file(path);
  std::size_t at = text.find('}', text.find("FoamFile"));
  // Past the header block and any comment lines, to the count.
  while (true) {
    at = text.find_first_not_of(" \t\r\n", at + 1);
    if (text.compare(at, 2, "//") != 0) break;
    at = text.find('\n', at);
  }
  text = text.substr(at);
  std::replace(text.begin(), text.end(), '(', ' ');
  std::replace(text.begin(), text.end(), ')', ' ');
  return std::istringstream(text);
}

inline std::vector<long> read_labels(const std::string& path) {
  std::istringstream is = foam_list(path);
  std::size_t n = 0;
  is >> n;
  std::vector<long> out(n);
  for (long& v : out) is >> v;
  return out;
}

inline PolyMeshFile read_poly_mesh(const std::string& case_dir) {
  const std::string dir = case_dir + "/constant/polyMesh/";
  PolyMeshFile m;
  {
    std::istringstream is = foam_list(dir + "points");
    std::size_t n = 0;
    is >> n;
    m.points.resize(n);
    for (Point3& p : m.points) is >> p[0] >> p[1] >> p[2];
  }
  {
    std::istringstream is = foam_list(dir + "faces");
    std::size_t n = 0;
    is >> n;
    m.faces.resize(n);
    for (auto& f : m.faces) {
      std::size_t k = 0;
      is >> k;
      f.resize(k);
      for (long& v : f) is >> v;
    }
  }
  m.owner = read_labels(dir + "owner");
  m.neighbour = read_labels(dir + "neighbour");
  for (const long c : m.owner) m.cells = std::max(m.cells, c + 1);
  const std::string text = scene::read_file(dir + "boundary");
  const std::regex entry(R"((\w+)\s*\{([^}]*)\})");
  const std::regex type(R"(\btype\s+(\w+);)"), faces(R"(nFaces\s+(\d+);)"),
      start(R"(startFace\s+(\d+);)");
  for (auto it = std::sregex_iterator(text.begin() + static_cast<long>(text.find('}')) + 1,
                                      text.end(), entry);
       it != std::sregex_iterator(); ++it) {
    const std::string body = (*it)[2].str();
    std::smatch t, f, s;
    if (!std::regex_search(body, t, type) || !std::regex_search(body, f, faces) ||
        !std::regex_search(body, s, start))
      continue;
    m.patches.push_back({(*it)[1].str(), t[1].str(), std::stol(f[1].str()), std::stol(s[1].str())});
  }
  return m;
}

// Area vector (right-hand rule on the point order) of a planar face.
inline Point3 area_vector(const PolyMeshFile& m, const std::vector<long>& f) {
  Point3 s{0, 0, 0};
  const Point3& o = m.points[static_cast<std::size_t>(f[0])];
  for (std::size_t k = 1; k + 1 < f.size(); ++k) {
    const Point3& p = m.points[static_cast<std::size_t>(f[k])];
    const Point3& q = m.points[static_cast<std::size_t>(f[k + 1])];
    const Point3 u{p[0] - o[0], p[1] - o[1], p[2] - o[2]}, v{q[0] - o[0], q[1] - o[1], q[2] - o[2]};
    s[0] += 0.5 * (u[1] * v[2] - u[2] * v[1]);
    s[1] += 0.5 * (u[2] * v[0] - u[0] * v[2]);
    s[2] += 0.5 * (u[0] * v[1] - u[1] * v[0]);
  }
  return s;
}

inline double norm(const Point3& s) {
  return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
}

// Cell volumes: V = sum over the cell's faces of x0 . S / 3 (S out of the
// cell), exact for planar faces.
inline std::vector<double> cell_volumes(const PolyMeshFile& m) {
  std::vector<double> v(static_cast<std::size_t>(m.cells), 0.0);
  for (std::size_t f = 0; f < m.faces.size(); ++f) {
    const Point3 s = area_vector(m, m.faces[f]);
    const Point3& x = m.points[static_cast<std::size_t>(m.faces[f][0])];
    const double flux = (x[0] * s[0] + x[1] * s[1] + x[2] * s[2]) / 3.0;
    v[static_cast<std::size_t>(m.owner[f])] += flux;
    if (f < m.neighbour.size()) v[static_cast<std::size_t>(m.neighbour[f])] -= flux;
  }
  return v;
}

inline double patch_area(const PolyMeshFile& m, const PolyPatch& p) {
  double a = 0.0;
  for (long f = p.start; f < p.start + p.faces; ++f)
    a += norm(area_vector(m, m.faces[static_cast<std::size_t>(f)]));
  return a;
}

}  // namespace meshgen_test
