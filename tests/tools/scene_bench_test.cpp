// Tests of contactsim-bench's scene mode, run as a program: the JSON it
// prints and the physics it measures (the bounce's first apex against the
// analytic e^2 h); and of the metrics' failure detection. No timing is
// asserted.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "bench/tools/scene_bench/scene_metrics.h"
#include "service/collision/height_field.h"
#include "service/physics/body_settings.h"

namespace contactsim::bench {
namespace {

struct Output {
  int exit_code = -1;
  std::string out;
};

// stderr is dropped unless `with_stderr`, which appends it to out.
Output RunBench(const std::string& args, bool with_stderr = false) {
  const std::string cmd =
      std::string(CONTACTSIM_BIN_DIR) + "/contactsim-bench " + args + (with_stderr ? " 2>&1" : " 2>/dev/null");
  Output o;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return o;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) o.out.append(buf, n);
  const int status = pclose(pipe);
  o.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return o;
}

std::string Scene(const char* name) { return std::string(CONTACTSIM_SOURCE_DIR) + "/config/scenes/" + name; }

// The text after "key": up to the next top-level ',' or '}' (values here
// are numbers, strings without commas, null or a flat object).
std::string Field(const std::string& json, const std::string& key) {
  const std::string tag = "\"" + key + "\": ";
  const size_t at = json.find(tag);
  if (at == std::string::npos) return "";
  const size_t start = at + tag.size();
  const size_t end = json[start] == '{' ? json.find('}', start) + 1 : json.find_first_of(",}", start);
  return json.substr(start, end - start);
}

double Number(const std::string& json, const std::string& key) {
  const std::string v = Field(json, key);
  return v.empty() || v == "null" ? std::numeric_limits<double>::quiet_NaN() : std::stod(v);
}

// Verifies that --json prints every field the issue lists, and that the
// bounce scene's first apex under the impulse method is within 2% of the
// analytic e^2 h = 0.5^2 * 0.9 m = 0.225 m.
TEST(SceneBench, BounceJsonHasEveryFieldAndTheAnalyticApex) {
  const Output o = RunBench("--scene " + Scene("bounce.pbtxt") + " --method impulse --repeat 1 --json");
  ASSERT_EQ(o.exit_code, 0) << o.out;
  for (const char* key : {"scene", "method", "params", "bodies", "steps", "dt", "ms_per_step", "ms_per_step_min",
                          "ms_per_step_max", "max_penetration", "min_distance", "final_kinetic_energy", "top_displacement",
                          "rebound_height", "fell_through", "peak_rss_mb"}) {
    EXPECT_FALSE(Field(o.out, key).empty()) << key << " missing in " << o.out;
  }
  EXPECT_EQ(Field(o.out, "scene"), "\"bounce\"");
  EXPECT_EQ(Field(o.out, "method"), "\"impulse\"");
  EXPECT_NE(Field(o.out, "params").find("\"iterations\""), std::string::npos) << o.out;
  EXPECT_EQ(Number(o.out, "bodies"), 2);
  EXPECT_EQ(Number(o.out, "steps"), 480);
  EXPECT_DOUBLE_EQ(Number(o.out, "dt"), 1.0 / 240.0);
  EXPECT_EQ(Field(o.out, "top_displacement"), "null");  // no body "top"
  EXPECT_EQ(Field(o.out, "status"), "\"ok\"");
  EXPECT_GT(Number(o.out, "ms_per_step"), 0.0);
  EXPECT_LE(Number(o.out, "ms_per_step_min"), Number(o.out, "ms_per_step"));
  EXPECT_GT(Number(o.out, "peak_rss_mb"), 0.0);
  const double apex = 0.5 * 0.5 * 0.9;  // m, e^2 h
  EXPECT_NEAR(Number(o.out, "rebound_height"), apex, 0.02 * apex) << o.out;
  // the ball touched the plane: its closest approach is the deepest contact
  EXPECT_GT(Number(o.out, "max_penetration"), 0.0) << o.out;
  EXPECT_DOUBLE_EQ(Number(o.out, "min_distance"), -Number(o.out, "max_penetration")) << o.out;
}

// The bounce scene with restitution 0, in the test's temporary folder: the
// barrier method simulates no restitution and refuses the bouncy one
// (service/contact/method_contract.h).
std::string InelasticBounce() {
  const std::string path = ::testing::TempDir() + "/bounce_inelastic.pbtxt";
  std::ofstream out(path);
  out << "gravity { z: -9.81 }\ndt: 0.004166666666666667\nsteps: 480\n"
         "default_material { restitution: 0 friction: 0.5 }\n"
         "bodies { name: \"ground\" plane { normal { z: 1 } offset: 0 } }\n"
         "bodies { name: \"ball\" sphere { radius: 0.1 } position { z: 1.0 } density: 1000 }\n";
  return path;
}

// Verifies that the method's own report reaches the JSON: the barrier
// method's Newton iterations and stiffness, and its smallest distance, which
// for a sphere over a plane is the exact distance the metrics measure too.
TEST(SceneBench, BarrierBounceJsonHasTheMethodsReport) {
  const Output o = RunBench("--scene " + InelasticBounce() + " --method barrier --repeat 1 --json");
  ASSERT_EQ(o.exit_code, 0) << o.out;
  EXPECT_GE(Number(o.out, "iterations_mean"), 1.0) << o.out;
  EXPECT_GE(Number(o.out, "iterations_max"), Number(o.out, "iterations_mean")) << o.out;
  EXPECT_GT(Number(o.out, "stiffness_max"), 0.0) << o.out;
  EXPECT_GT(Number(o.out, "residual_min"), 0.0) << o.out;
  EXPECT_NEAR(Number(o.out, "residual_min"), Number(o.out, "min_distance"), 1e-12) << o.out;
}

// Verifies that a method is refused a scene it cannot honour, with the
// reason: barrier on the bouncy scene (restitution 0.5) exits 1.
TEST(SceneBench, BarrierRefusesTheBouncyScene) {
  const Output o = RunBench("--scene " + Scene("bounce.pbtxt") + " --method barrier --repeat 1 --json");
  EXPECT_EQ(o.exit_code, 1) << o.out;
  EXPECT_NE(o.out.find("does not simulate restitution"), std::string::npos) << o.out;
}

// Verifies that an unknown method exits 1 with a JSON status naming it and
// the known methods.
TEST(SceneBench, UnknownMethodIsAnErrorNamingIt) {
  const Output o = RunBench("--scene " + Scene("bounce.pbtxt") + " --method nosuch --repeat 1 --json");
  EXPECT_EQ(o.exit_code, 1);
  EXPECT_NE(o.out.find("\"status\": \"error: unknown contact method \\\"nosuch\\\""), std::string::npos) << o.out;
  EXPECT_NE(o.out.find("impulse"), std::string::npos) << o.out;
}

World OneBall() {
  World world;
  BodySettings s;
  s.name = "ball";
  s.radius = 0.1;
  s.position = Vec3(0, 0, 1);
  RigidBody b;
  EXPECT_TRUE(CreateBody(s, Material{}, &b).ok());
  world.AddBody(b);
  return world;
}

// Verifies that the metrics call a non-finite state "nan" and a body far
// from its start "exploded", naming the body, and a sane state healthy.
TEST(SceneBench, MetricsReportNanAndExplosion) {
  World world = OneBall();
  SceneMetrics metrics;
  metrics.Start(world);
  EXPECT_EQ(metrics.Check(world), "");
  world.bodies()[0].x.z() = 1.0 + 2.0 * kEscapeDistance;
  EXPECT_EQ(metrics.Check(world).rfind("exploded: \"ball\"", 0), 0u) << metrics.Check(world);
  world.bodies()[0].P.x() = std::nan("");
  EXPECT_EQ(metrics.Check(world).rfind("nan: \"ball\"", 0), 0u) << metrics.Check(world);
}

// Verifies the fell-through count: none without a surface; a ball whose
// centre goes below a heightfield (a 1 m grid tilted to z = 0.1 x) is
// counted once, and stays counted after it comes back up; one beside the
// surface is not.
TEST(SceneBench, MetricsCountBodiesBelowASurfaceOnce) {
  World bare = OneBall();
  SceneMetrics none;
  none.Start(bare);
  none.Observe(bare);
  EXPECT_FALSE(none.fell_through().has_value());

  World world;
  BodySettings ground;
  ground.name = "ground";
  ground.shape = ShapeType::kHeightfield;
  std::vector<double> heights;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) heights.push_back(0.1 * (c - 1));
  }
  ASSERT_TRUE(BuildHeightField(3, 3, heights, 1.0, 1.0, &ground.heightfield).ok());
  RigidBody g;
  ASSERT_TRUE(CreateBody(ground, Material{}, &g).ok());
  world.AddBody(g);
  for (const double x : {0.5, 3.0}) {  // over the surface, and beside it
    BodySettings s;
    s.radius = 0.1;
    s.position = Vec3(x, 0.3, 1);  // inside a cell's half, off its edges
    RigidBody b;
    ASSERT_TRUE(CreateBody(s, Material{}, &b).ok());
    world.AddBody(b);
  }
  SceneMetrics metrics;
  metrics.Start(world);
  metrics.Observe(world);
  EXPECT_EQ(metrics.fell_through(), 0);
  world.bodies()[1].x.z() = 0.05 - 1e-6;  // the surface is at 0.1 x = 0.05 under it
  world.bodies()[2].x.z() = -5.0;
  metrics.Observe(world);
  EXPECT_EQ(metrics.fell_through(), 1);
  world.bodies()[1].x.z() = 0.05 + 1e-6;
  metrics.Observe(world);
  EXPECT_EQ(metrics.fell_through(), 1);
}

