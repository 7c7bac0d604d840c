// Tests of the float path's prepare kernel (soft_wide_prepare_impl.h): the
// rows, effective masses and K^-1 it computes in float over the lanes
// agree with the double path's (PrepareSoftRows, InvertNormalBlock) to float's round-off, take
// the block solve where the double path does and K is well conditioned,
// and come out the same bit for bit at every width.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "service/collision/parallel_runner.h"
#include "service/contact/soft/soft_manifold.h"
#include "service/contact/soft/wide/soft_wide_bundles.h"
#include "service/contact/soft/wide/soft_wide_kernels.h"

namespace contactsim {
namespace {

// A manifold's points in its contact plane (tangent coordinates, m), and
// whether the double path block-solves it.
struct Shape {
  const char* name;
  std::vector<std::pair<double, double>> uv;
};
const Shape kShapes[] = {
    {"one point", {{0.1, 0.2}}},
    {"edge", {{-0.5, 0.0}, {0.5, 0.0}}},
    {"triangle", {{-0.4, -0.3}, {0.5, -0.2}, {0.0, 0.45}}},
    {"square face", {{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}},
    {"long face", {{-1.5, -0.1}, {1.5, -0.1}, {1.5, 0.1}, {-1.5, 0.1}}},
    {"three in line", {{-0.5, 0.0}, {0.0, 0.0}, {0.5, 0.0}}},
    {"four in line", {{-0.5, 0.0}, {-0.1, 0.0}, {0.2, 0.0}, {0.5, 0.0}}},
    {"skewed face", {{-0.3, -0.5}, {0.6, -0.4}, {0.4, 0.5}, {-0.5, 0.3}}},
};

struct Scene {
  std::vector<SoftBody> bodies;
  std::vector<SoftPoint> points;
  std::vector<SoftManifold> manifolds;
  BlockColours colours;
};

Mat3 RandomRotation(std::mt19937& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  return q.normalized().toRotationMatrix();
}

// Every shape between two dynamic bodies and against a static one, at
// random poses, masses and inertias; one colour (every manifold its own bodies).
Scene MakeScene(int repeats) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> mass(0.2, 20.0), ratio(0.3, 1.0), offset(-2.0, 2.0);
  Scene s;
  for (int r = 0; r < repeats; ++r) {
    for (const Shape& shape : kShapes) {
      for (const bool fixed_b : {false, true}) {
        const int a = static_cast<int>(s.bodies.size());
        for (int i = 0; i < 2; ++i) {
          SoftBody body;
          const bool fixed = i == 1 && fixed_b;
          if (!fixed) {
            const Mat3 R = RandomRotation(rng);
            const double m = mass(rng);
            body.inv_mass = 1.0 / m;
            const Vec3 inv_i(ratio(rng) / m, ratio(rng) / m, ratio(rng) / m);
            body.inv_inertia = R * inv_i.asDiagonal() * R.transpose();
          }
          s.bodies.push_back(body);
        }
        const Mat3 frame = RandomRotation(rng);
        const Vec3 n = frame.col(2), t1 = frame.col(0), t2 = frame.col(1);
        const Vec3 centre(offset(rng), offset(rng), offset(rng));
        const Vec3 ca = centre - 0.5 * n + Vec3(0.1, -0.2, 0.05), cb = centre + 0.7 * n;
        s.manifolds.push_back(SoftManifold{static_cast<int>(s.points.size()), static_cast<int>(shape.uv.size()),
                                           false, Eigen::Matrix4d::Zero()});
        for (const auto& [u, v] : shape.uv) {
          SoftPoint p;  // its rows: PrepareSoftRows below
          p.ra_t1 = p.ra_t2 = p.rb_t1 = p.rb_t2 = Vec3::Zero();
          p.ia_t1 = p.ia_t2 = p.ib_t1 = p.ib_t2 = Vec3::Zero();
          p.a = a, p.b = a + 1;
          p.n = n, p.t1 = t1, p.t2 = t2;
          const Vec3 point = centre + u * t1 + v * t2;
          p.ra = point - ca, p.rb = point - cb;
          s.points.push_back(p);
        }
      }
    }
  }
  s.colours.starts = {0, static_cast<int>(s.manifolds.size())};
  return s;
}

// The prepared bundles' floats, at `kernels`' width.
std::vector<float> Prepare(const Scene& scene, const wide::WideKernels& kernels, WideBundles* bundles) {
  const int dummy = static_cast<int>(scene.bodies.size());
  std::vector<float> inertia(9 * (scene.bodies.size() + 1), 0.0f);
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    Eigen::Map<Eigen::Matrix3f> column_major(&inertia[9 * i]);
    column_major = scene.bodies[i].inv_inertia.cast<float>();
  }
  bundles->Pack(scene.points, scene.manifolds, scene.colours, scene.bodies, nullptr, kernels.width, dummy);
  std::vector<wide::WideBody> state(scene.bodies.size() + 1);
  wide::WideView view = bundles->View(state.data());
  view.inv_inertia = inertia.data();
  view.inertia_stride = 9;
  kernels.prepare(view, 0, bundles->bundles());
  std::vector<float> fields;
  for (int k = 0; k < static_cast<int>(scene.manifolds.size()); ++k) {
    const float* base = view.data + view.offsets[k / kernels.width] + k % kernels.width;
    for (int f = 0; f < wide::BundleFields(scene.manifolds[k].count); ++f) fields.push_back(base[f * kernels.width]);
  }
  return fields;
}

std::vector<const wide::WideKernels*> Widths() {
  std::vector<const wide::WideKernels*> widths = {&wide::BaseKernels()};
  const wide::WideKernels& widest = wide::ChooseKernels(0);
  if (widest.width != widths[0]->width) widths.push_back(&widest);
  return widths;
}

// float's round-off of a row computed from values of order 1 (m, 1/kg)
constexpr double kRowTolerance = 2e-6;
// K^-1's: its round-off, amplified by K's condition (at most 1e3 where
// the block solve applies), relative to K^-1's largest entry
constexpr double kInverseTolerance = 2e-4;

void ExpectNear3(const Vec3& expected, const float* base, int field, int width, double scale, const char* what) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(base[(field + k) * width], expected[k], kRowTolerance * scale) << what << "[" << k << "]";
  }
}

