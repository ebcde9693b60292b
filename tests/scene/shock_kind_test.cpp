// The shock kind crosses files as text: each kind reads back as itself, and
// text that names no kind (a missing summary key) reads as none.
#include "scene/shock_kind.hpp"

#include <gtest/gtest.h>

namespace {

TEST(ShockKind, TextRoundTrip) {
  for (const scene::ShockKind k :
       {scene::ShockKind::attached, scene::ShockKind::detached, scene::ShockKind::none})
    EXPECT_EQ(scene::shock_kind_from(scene::to_string(k)), k) << scene::to_string(k);
  EXPECT_EQ(scene::to_string(scene::ShockKind::attached), "attached");
  EXPECT_EQ(scene::to_string(scene::ShockKind::detached), "detached");
  EXPECT_EQ(scene::to_string(scene::ShockKind::none), "none");
}

TEST(ShockKind, UnknownTextIsNone) {
  EXPECT_EQ(scene::shock_kind_from(""), scene::ShockKind::none);
  EXPECT_EQ(scene::shock_kind_from("Attached"), scene::ShockKind::none);
}

}  // namespace
