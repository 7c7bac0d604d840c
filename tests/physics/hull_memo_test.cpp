#include "service/physics/hull_memo.h"

#include <gtest/gtest.h>

#include "service/physics/hull_vertex_budget.h"
#include "tests/physics/point_clouds.h"

namespace contactsim {
namespace {

// Verifies that a remembered budget and hull are the ones a new computation
// gives, bit for bit, that the same points share one built hull, and that
// other points (another budget, a moved point, -0.0 for 0.0) are computed
// anew.
TEST(HullMemoTest, GivesWhatANewComputationGivesAndSharesEqualPoints) {
  const std::vector<Vec3> cloud = EllipsoidPoints(300, Vec3(0.05, 0.08, 0.2));
  HullMemo memo;
  for (int budget : {16, 64, 16}) {
    std::vector<Vec3> kept, direct;
    ASSERT_TRUE(memo.BudgetedPoints(cloud, budget, &kept).ok());
    ASSERT_TRUE(BudgetedHullPoints(cloud, budget, &direct).ok());
    EXPECT_EQ(kept, direct) << "budget " << budget;
  }
  std::shared_ptr<const ConvexHull> a, b, direct;
  Vec3 ca, cb, cdirect;
  ASSERT_TRUE(memo.Hull(cloud, &a, &ca).ok());
  ASSERT_TRUE(memo.Hull(cloud, &b, &cb).ok());
  ASSERT_TRUE(BuildConvexHull(cloud, &direct, &cdirect).ok());
  EXPECT_EQ(a, b);
  EXPECT_EQ(ca, cdirect);
  EXPECT_EQ(a->vertices, direct->vertices);
  ASSERT_EQ(a->faces.size(), direct->faces.size());
  for (size_t f = 0; f < a->faces.size(); ++f) {
    EXPECT_EQ(a->faces[f].vertices, direct->faces[f].vertices);
    EXPECT_EQ(a->faces[f].normal, direct->faces[f].normal);
  }
  std::vector<Vec3> moved = cloud;
  moved[7].x() += 1e-3;
  std::shared_ptr<const ConvexHull> c;
  ASSERT_TRUE(memo.Hull(moved, &c, &cb).ok());
  EXPECT_NE(c, a);
  // a box with a corner at -0.0: a hull may keep the sign, so it is a key of its own
  std::vector<Vec3> box, signed_box;
  for (int i = 0; i < 8; ++i) box.emplace_back((i & 1) ? 1.0 : 0.0, (i & 2) ? 1.0 : 0.0, (i & 4) ? 1.0 : 0.0);
  signed_box = box;
  signed_box[0].x() = -0.0;
  std::shared_ptr<const ConvexHull> d, e;
  ASSERT_TRUE(memo.Hull(box, &d, &ca).ok());
  ASSERT_TRUE(memo.Hull(signed_box, &e, &cb).ok());
  EXPECT_NE(d, e);
}

// Verifies that a failure is reported as BuildConvexHull reports it and not
// remembered as a hull.
TEST(HullMemoTest, PassesFailuresOn) {
  HullMemo memo;
  std::vector<Vec3> flat;
  for (int i = 0; i < 20; ++i) flat.emplace_back(std::cos(i), std::sin(i), 0.0);
  std::shared_ptr<const ConvexHull> hull;
  Vec3 centroid;
  const Status st = memo.Hull(flat, &hull, &centroid);
  EXPECT_FALSE(st.ok());
  EXPECT_EQ(st.message(), BuildConvexHull(flat, &hull, &centroid).message());
  std::vector<Vec3> kept;
  EXPECT_FALSE(memo.BudgetedPoints(flat, 64, &kept).ok());
}

}  // namespace
}  // namespace contactsim
