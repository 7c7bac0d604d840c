// Runs a scene file under one contact method configuration and returns the
// world hash at the end: shared by the determinism tests (pinned hashes
// across builds, equal hashes across thread counts).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "service/collision/manifold_cache.h"
#include "service/contact/contact_method.h"
#include "service/scene/scene_spec.h"

namespace contactsim {
namespace testing_util {

struct SceneRun {
  std::string scene;   // file name under config/scenes/
  std::string method;  // registered contact method
  ParamMap params;     // over the method's defaults
  int steps = 0;       // 0: the scene's own `steps`
  int threads = 1;     // of the collision detector
  bool manifold_reuse = kManifoldReuseDefault;  // the detector's (manifold_cache.h)
};

inline std::string Describe(const std::string& method, const ParamMap& params) {
  std::string s = method;
  for (const auto& [k, v] : params) s += " " + k + "=" + v;
  return s;
}

struct SceneRunResult {
  uint64_t hash = 0;        // HashWorldState at the end
  int64_t detections = 0;   // the method's calls of the collision detector
};

// The world at the end of the run's steps; a failed load or set-up fails
// the calling test and returns a zero hash.
inline SceneRunResult RunSceneOnce(const SceneRun& run) {
  SceneSpec spec;
  World world;
  Status st = LoadSceneFile(std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/" + run.scene, &spec);
  EXPECT_TRUE(st.ok()) << st.message();
  st = BuildWorld(spec, &world);
  EXPECT_TRUE(st.ok()) << st.message();
  std::unique_ptr<ContactMethod> method;
  st = CreateContactMethod(run.method, &method);
  EXPECT_TRUE(st.ok()) << st.message();
  if (!st.ok()) return {};
  st = method->SetParams(run.params);
  EXPECT_TRUE(st.ok()) << st.message();
  CollisionDetector detector;
  st = detector.SetThreads(run.threads);
  EXPECT_TRUE(st.ok()) << st.message();
  detector.SetManifoldReuse(run.manifold_reuse);
  ContactSet contacts;
  const int steps = run.steps > 0 ? run.steps : spec.steps;
  EXPECT_GT(steps, 0);
  for (int i = 0; i < steps; ++i) method->Step(world, detector, &contacts);
  EXPECT_EQ(world.step, steps);
  EXPECT_TRUE(std::isfinite(KineticEnergy(world)));
  return {HashWorldState(world), detector.stats().detections};
}

inline uint64_t RunSceneHash(const SceneRun& run) { return RunSceneOnce(run).hash; }

// A new registered method by name; a failed creation fails the calling test.
inline std::shared_ptr<ContactMethod> NewMethod(const std::string& name) {
  std::unique_ptr<ContactMethod> m;
  EXPECT_TRUE(CreateContactMethod(name, &m).ok()) << name;
  return std::shared_ptr<ContactMethod>(std::move(m));
}

// HashWorldState after each of `n` steps of `method` with `detector`.
inline std::vector<uint64_t> StepHashes(World& w, ContactMethod& method, CollisionDetector& detector, int n) {
  ContactSet contacts;
  std::vector<uint64_t> hashes;
  for (int i = 0; i < n; ++i) {
    method.Step(w, detector, &contacts);
    hashes.push_back(HashWorldState(w));
  }
  return hashes;
}

}  // namespace testing_util
}  // namespace contactsim
