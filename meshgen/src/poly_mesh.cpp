#include "poly_mesh.hpp"

#include "foam_export.hpp"
#include "scene/errors.hpp"
#include "scene/io.hpp"
#include "text_out.hpp"

namespace meshgen {

namespace {

// Bytes per entry, to reserve the buffers once.
constexpr std::size_t kPointChars = 64, kFaceChars = 48, kLabelChars = 8;

const char* const kLocation = "constant/polyMesh";

std::string header(const std::string& cls, const std::string& object,
                   const std::string& note = {}) {
  std::string h = foam_header(cls, object, kLocation);
  if (!note.empty()) h.insert(h.find("    location"), "    note        \"" + note + "\";\n");
  return h + "\n";
}

void write_points(const PlaneMesh& m, double thickness, const std::string& dir) {
  TextOut out(2 * m.nodes.size() * kPointChars);
  out << header("vectorField", "points") << 2 * m.nodes.size() << "\n(\n";
  for (const double z : {0.0, thickness})
    for (const scene::Vec2 p : m.nodes) out << '(' << p.x << ' ' << p.y << ' ' << z << ")\n";
  out << ")\n";
  scene::write_file_atomic(dir + "/points", out.str());
}

struct FaceLists {
  TextOut faces, owner, neighbour;
  long count = 0;
};

void add_lateral(FaceLists& f, const LayerFace& face, int n) {
  f.faces << "4(" << face.a << ' ' << face.b << ' ' << face.b + n << ' ' << face.a + n << ")\n";
  f.owner << face.owner << '\n';
  ++f.count;
}

// Back (z = 0, normal -z) and front (z = thickness, normal +z) of each cell.
void add_front_and_back(FaceLists& f, const ExtrudedLayer& layer, int n) {
  for (std::size_t i = 0; i < layer.cells.size(); ++i) {
    const auto& c = layer.cells[i];
    const int k = corner_count(c);
    f.faces << k << '(';
    for (int j = k - 1; j >= 0; --j) f.faces << c[static_cast<std::size_t>(j)] << (j ? ' ' : ')');
    f.faces << '\n' << k << '(';
    for (int j = 0; j < k; ++j)
      f.faces << c[static_cast<std::size_t>(j)] + n << (j + 1 < k ? ' ' : ')');
    f.faces << '\n';
    f.owner << i << '\n' << i << '\n';
    f.count += 2;
  }
}

}  // namespace

std::vector<FoamPatch> foam_patches(bool symmetric) {
  return {{"frontAndBack", "empty", std::nullopt},
          {"body", "wall", Patch::body},
          {"outlet", "patch", Patch::outlet},
          {"top", "patch", Patch::top},
          {"inlet", "patch", Patch::inlet},
          {"bottom", symmetric ? "symmetryPlane" : "patch", Patch::bottom}};
}

void write_poly_mesh(const PlaneMesh& m, const ExtrudedLayer& layer, double thickness,
                     const std::vector<FoamPatch>& patches, const std::string& case_dir) {
  const std::string dir = case_dir + "/" + kLocation;
  scene::make_dirs(dir);
  for (int p = 0; p < kPatchCount; ++p) {
    bool listed = false;
    for (const FoamPatch& fp : patches)
      listed = listed || (fp.edges && static_cast<int>(*fp.edges) == p);
    if (!layer.boundary[static_cast<std::size_t>(p)].empty() && !listed)
      throw scene::RunError("meshgen: boundary faces on patch '" +
                            patch_name(static_cast<Patch>(p)) + "', which the case does not list");
  }
  write_points(m, thickness, dir);

  const int n = static_cast<int>(m.nodes.size());
  const std::size_t faces = layer.internal.size() + 2 * layer.cells.size() + 4 * m.boundary.size();
  FaceLists f{TextOut(faces * kFaceChars), TextOut(faces * kLabelChars),
              TextOut(layer.internal.size() * kLabelChars), 0};
  for (const LayerFace& face : layer.internal) {
    add_lateral(f, face, n);
    f.neighbour << face.neighbour << '\n';
  }
  const long internal = f.count;
  TextOut boundary;
  boundary << patches.size() << "\n(\n";
  for (const FoamPatch& fp : patches) {
    const long start = f.count;
    if (fp.edges) {
      for (const LayerFace& face : layer.boundary[static_cast<std::size_t>(*fp.edges)])
        add_lateral(f, face, n);
    } else {
      add_front_and_back(f, layer, n);
    }
    boundary << "    " << fp.name << "\n    {\n        type            " << fp.type << ";\n";
    if (fp.type != "patch")
      boundary << "        inGroups        List<word> 1(" << fp.type << ");\n";
    boundary << "        nFaces          " << f.count - start << ";\n        startFace       "
             << start << ";\n    }\n";
  }
  boundary << ")\n";

  const std::string note =
      "nPoints:" + std::to_string(2 * n) + "  nCells:" + std::to_string(layer.cells.size()) +
      "  nFaces:" + std::to_string(f.count) + "  nInternalFaces:" + std::to_string(internal);
  TextOut text(f.faces.str().size() + 1024);
  text << header("faceList", "faces") << f.count << "\n(\n" << f.faces.str() << ")\n";
  scene::write_file_atomic(dir + "/faces", text.str());
  scene::write_file_atomic(dir + "/owner", header("labelList", "owner", note) +
                                               std::to_string(f.count) + "\n(\n" + f.owner.str() +
                                               ")\n");
  scene::write_file_atomic(dir + "/neighbour", header("labelList", "neighbour", note) +
                                                   std::to_string(internal) + "\n(\n" +
                                                   f.neighbour.str() + ")\n");
  scene::write_file_atomic(dir + "/boundary",
                           header("polyBoundaryMesh", "boundary") + boundary.str());
}

}  // namespace meshgen