// Verifies that --threads reaches the report and that zero, negative and
// absurd counts are refused with a message naming the value.
TEST(SceneBench, ThreadsAreReportedAndBadCountsRefused) {
  const Output o = RunBench("--scene " + Scene("bounce.pbtxt") + " --method impulse --steps 10 --repeat 1 --threads 2 --json");
  ASSERT_EQ(o.exit_code, 0) << o.out;
  EXPECT_EQ(Number(o.out, "threads"), 2) << o.out;
  for (const std::string value : {"0", "-1", "100000"}) {
    const Output bad = RunBench("--scene " + Scene("bounce.pbtxt") + " --method impulse --threads " + value, true);
    EXPECT_EQ(bad.exit_code, 1) << value;
    EXPECT_NE(bad.out.find("--threads: threads must be between 1 and 256, got " + value), std::string::npos) << bad.out;
  }
}

// Verifies that sleeping is off unless --sleep is given (benchmarks time
// the solver), and that with --sleep a ball resting after its bounces
// sleeps by the end of 10 s and the report says so.
TEST(SceneBench, SleepIsOffUnlessAskedAndReported) {
  const std::string run = "--scene " + Scene("bounce.pbtxt") + " --method impulse --steps 2400 --repeat 1 --json";
  const Output off = RunBench(run);
  ASSERT_EQ(off.exit_code, 0) << off.out;
  EXPECT_NE(off.out.find("\"sleep\": false"), std::string::npos) << off.out;
  EXPECT_EQ(Number(off.out, "sleeping"), 0) << off.out;
  const Output on = RunBench(run + " --sleep");
  ASSERT_EQ(on.exit_code, 0) << on.out;
  EXPECT_NE(on.out.find("\"sleep\": true"), std::string::npos) << on.out;
  EXPECT_EQ(Number(on.out, "sleeping"), 1) << on.out;
}

