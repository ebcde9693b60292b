// The event calendar (granular/src/engine/calendar.hpp) against a brute-force
// reference: whatever its bucket width, ring size, far entries, same-batch
// pushes, stale entries and re-tuning, it must hand out the live entries in
// exact lexicographic (time, slot) order.
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "calendar.hpp"

namespace granular::detail {
namespace {

using Entry = Calendar::Entry;

// A model of the engine's use: each slot has one live key (or none) and a
// version; rescheduling bumps the version, so the old entry goes stale.
struct Model {
  std::vector<double> key;
  std::vector<std::uint32_t> ver;
  std::set<std::pair<double, std::uint32_t>> ref;  // live (time, slot)

  explicit Model(std::size_t n) : key(n, -1.0), ver(n, 0) {}

  void schedule(Calendar& cal, std::uint32_t slot, double t) {
    if (key[slot] >= 0.0) ref.erase({key[slot], slot});
    ++ver[slot];
    key[slot] = t;
    ref.insert({t, slot});
    cal.push({t, slot, ver[slot]});
  }
  void unschedule(std::uint32_t slot) {
    if (key[slot] >= 0.0) ref.erase({key[slot], slot});
    ++ver[slot];
    key[slot] = -1.0;
  }
  bool live(const Entry& e) const { return ver[e.slot] == e.ver; }
  double time_of(std::uint32_t slot) const { return key[slot]; }
};

// Slot -> scheduled time, for tests that push fixed entries, all live.
struct Fixed {
  std::vector<double> t = std::vector<double>(16, -1.0);
  void push(Calendar& cal, double time, std::uint32_t slot) {
    t[slot] = time;
    cal.push({time, slot, 0});
  }
};

// Drives `steps` pops with random rescheduling; returns how many pops
// matched the reference (all of them, or the test failed).
std::size_t drive(std::size_t slots, std::size_t steps, std::uint64_t seed, bool retune_midway) {
  std::mt19937_64 rng(seed);
  std::exponential_distribution<double> typical(1.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Calendar cal;
  Model m(slots);
  double now = 0.0;
  cal.reset(now, slots, static_cast<double>(slots));
  for (std::uint32_t s = 0; s < slots; ++s) m.schedule(cal, s, now + typical(rng));
  const auto live = [&m](const Entry& e) { return m.live(e); };
  const auto time_of = [&m](std::uint32_t slot) { return m.time_of(slot); };
  std::size_t matched = 0;
  for (std::size_t step = 0; step < steps; ++step) {
    const Entry* e = cal.top(live, time_of);
    if (m.ref.empty()) {
      EXPECT_EQ(e, nullptr);
      break;
    }
    EXPECT_NE(e, nullptr);
    if (!e) break;
    const auto want = *m.ref.begin();
    EXPECT_EQ(e->t, want.first) << "step " << step;
    EXPECT_EQ(e->slot, want.second) << "step " << step;
    if (e->t != want.first || e->slot != want.second) break;
    ++matched;
    now = e->t;
    const std::uint32_t slot = e->slot;
    cal.pop();
    m.unschedule(slot);
    // The popped slot and a random other get new events: mostly typical,
    // sometimes within the current batch, at exactly now (ties), far
    // beyond the ring, or never (left unscheduled).
    for (const std::uint32_t s : {slot, static_cast<std::uint32_t>(rng() % slots)}) {
      const double u = unit(rng);
      if (u < 0.05) continue;                                   // no event
      double t = now + typical(rng);
      if (u < 0.15) t = now + 1e-6 * unit(rng);                 // same batch
      else if (u < 0.20) t = now;                               // tie at now
      else if (u < 0.25) t = now + 1e3 * (1.0 + unit(rng));     // far heap
      else if (u < 0.27 && m.key[s] >= 0.0) t = m.key[s];      // same time again
      m.schedule(cal, s, t);
    }
    if (retune_midway && step == steps / 2) {
      cal.reset(now, slots, cal.measured_rate(now) * 50.0);  // deliberately off
      for (std::uint32_t s = 0; s < slots; ++s)
        if (m.key[s] >= 0.0) cal.push({m.key[s], s, m.ver[s]});
    }
  }
  return matched;
}

TEST(EngineCalendar, PopsLiveEntriesInExactTimeSlotOrder) {
  EXPECT_EQ(drive(3000, 200000, 1, false), 200000u);
}

TEST(EngineCalendar, OrderSurvivesAReset) {
  EXPECT_EQ(drive(500, 50000, 2, true), 50000u);
}

TEST(EngineCalendar, TiesAreOrderedBySlot) {
  Calendar cal;
  cal.reset(0.0, 8, 8.0);
  Fixed f;
  for (const std::uint32_t s : {5u, 2u, 7u, 0u}) f.push(cal, 1.5, s);
  const auto all = [](const Entry&) { return true; };
  const auto time_of = [&f](std::uint32_t slot) { return f.t[slot]; };
  for (const std::uint32_t want : {0u, 2u, 5u, 7u}) {
    const Entry* e = cal.top(all, time_of);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->slot, want);
    cal.pop();
  }
  EXPECT_EQ(cal.top(all, time_of), nullptr);
}

TEST(EngineCalendar, JumpsOverEmptyTimeToFarEntries) {
  Calendar cal;
  cal.reset(0.0, 4, 4.0);  // buckets of ~8 time units, ring of a few hundred
  Fixed f;
  f.push(cal, 1e12, 3);
  f.push(cal, 2e15, 1);
  const auto all = [](const Entry&) { return true; };
  const auto time_of = [&f](std::uint32_t slot) { return f.t[slot]; };
  const Entry* e = cal.top(all, time_of);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->t, 1e12);
  cal.pop();
  e = cal.top(all, time_of);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->t, 2e15);
  cal.pop();
  EXPECT_EQ(cal.top(all, time_of), nullptr);
}

