// Tests of the friction anchors' bookkeeping and the Coulomb limit.
#include "service/contact/penalty/penalty_friction.h"

#include <gtest/gtest.h>

namespace contactsim {
namespace {

Contact MakeContact(BodyId a, BodyId b, uint32_t feature) {
  Contact c;
  c.id_a = a;
  c.id_b = b;
  c.feature_id = feature;
  return c;
}

// Verifies that an anchor is found for the same feature whatever the body
// order, with the stretch of B relative to A flipped with the order.
TEST(PenaltyFriction, AnchorsAreKeyedByPairAndFeature) {
  FrictionAnchors anchors;
  AnchorState s;
  s.stretch = Vec3(1e-3, -2e-3, 0);
  anchors.Keep(MakeContact(1, 2, 7), s);
  anchors.Commit();
  AnchorState found;
  ASSERT_TRUE(anchors.Find(MakeContact(1, 2, 7), &found));
  EXPECT_EQ(found.stretch, s.stretch);
  ASSERT_TRUE(anchors.Find(MakeContact(2, 1, 7), &found));
  EXPECT_EQ(found.stretch, Vec3(-s.stretch));
  EXPECT_FALSE(anchors.Find(MakeContact(1, 2, 8), &found));
  EXPECT_FALSE(anchors.Find(MakeContact(1, 3, 7), &found));
}

// Verifies that Commit drops the anchors not kept this step, and Clear all.
TEST(PenaltyFriction, CommitDropsAnchorsOfVanishedContacts) {
  FrictionAnchors anchors;
  anchors.Keep(MakeContact(1, 2, 1), AnchorState());
  anchors.Keep(MakeContact(1, 2, 2), AnchorState());
  anchors.Commit();
  EXPECT_EQ(anchors.size(), 2u);
  anchors.Keep(MakeContact(2, 1, 2), AnchorState());
  anchors.Commit();
  EXPECT_EQ(anchors.size(), 1u);
  AnchorState found;
  EXPECT_TRUE(anchors.Find(MakeContact(1, 2, 2), &found));
  anchors.Clear();
  EXPECT_EQ(anchors.size(), 0u);
}

// Verifies the Coulomb disk: inside, the force is kept (sticking); outside,
// it is scaled onto the disk along its own direction (sliding).
TEST(PenaltyFriction, CoulombLimitKeepsOrScalesOntoTheDisk) {
  bool sliding = true;
  EXPECT_EQ(CoulombLimit(Vec3(3, 4, 0), 5.0, &sliding), Vec3(3, 4, 0));
  EXPECT_FALSE(sliding);
  const Vec3 f = CoulombLimit(Vec3(3, 4, 0), 2.5, &sliding);
  EXPECT_TRUE(sliding);
  EXPECT_NEAR((f - Vec3(1.5, 2, 0)).norm(), 0.0, 1e-15);
  EXPECT_EQ(CoulombLimit(Vec3(1, 0, 0), 0.0, &sliding), Vec3::Zero());
}

// Verifies that a stretch moved onto a turned tangent plane keeps its length
// and loses its normal part.
TEST(PenaltyFriction, ProjectStretchKeepsLength) {
  const Vec3 n = Vec3(0.1, 0, 1).normalized();
  const Vec3 s = ProjectStretch(Vec3(2e-3, 1e-3, 0), n);
  EXPECT_NEAR(s.dot(n), 0.0, 1e-18);
  EXPECT_NEAR(s.norm(), Vec3(2e-3, 1e-3, 0).norm(), 1e-18);
  EXPECT_EQ(ProjectStretch(Vec3(0, 0, 1e-3), Vec3::UnitZ()), Vec3::Zero());
}

}  // namespace
}  // namespace contactsim
