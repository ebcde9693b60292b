#include "scene/lattice.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <regex>
#include <sstream>

#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "scene/units.hpp"

namespace scene {

Lattice::Lattice(int nx_, int ny_, double x0_, double y0_, double dx_, double dy_)
    : nx(nx_), ny(ny_), x0(x0_), y0(y0_), dx(dx_), dy(dy_) {}

Lattice domain_lattice(const Domain& d, int nx, int ny) {
  return Lattice(nx, ny, d.xmin, d.ymin, d.width() / nx, d.height() / ny);
}

std::vector<double>& Lattice::add(const std::string& name, double value) {
  auto& f = fields[name];
  f.assign(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny), value);
  return f;
}

const std::vector<double>& Lattice::field(const std::string& name) const {
  const auto it = fields.find(name);
  if (it == fields.end()) {
    std::string have;
    for (const auto& [k, v] : fields) have += (have.empty() ? "" : ", ") + k;
    throw InputError("lattice has no field '" + name + "' (has: " + have + ")");
  }
  return it->second;
}

bool Lattice::sample(const std::string& name, double x, double y, double& out) const {
  const auto& f = field(name);
  const double fx = (x - x0) / dx - 0.5, fy = (y - y0) / dy - 0.5;
  // Within half a cell of the outer edge, clamp to the outermost centres.
  const double cx = std::clamp(fx, 0.0, static_cast<double>(nx - 1));
  const double cy = std::clamp(fy, 0.0, static_cast<double>(ny - 1));
  if (fx < -0.5 || fy < -0.5 || fx > nx - 0.5 || fy > ny - 0.5) return false;
  const int i = std::min(static_cast<int>(cx), nx - 2 < 0 ? 0 : nx - 2);
  const int j = std::min(static_cast<int>(cy), ny - 2 < 0 ? 0 : ny - 2);
  const double tx = nx > 1 ? cx - i : 0.0, ty = ny > 1 ? cy - j : 0.0;
  const int i1 = std::min(i + 1, nx - 1), j1 = std::min(j + 1, ny - 1);
  const double a = f[index(i, j)], b = f[index(i1, j)], c = f[index(i, j1)], d = f[index(i1, j1)];
  if (!std::isfinite(a) || !std::isfinite(b) || !std::isfinite(c) || !std::isfinite(d)) return false;
  out = (1 - tx) * (1 - ty) * a + tx * (1 - ty) * b + (1 - tx) * ty * c + tx * ty * d;
  return true;
}

void write_vti(const Lattice& lat, const std::string& path) {
  write_stream_atomic(path, [&](std::ostream& os) {
    os << std::setprecision(10);
    os << "<?xml version=\"1.0\"?>\n"
       << "<VTKFile type=\"ImageData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
       << "  <ImageData WholeExtent=\"0 " << lat.nx << " 0 " << lat.ny << " 0 0\" Origin=\""
       << lat.x0 << " " << lat.y0 << " 0\" Spacing=\"" << lat.dx << " " << lat.dy << " 1\">\n"
       << "    <Piece Extent=\"0 " << lat.nx << " 0 " << lat.ny << " 0 0\">\n"
       << "      <CellData>\n";
    for (const auto& [name, f] : lat.fields) {
      os << "        <DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
      for (std::size_t k = 0; k < f.size(); ++k) {
        // NaN marks "no data" (inside the body); VTK reads "nan".
        if (std::isfinite(f[k])) os << f[k]; else os << "nan";
        os << ((k + 1) % 10 == 0 ? '\n' : ' ');
      }
      os << "\n        </DataArray>\n";
    }
    os << "      </CellData>\n    </Piece>\n  </ImageData>\n</VTKFile>\n";
  });
}

