#include "scene/group_fields.hpp"

#include <map>

#include "scene/errors.hpp"

namespace scene {

namespace {

constexpr std::string_view kPrefix = "group_";
constexpr const char* kMask = "inside_body";

}  // namespace

Lattice pack_groups(const std::vector<Lattice>& groups) {
  if (groups.empty()) return {};
  const Lattice& first = groups.front();
  Lattice packed(first.nx, first.ny, first.x0, first.y0, first.dx, first.dy);
  if (first.has(kMask)) packed.fields[kMask] = first.field(kMask);
  for (std::size_t k = 0; k < groups.size(); ++k)
    for (const char* name : kGroupFields)
      if (groups[k].has(name))
        packed.fields[std::string(kPrefix) + std::to_string(k) + "/" + name] =
            groups[k].field(name);
  return packed;
}

std::vector<Lattice> unpack_groups(const Lattice& packed, const std::string& what) {
  std::map<int, Lattice> by_index;
  for (const auto& [name, values] : packed.fields) {
    if (name.rfind(kPrefix, 0) != 0) continue;
    const std::size_t slash = name.find('/');
    const std::string index =
        slash == std::string::npos ? "" : name.substr(kPrefix.size(), slash - kPrefix.size());
    if (index.empty() || index.size() > 6 ||
        index.find_first_not_of("0123456789") != std::string::npos)
      throw InputError(what + ": array '" + name + "' is not group_<k>/<field>");
    auto [it, fresh] = by_index.try_emplace(std::stoi(index));
    if (fresh) {
      it->second = Lattice(packed.nx, packed.ny, packed.x0, packed.y0, packed.dx, packed.dy);
      if (packed.has(kMask)) it->second.fields[kMask] = packed.field(kMask);
    }
    it->second.fields[name.substr(slash + 1)] = values;
  }
  if (by_index.size() < 2) throw InputError(what + ": holds fewer than two averaging groups");
  std::vector<Lattice> out;
  for (auto& [k, lat] : by_index) out.push_back(std::move(lat));
  for (const Lattice& lat : out)
    if (lat.fields.size() != out.front().fields.size())
      throw InputError(what + ": the groups do not hold the same fields");
  return out;
}

}  // namespace scene
