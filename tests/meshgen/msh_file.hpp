#pragma once
// A gmsh 2.2 ASCII file read back for tests: physical names, node
// coordinates (x, y) and elements with their tags and nodes.
#include <cstddef>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "scene/io.hpp"
#include "scene/vec2.hpp"

namespace meshgen_test {

struct MshElement {
  int type = 0;                     // gmsh element type: 1 line, 2 triangle, 3 quad, 5 hexahedron, 6 prism
  std::vector<int> tags;            // 2.2: the first tag is the physical group
  std::vector<std::size_t> nodes;
};

struct MshFile {
  std::map<std::string, int> physical;  // name (quotes removed) -> tag
  std::vector<scene::Vec2> nodes;        // indexed by node id
  std::vector<MshElement> elements;
};

inline int nodes_per_element(int type) {
  switch (type) {
    case 5: return 8;
    case 6: return 6;
    case 3: return 4;
    case 2: return 3;
    case 1: return 2;
    default: return 1;
  }
}

// Extruded hexahedra and prisms list their bottom face first.
inline bool is_volume(const MshElement& e) { return e.type == 5 || e.type == 6; }

inline MshFile read_msh(const std::string& path) {
  std::istringstream is(scene::read_file(path));
  MshFile f;
  std::string line;
  while (std::getline(is, line)) {
    if (line == "$PhysicalNames") {
      int n = 0;
      is >> n;
      for (int k = 0; k < n; ++k) {
        int dim = 0, tag = 0;
        std::string name;
        is >> dim >> tag >> name;
        if (name.size() >= 2 && name.front() == '"' && name.back() == '"') name = name.substr(1, name.size() - 2);
        f.physical[name] = tag;
      }
    } else if (line == "$Nodes") {
      std::size_t n = 0;
      is >> n;
      f.nodes.resize(n + 1);
      for (std::size_t k = 0; k < n; ++k) {
        std::size_t id = 0;
        double x = 0, y = 0, z = 0;
        is >> id >> x >> y >> z;
        if (id >= f.nodes.size()) f.nodes.resize(id + 1);
        f.nodes[id] = {x, y};
      }
    } else if (line == "$Elements") {
      std::size_t n = 0;
      is >> n;
      for (std::size_t k = 0; k < n; ++k) {
        MshElement e;
        int id = 0, ntags = 0;
        is >> id >> e.type >> ntags;
        e.tags.resize(static_cast<std::size_t>(ntags));
        for (int& t : e.tags) is >> t;
        e.nodes.resize(static_cast<std::size_t>(nodes_per_element(e.type)));
        for (std::size_t& node : e.nodes) is >> node;
        f.elements.push_back(std::move(e));
      }
    }
  }
  return f;
}

}  // namespace meshgen_test