// Verifies every row and K^-1 against the double path's, at every width.
TEST(SoftWidePrepareTest, RowsAndInverseMatchTheDoublePath) {
  Scene scene = MakeScene(3);
  ParallelRunner runner(1);
  PrepareSoftRows(scene.bodies, nullptr, runner, &scene.points);
  std::vector<SoftManifold> reference = scene.manifolds;
  InvertSoftManifolds(scene.points, runner, &reference);
  for (const wide::WideKernels* kernels : Widths()) {
    WideBundles bundles;
    Prepare(scene, *kernels, &bundles);
    const int width = kernels->width;
    const wide::WideView view = bundles.View(nullptr);
    for (size_t k = 0; k < scene.manifolds.size(); ++k) {
      const SoftManifold& m = reference[k];
      const Shape& shape = kShapes[(k / 2) % std::size(kShapes)];
      SCOPED_TRACE(testing::Message() << shape.name << " (manifold " << k << ") at " << width << " lanes");
      const float* base = view.data + view.offsets[k / width] + k % width;
      for (int s = 0; s < m.count; ++s) {
        const SoftPoint& p = scene.points[m.first + s];
        const auto at = [s](int field) { return wide::SlotAt(s, field); };
        ExpectNear3(p.ra_n, base, at(wide::kRaN), width, 1.0, "ra_n");
        ExpectNear3(p.rb_n, base, at(wide::kRbN), width, 1.0, "rb_n");
        ExpectNear3(p.ia_n, base, at(wide::kIaN), width, 1.0, "ia_n");
        ExpectNear3(p.ib_t2, base, at(wide::kIbT2), width, 1.0, "ib_t2");
        ExpectNear3(p.ra_t1, base, at(wide::kRaT1), width, 1.0, "ra_t1");
        EXPECT_NEAR(base[at(wide::kMassN) * width], p.mass_n, kRowTolerance * 4.0 * p.mass_n);
        EXPECT_NEAR(base[at(wide::kMassT1) * width], p.mass_t1, kRowTolerance * 4.0 * p.mass_t1);
        EXPECT_NEAR(base[at(wide::kMassT2) * width], p.mass_t2, kRowTolerance * 4.0 * p.mass_t2);
        EXPECT_NEAR(base[at(wide::kKT12) * width], p.k_t12, kRowTolerance);
      }
      // the bundle's slots past the lane's points push nothing
      for (int s = m.count; s < view.slots[k / width]; ++s) {
        for (const int field : {wide::kMassN, wide::kMassT1, wide::kMassT2}) {
          EXPECT_EQ(base[wide::SlotAt(s, field) * width], 0.0f) << "slot " << s << " field " << field;
        }
      }
      const bool block = base[wide::kBlock * width] > 0.0f;
      double k_max = 0.0;
      for (int i = 0; i < m.count; ++i) k_max = std::max(k_max, 1.0 / scene.points[m.first + i].mass_n);
      const double inv_max = m.inv_k.cwiseAbs().maxCoeff();
      // the float block: where the double path inverts and K is well conditioned
      EXPECT_EQ(block, m.block && k_max * inv_max <= 1e3) << "condition " << k_max * inv_max;
      if (!block) continue;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          const double got = i < m.count && j < m.count ? base[(wide::kInvK + 4 * i + j) * width] : 0.0;
          EXPECT_NEAR(got, m.inv_k(i, j), kInverseTolerance * inv_max) << "K^-1(" << i << ", " << j << ")";
        }
      }
    }
  }
}

// Verifies that every shape the double path block-solves takes the block
// solve in float too (these are all well conditioned), and the lines do not.
TEST(SoftWidePrepareTest, BlocksTheFacesEdgesAndTrianglesNotTheLines) {
  Scene scene = MakeScene(1);
  WideBundles bundles;
  Prepare(scene, wide::BaseKernels(), &bundles);
  const int width = wide::BaseKernels().width;
  const wide::WideView view = bundles.View(nullptr);
  for (size_t k = 0; k < scene.manifolds.size(); ++k) {
    const Shape& shape = kShapes[(k / 2) % std::size(kShapes)];
    const std::string name = shape.name;
    const bool expected = shape.uv.size() >= 2 && name.find("line") == std::string::npos;
    const float* base = view.data + view.offsets[k / width] + k % width;
    EXPECT_EQ(base[wide::kBlock * width] > 0.0f, expected) << name << " (manifold " << k << ")";
  }
}

// Verifies that the prepared bundles are the same bit for bit at 4 and 8
// lanes (every lane is its own manifold's arithmetic).
TEST(SoftWidePrepareTest, SameBitsAtEveryWidth) {
  const std::vector<const wide::WideKernels*> widths = Widths();
  if (widths.size() < 2) GTEST_SKIP() << "one width on this processor";
  const Scene scene = MakeScene(3);
  WideBundles narrow, wide_bundles;
  const std::vector<float> a = Prepare(scene, *widths[0], &narrow);
  const std::vector<float> b = Prepare(scene, *widths[1], &wide_bundles);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(std::memcmp(&a[i], &b[i], sizeof(float)), 0) << "float " << i << ": " << a[i] << " against " << b[i];
  }
}

}  // namespace
}  // namespace contactsim
