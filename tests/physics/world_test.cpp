// Tests of the world's body bookkeeping.
#include "service/physics/world.h"

#include <gtest/gtest.h>

#include <limits>
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

// Verifies that ids no body can have, the extremes of the id type among
// them, find nothing: a client may name any id, and the lookup's offset
// from the first id must not overflow (the sanitizer build checks it).
TEST(WorldIndex, IdsAtTheExtremesFindNothing) {
  World world;
  for (int k = 0; k < 4; ++k) world.AddBody(RigidBody{});
  const BodyId lo = std::numeric_limits<BodyId>::min();
  const BodyId hi = std::numeric_limits<BodyId>::max();
  for (BodyId id : {lo, lo + 1, BodyId{-1}, BodyId{0}, hi - 1, hi}) {
    EXPECT_EQ(world.IndexOf(id), -1) << "id " << id;
    EXPECT_EQ(world.Find(id), nullptr) << "id " << id;
  }
  // a restored world whose ids sit just below the largest id
  std::vector<RigidBody> saved(world.bodies().begin(), world.bodies().end());
  for (size_t i = 0; i < saved.size(); ++i) saved[i].id = hi - 8 + 2 * static_cast<BodyId>(i);
  World restored;
  ASSERT_TRUE(restored.Assign(saved, {}, hi).ok());
  for (BodyId id : {lo, BodyId{1}, hi - 9, hi - 7, hi}) EXPECT_EQ(restored.IndexOf(id), -1) << "id " << id;
  for (size_t i = 0; i < saved.size(); ++i) EXPECT_EQ(restored.IndexOf(saved[i].id), static_cast<int>(i));
}

}  // namespace
}  // namespace contactsim
