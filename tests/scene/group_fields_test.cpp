// The averaging groups' fields in one lattice and back.
#include "scene/group_fields.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "scene/errors.hpp"
#include "scratch.hpp"

namespace {

scene::Lattice group(double value) {
  scene::Lattice lat(3, 2, -1.0, 0.0, 0.5, 0.5);
  lat.add("inside_body", 0.0)[4] = 1.0;
  lat.add("volume_fraction", value)[4] = std::nan("");
  lat.add("v", -value);
  lat.add("samples", 10.0 * value);
  lat.add("temperature", 7.0);  // not a locator's field: not kept
  return lat;
}

}  // namespace

TEST(GroupFields, RoundTripThroughAVtiFile) {
  const std::vector<scene::Lattice> groups{group(0.1), group(0.2), group(0.3)};
  const std::string path =
      (test_support::scratch_root() / ("groups_" + std::to_string(::getpid()) + ".vti")).string();
  scene::write_vti(scene::pack_groups(groups), path);
  const std::vector<scene::Lattice> back = scene::unpack_groups(scene::read_vti(path), path);
  std::filesystem::remove(path);
  ASSERT_EQ(back.size(), groups.size());
  for (std::size_t k = 0; k < groups.size(); ++k) {
    EXPECT_EQ(back[k].nx, 3);
    EXPECT_EQ(back[k].ny, 2);
    EXPECT_DOUBLE_EQ(back[k].dx, 0.5);
    for (const char* name : {"inside_body", "volume_fraction", "v", "samples"}) {
      ASSERT_TRUE(back[k].has(name)) << name;
      for (std::size_t c = 0; c < 6; ++c) {
        const double want = groups[k].field(name)[c], got = back[k].field(name)[c];
        if (std::isnan(want))
          EXPECT_TRUE(std::isnan(got)) << name << " cell " << c;
        else
          EXPECT_DOUBLE_EQ(got, want) << name << " cell " << c;
      }
    }
    EXPECT_FALSE(back[k].has("temperature"));
  }
}

TEST(GroupFields, FewerThanTwoGroupsOrAStrangeArrayAreInputErrors) {
  EXPECT_THROW((void)scene::unpack_groups(scene::pack_groups({group(0.1)}), "one.vti"),
               scene::InputError);
  scene::Lattice packed = scene::pack_groups({group(0.1), group(0.2)});
  packed.add("group_x/v", 0.0);
  try {
    (void)scene::unpack_groups(packed, "odd.vti");
    FAIL() << "expected InputError";
  } catch (const scene::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("odd.vti: array 'group_x/v'"), std::string::npos)
        << e.what();
  }
  scene::Lattice uneven = scene::pack_groups({group(0.1), group(0.2)});
  uneven.fields.erase("group_1/v");
  EXPECT_THROW((void)scene::unpack_groups(uneven, "uneven.vti"), scene::InputError);
}