TEST(EngineCalendar, HugeTimesRebaseInsteadOfOverflowing) {
  // A nearly stopped disk can predict a cell crossing at 1e300: with
  // buckets of ~1e-3 the bucket number overflows; the calendar must still
  // hand the entries out in order (and not spin on an infinite count).
  Calendar cal;
  cal.reset(0.0, 1000, 1.0e6);
  Fixed f;
  f.push(cal, 2e300, 7);
  f.push(cal, 0.5, 3);
  f.push(cal, 1e300, 9);
  f.push(cal, 1e300, 2);
  const auto all = [](const Entry&) { return true; };
  const auto time_of = [&f](std::uint32_t slot) { return f.t[slot]; };
  const std::vector<std::pair<double, std::uint32_t>> want{{0.5, 3}, {1e300, 2}, {1e300, 9}, {2e300, 7}};
  for (const auto& [t, slot] : want) {
    const Entry* e = cal.top(all, time_of);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->t, t);
    EXPECT_EQ(e->slot, slot);
    cal.pop();
  }
  EXPECT_EQ(cal.top(all, time_of), nullptr);
}

TEST(EngineCalendar, PileOfSupersededFarEntriesAsksForARebuild) {
  // Ten slots re-predicting far-off events again and again: the stale far
  // entries would wait until their time; the calendar asks its owner to
  // rebuild from the live predictions once they outnumber the live slots.
  Calendar cal;
  Model m(10);
  cal.reset(0.0, 10, 10.0);
  std::size_t pushes = 0;
  while (!cal.wants_retune() && pushes < 100000) {
    m.schedule(cal, static_cast<std::uint32_t>(pushes % 10), 1e9 + static_cast<double>(pushes));
    ++pushes;
  }
  EXPECT_TRUE(cal.wants_retune());
  EXPECT_LE(pushes, Calendar::kFarMin + 1);
  // Rebuilt from the live entries, it hands out exactly those, in order.
  cal.reset(0.0, 10, 10.0);
  for (std::uint32_t s = 0; s < 10; ++s) cal.push({m.key[s], s, m.ver[s]});
  EXPECT_FALSE(cal.wants_retune());
  const auto live = [&m](const Entry& e) { return m.live(e); };
  const auto time_of = [&m](std::uint32_t slot) { return m.time_of(slot); };
  for (const auto& [t, slot] : std::set<std::pair<double, std::uint32_t>>(m.ref)) {
    const Entry* e = cal.top(live, time_of);
    ASSERT_NE(e, nullptr);
    EXPECT_EQ(e->t, t);
    EXPECT_EQ(e->slot, slot);
    cal.pop();
  }
}

TEST(EngineCalendar, MemoryFollowsWhatIsScheduled) {
  // 10^5 live entries, each rescheduled many times: stale entries are
  // dropped as their buckets come up, so memory stays near 8 B per entry
  // plus the ring, not growing with the number of pushes.
  std::size_t slots = 100000;
  Calendar cal;
  Model m(slots);
  std::mt19937_64 rng(3);
  std::exponential_distribution<double> typical(1.0);
  cal.reset(0.0, slots, static_cast<double>(slots));
  for (std::uint32_t s = 0; s < slots; ++s) m.schedule(cal, s, typical(rng));
  const auto live = [&m](const Entry& e) { return m.live(e); };
  const auto time_of = [&m](std::uint32_t slot) { return m.time_of(slot); };
  for (std::size_t step = 0; step < 20 * slots; ++step) {
    const Entry* e = cal.top(live, time_of);
    ASSERT_NE(e, nullptr);
    const double now = e->t;
    const std::uint32_t slot = e->slot;
    cal.pop();
    m.schedule(cal, slot, now + typical(rng));
    m.schedule(cal, static_cast<std::uint32_t>(rng() % slots), now + typical(rng));
  }
  EXPECT_LT(cal.bytes() / static_cast<double>(slots), 100.0);
}

}  // namespace
}  // namespace granular::detail
