// The contact report on request (ContactMethod::RequestContactReport,
// contact_method.h): a caller that reads no contact values (the scene
// bench) turns it off, and the step must be the same bit for bit; the
// contacts then still name each pair's points, as island sleep reads them,
// and a step with the report on again reports as before.
#include <gtest/gtest.h>

#include "tests/scene/scene_run_util.h"

namespace contactsim {
namespace {

struct Stepper {
  World world;
  std::shared_ptr<ContactMethod> method;
  CollisionDetector detector;
  ContactSet contacts;
  StepStats stats;

  Stepper(const World& w, const ParamMap& params) : world(w), method(testing_util::NewMethod("soft")) {
    EXPECT_TRUE(method->SetParams(params).ok());
  }
  void Step() { stats = method->Step(world, detector, &contacts); }
};

World Pyramid() {
  SceneSpec spec;
  World world;
  EXPECT_TRUE(LoadSceneFile(std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/box_pyramid.pbtxt", &spec).ok());
  EXPECT_TRUE(BuildWorld(spec, &world).ok());
  return world;
}

// Verifies, on the float and the double path, that the steps without the
// report are those with it, bit for bit, and the contacts the same pairs'
// points; then that the report, asked for again, is the reporting run's.
TEST(ContactReportTest, SkippedReportLeavesTheStepsAsTheyWere) {
  const World world = Pyramid();
  for (const char* precision : {"float", "double"}) {
    Stepper reported(world, {{"precision", precision}});
    Stepper silent(world, {{"precision", precision}});
    silent.method->RequestContactReport(false);
    for (int step = 0; step < 24; ++step) {
      reported.Step();
      silent.Step();
      ASSERT_EQ(HashWorldState(silent.world), HashWorldState(reported.world)) << precision << " step " << step;
      ASSERT_EQ(silent.contacts.size(), reported.contacts.size()) << precision << " step " << step;
      EXPECT_EQ(silent.stats.contacts, reported.stats.contacts);
      EXPECT_EQ(silent.stats.iterations, reported.stats.iterations);
      for (size_t k = 0; k < silent.contacts.size(); ++k) {
        const Contact& s = silent.contacts[k];
        const Contact& r = reported.contacts[k];
        EXPECT_TRUE(s.a == r.a && s.b == r.b && s.feature_id == r.feature_id && s.point == r.point)
            << precision << " step " << step << " contact " << k;
        EXPECT_EQ(s.normal_value, 0.0);
      }
    }
    EXPECT_GT(reported.stats.max_penetration, 0.0) << precision;
    silent.method->RequestContactReport(true);
    reported.Step();
    silent.Step();
    ASSERT_EQ(silent.contacts.size(), reported.contacts.size());
    EXPECT_EQ(silent.stats.max_penetration, reported.stats.max_penetration) << precision;
    for (size_t k = 0; k < silent.contacts.size(); ++k) {
      EXPECT_EQ(silent.contacts[k].depth, reported.contacts[k].depth) << precision << " contact " << k;
      EXPECT_EQ(silent.contacts[k].normal_value, reported.contacts[k].normal_value) << precision << " contact " << k;
      EXPECT_EQ(silent.contacts[k].tangent_value, reported.contacts[k].tangent_value) << precision << " contact " << k;
    }
  }
}

}  // namespace
}  // namespace contactsim
