// Checkpoint / restart. The whole engine state is written raw (doubles as
// their bytes), including the cell lists' order and every prediction, so a
// restored engine takes exactly the same decisions: the continuation is
// bit-identical to an uninterrupted run. The calendar is rebuilt from the
// stored predictions (its order, (time, slot), is a pure function of them).
#include <cstring>
#include <istream>
#include <ostream>
#include <string>
#include <type_traits>

#include "engine_impl.hpp"
#include "scene/errors.hpp"

namespace granular {

namespace {

constexpr char kMagic[8] = {'G', 'R', 'A', 'N', 'C', 'K', 'P', '4'};

template <class T>
void put(std::ostream& o, const T& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  o.write(reinterpret_cast<const char*>(&v), sizeof(T));
}
template <class T, class A>
void put_vec(std::ostream& o, const std::vector<T, A>& v) {
  put(o, static_cast<std::uint64_t>(v.size()));
  if (!v.empty()) o.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(v.size() * sizeof(T)));
}
template <class T>
void get(std::istream& in, T& v) {
  in.read(reinterpret_cast<char*>(&v), sizeof(T));
  if (!in) throw scene::InputError("checkpoint: truncated file");
}
template <class T, class A>
void get_vec(std::istream& in, std::vector<T, A>& v) {
  std::uint64_t n = 0;
  get(in, n);
  if (n > (std::uint64_t{1} << 40)) throw scene::InputError("checkpoint: corrupt size");
  v.resize(n);
  if (n) in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(n * sizeof(T)));
  if (!in) throw scene::InputError("checkpoint: truncated file");
}

void put_config(std::ostream& o, const EngineConfig& c) {
  put(o, c.xmin); put(o, c.xmax); put(o, c.ymin); put(o, c.ymax);
  put(o, c.left); put(o, c.right); put(o, c.bottom); put(o, c.top);
  put_vec(o, c.species);
  put_vec(o, c.restitution);
  put_vec(o, c.walls);
  put_vec(o, c.vertices);
  put(o, c.gravity);
  put(o, c.tc);
  put(o, c.min_cell);
  put(o, c.grid_speed);
}

EngineConfig get_config(std::istream& in) {
  EngineConfig c;
  get(in, c.xmin); get(in, c.xmax); get(in, c.ymin); get(in, c.ymax);
  get(in, c.left); get(in, c.right); get(in, c.bottom); get(in, c.top);
  get_vec(in, c.species);
  get_vec(in, c.restitution);
  get_vec(in, c.walls);
  get_vec(in, c.vertices);
  get(in, c.gravity);
  get(in, c.tc);
  get(in, c.min_cell);
  get(in, c.grid_speed);
  return c;
}

}  // namespace

void Engine::save(std::ostream& o) const {
  const Impl& m = *impl_;
  o.write(kMagic, sizeof(kMagic));
  put_config(o, m.cfg);
  put_vec(o, m.p);
  put_vec(o, m.s);
  put_vec(o, m.timer_t);
  put_vec(o, m.head);
  put_vec(o, m.free_slots);
  put(o, m.started);
  put(o, m.now);
  put(o, m.st);
  put(o, m.energy);
  put(o, m.virial);
  put(o, m.meas_start);
  put(o, m.energy_integral);
  put(o, m.energy_since);
  put(o, m.events);
  put(o, m.next_reorder);
  if (!o) throw scene::RunError("checkpoint: write failed");
}

Engine Engine::load(std::istream& in) {
  char magic[sizeof(kMagic)] = {};
  in.read(magic, sizeof(magic));
  if (in && std::memcmp(magic, kMagic, sizeof(kMagic) - 1) == 0 && magic[7] != kMagic[7])
    throw scene::InputError(std::string("checkpoint: written in format ") + magic[7] +
                            ", this engine reads format " + kMagic[7] +
                            " (the memory layout changed): restart the run from its scene");
  if (!in || std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
    throw scene::InputError("checkpoint: not a granular engine checkpoint");
  Engine e(get_config(in));
  Impl& m = *e.impl_;
  get_vec(in, m.p);
  get_vec(in, m.s);
  get_vec(in, m.timer_t);
  decltype(m.head) head;
  get_vec(in, head);
  if (head.size() != m.head.size() || m.s.size() != m.p.size() ||
      m.timer_t.size() != (m.drifting ? m.p.size() : 0))
    throw scene::InputError("checkpoint: inconsistent grid");
  m.head = std::move(head);
  get_vec(in, m.free_slots);
  get(in, m.started);
  get(in, m.now);
  get(in, m.st);
  get(in, m.energy);
  get(in, m.virial);
  get(in, m.meas_start);
  get(in, m.energy_integral);
  get(in, m.energy_since);
  get(in, m.events);
  get(in, m.next_reorder);
  if (m.started) m.rebuild_calendar();
  m.choose_look_ahead();
  return e;
}

}  // namespace granular