// Verifies that manifold reuse is on unless --no-manifold-reuse is given,
// as in the server, that the report says which, and that on a box
// pyramid the two runs differ only in round-off (the same bodies resting,
// penetration within a tenth of the 1 mm slop of each other).
TEST(SceneBench, ManifoldReuseIsOnUnlessTurnedOffAndReported) {
  const std::string run = "--scene " + Scene("box_pyramid.pbtxt") + " --method impulse --steps 120 --repeat 1 --json";
  const Output on = RunBench(run);
  ASSERT_EQ(on.exit_code, 0) << on.out;
  EXPECT_NE(on.out.find("\"manifold_reuse\": true"), std::string::npos) << on.out;
  const Output off = RunBench(run + " --no-manifold-reuse");
  ASSERT_EQ(off.exit_code, 0) << off.out;
  EXPECT_NE(off.out.find("\"manifold_reuse\": false"), std::string::npos) << off.out;
  EXPECT_NEAR(Number(on.out, "max_penetration"), Number(off.out, "max_penetration"), 1e-4);
  // the flag alone: one step says which
  const Output again = RunBench("--scene " + Scene("box_pyramid.pbtxt") +
                                " --method impulse --steps 1 --repeat 1 --json --manifold-reuse");
  EXPECT_NE(again.out.find("\"manifold_reuse\": true"), std::string::npos) << again.out;
}

}  // namespace
}  // namespace contactsim::bench