Lattice read_vti(const std::string& path) {
  const std::string text = read_file(path);
  auto bad = [&](const std::string& what) -> InputError {
    return InputError(path + ": not a lattice .vti file: " + what);
  };
  if (text.empty()) throw bad("file is empty");
  const std::regex image(
      R"(<ImageData\s+WholeExtent=\"0 (\d+) 0 (\d+) 0 0\"\s+Origin=\"([^ ]+) ([^ ]+) [^\"]+\"\s+Spacing=\"([^ ]+) ([^ ]+) [^\"]+\")");
  std::smatch m;
  // Only the header is searched (std::regex is slow and recursive on long text).
  // The header is a few hundred characters; capping it keeps a junk file
  // without any <DataArray from being fed whole to the regex.
  constexpr std::size_t kMaxHeaderChars = 4096;
  const std::string head = text.substr(0, std::min(text.find("<DataArray"), kMaxHeaderChars));
  if (!std::regex_search(head, m, image)) throw bad("no <ImageData WholeExtent/Origin/Spacing> header");
  // Header numbers are checked before anything is sized from them: a hostile
  // extent would otherwise overflow stoi or allocate billions of values.
  const auto count = [&](const std::string& t, const char* what) {
    if (t.size() > 9) throw bad(std::string(what) + " '" + t + "' is too large");
    return std::stoi(t);
  };
  const auto real = [&](const std::string& t, const char* what) {
    double v = 0;
    try {
      v = std::stod(t);
    } catch (...) {
      throw bad(std::string(what) + " '" + t + "' is not a number");
    }
    if (!std::isfinite(v)) throw bad(std::string(what) + " '" + t + "' is not finite");
    return v;
  };
  Lattice lat(count(m[1], "WholeExtent nx"), count(m[2], "WholeExtent ny"), real(m[3], "Origin x"),
              real(m[4], "Origin y"), real(m[5], "Spacing x"), real(m[6], "Spacing y"));
  if (lat.nx < 1 || lat.ny < 1) throw bad("empty extent");
  if (!(lat.dx > 0) || !(lat.dy > 0)) throw bad("Spacing must be positive");
  const std::size_t n = static_cast<std::size_t>(lat.nx) * static_cast<std::size_t>(lat.ny);
  // Every value takes at least two characters ("0 "): a larger extent
  // cannot be what the file holds.
  if (n > text.size() / 2)
    throw bad("WholeExtent " + std::to_string(lat.nx) + " x " + std::to_string(lat.ny) +
              " needs more values than the file can hold");
  // DataArrays are found by plain search: std::regex recurses once per
  // character it matches and overflows the stack on large arrays.
  const std::regex name_attr(R"(Name=\"([^\"]+)\")");
  for (std::size_t pos = text.find("<DataArray"); pos != std::string::npos; pos = text.find("<DataArray", pos)) {
    const std::size_t tag_end = text.find('>', pos);
    if (tag_end == std::string::npos) throw bad("unterminated <DataArray> tag");
    const std::string tag = text.substr(pos, tag_end - pos);
    std::smatch nm;
    if (!std::regex_search(tag, nm, name_attr)) throw bad("<DataArray> without a Name");
    const std::string name = nm[1];
    const std::size_t close = text.find("</DataArray>", tag_end);
    if (close == std::string::npos) throw bad("field '" + name + "': no </DataArray>");
    std::istringstream is(text.substr(tag_end + 1, close - tag_end - 1));
    pos = close;
    std::vector<double> v;
    v.reserve(n);
    std::string tok;
    while (is >> tok) {
      if (tok == "nan" || tok == "NaN" || tok == "-nan") {
        v.push_back(kNaN);
        continue;
      }
      try {
        v.push_back(std::stod(tok));
      } catch (...) {
        throw bad("field '" + name + "': '" + tok + "' is not a number");
      }
    }
    if (v.size() != n)
      throw bad("field '" + name + "' has " + std::to_string(v.size()) + " values, expected " + std::to_string(n));
    lat.fields[name] = std::move(v);
  }
  if (lat.fields.empty()) throw bad("no DataArray fields");
  return lat;
}

}  // namespace scene
