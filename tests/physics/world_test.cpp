// Tests of the world's body bookkeeping.
#include "service/physics/world.h"

#include <gtest/gtest.h>

#include <vector>

namespace contactsim {
namespace {

// The index a scan of the bodies finds for `id`, or -1.
int ScanIndex(const World& world, BodyId id) {
  for (int i = 0; i < static_cast<int>(world.bodies().size()); ++i) {
    if (world.bodies()[i].id == id) return i;
  }
  return -1;
}

void ExpectIndexMatchesScan(const World& world, BodyId up_to) {
  for (BodyId id = -2; id <= up_to + 2; ++id) {
    EXPECT_EQ(world.IndexOf(id), ScanIndex(world, id)) << "id " << id;
    EXPECT_EQ(world.Find(id) != nullptr, ScanIndex(world, id) >= 0) << "id " << id;
  }
}

// Verifies that IndexOf finds every body where a scan does, and no other,
// while the ids are consecutive, after bodies are removed from the front,
// the middle and the back (ids with gaps), after more are added behind the
// gaps, and for a world restored from saved bodies whose ids start late.
TEST(WorldIndex, IndexOfAgreesWithAScanThroughAdditionsAndRemovals) {
  World world;
  std::vector<BodyId> ids;
  for (int k = 0; k < 8; ++k) ids.push_back(world.AddBody(RigidBody{}));
  ExpectIndexMatchesScan(world, ids.back());
  for (BodyId gone : {ids[0], ids[4], ids[7]}) {
    ASSERT_TRUE(world.RemoveBody(gone).ok());
    ExpectIndexMatchesScan(world, ids.back());
  }
  for (int k = 0; k < 3; ++k) ids.push_back(world.AddBody(RigidBody{}));
  ExpectIndexMatchesScan(world, ids.back());

  std::vector<RigidBody> saved(world.bodies().begin() + 2, world.bodies().end());
  World restored;
  ASSERT_TRUE(restored.Assign(saved, {}, ids.back() + 1).ok());
  ExpectIndexMatchesScan(restored, ids.back());
}

}  // namespace
}  // namespace contactsim
