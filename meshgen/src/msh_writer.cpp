#include "msh_writer.hpp"

#include "scene/io.hpp"
#include "text_out.hpp"

namespace meshgen {

namespace {

// gmsh 2.2 element types.
constexpr int kTriangle = 2, kQuad = 3, kHexahedron = 5, kPrism = 6;
// Physical tags: the lateral patches 1..5 in Patch order, then these.
constexpr int kFrontAndBackTag = kPatchCount + 1, kFluidTag = 1;
constexpr std::size_t kLineChars = 80;

// One element with two tags (physical, elementary: the same here); node
// numbers are 1-based.
template <class Nodes>
void element(TextOut& out, long& id, int type, int tag, const Nodes& nodes) {
  out << ++id << ' ' << type << " 2 " << tag << ' ' << tag;
  for (const int v : nodes) out << ' ' << v + 1;
  out << '\n';
}

}  // namespace

void write_extruded_msh(const PlaneMesh& m, const ExtrudedLayer& layer, double thickness,
                        const std::string& path) {
  const int n = static_cast<int>(m.nodes.size());
  TextOut out((2 * m.nodes.size() + 4 * layer.cells.size() + m.boundary.size()) * kLineChars);
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n" << kPatchCount + 2 << '\n';
  for (int p = 0; p < kPatchCount; ++p)
    out << "2 " << p + 1 << " \"" << patch_name(static_cast<Patch>(p)) << "\"\n";
  out << "2 " << kFrontAndBackTag << " \"frontAndBack\"\n3 " << kFluidTag
      << " \"fluid\"\n$EndPhysicalNames\n";
  out << "$Nodes\n" << 2 * m.nodes.size() << '\n';
  long id = 0;
  for (const double z : {0.0, thickness})
    for (const scene::Vec2 p : m.nodes) out << ++id << ' ' << p.x << ' ' << p.y << ' ' << z << '\n';
  out << "$EndNodes\n$Elements\n";
  std::size_t lateral = 0;
  for (const auto& faces : layer.boundary) lateral += faces.size();
  out << lateral + 3 * layer.cells.size() << '\n';
  id = 0;
  for (int p = 0; p < kPatchCount; ++p)
    for (const LayerFace& f : layer.boundary[static_cast<std::size_t>(p)])
      element(out, id, kQuad, p + 1, std::array<int, 4>{f.a, f.b, f.b + n, f.a + n});
  for (const auto& c : layer.cells) {
    if (corner_count(c) == 4) {
      element(out, id, kQuad, kFrontAndBackTag, std::array<int, 4>{c[0], c[3], c[2], c[1]});
      element(out, id, kQuad, kFrontAndBackTag,
              std::array<int, 4>{c[0] + n, c[1] + n, c[2] + n, c[3] + n});
    } else {
      element(out, id, kTriangle, kFrontAndBackTag, std::array<int, 3>{c[0], c[2], c[1]});
      element(out, id, kTriangle, kFrontAndBackTag,
              std::array<int, 3>{c[0] + n, c[1] + n, c[2] + n});
    }
  }
  for (const auto& c : layer.cells) {
    if (corner_count(c) == 4)
      element(out, id, kHexahedron, kFluidTag,
              std::array<int, 8>{c[0], c[1], c[2], c[3], c[0] + n, c[1] + n, c[2] + n, c[3] + n});
    else
      element(out, id, kPrism, kFluidTag,
              std::array<int, 6>{c[0], c[1], c[2], c[0] + n, c[1] + n, c[2] + n});
  }
  out << "$EndElements\n";
  scene::write_file_atomic(path, out.str());
}

}  // namespace meshgen
