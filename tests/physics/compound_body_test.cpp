// Tests of compound bodies and explicit mass properties (body_settings.h,
// body_shape.h, mass_properties.h) against hand-computed answers.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "service/physics/body_settings.h"
#include "service/physics/convex_hull.h"
#include "service/physics/mass_properties.h"

namespace contactsim {
namespace {

constexpr double kTol = 1e-12;  // closed forms and sums: only round-off

ShapePart BoxPart(const Vec3& half, const Vec3& position, const Quat& orientation = Quat::Identity()) {
  ShapePart p;
  p.type = ShapeType::kBox;
  p.half_extents = half;
  p.position = position;
  p.orientation = orientation;
  return p;
}

ShapePart SpherePart(double radius, const Vec3& position) {
  ShapePart p;
  p.type = ShapeType::kSphere;
  p.radius = radius;
  p.position = position;
  return p;
}

BodySettings Compound(std::vector<ShapePart> parts) {
  BodySettings s;
  s.shape = ShapeType::kCompound;
  s.parts = std::move(parts);
  return s;
}

RigidBody Build(const BodySettings& s) {
  RigidBody b;
  const Status st = CreateBody(s, Material{}, &b);
  EXPECT_TRUE(st.ok()) << st.message();
  return b;
}

// Verifies two equal cubes side by side: m = 2 rho 8 a^3, the centre of mass
// midway, I_xx = 2 m_1 (2 a^2) / 3 and I_yy = I_zz = 2 (m_1 (2 a^2) / 3 + m_1 a^2)
// (each cube a = 0.1 m from the centre of mass along x), the body origin at
// the centre of mass and the frame's origin kept at -c.
TEST(CompoundBody, TwoCubesMatchHandComputedMassProperties) {
  const double a = 0.1;
  BodySettings s = Compound({BoxPart(Vec3::Constant(a), Vec3::Zero()), BoxPart(Vec3::Constant(a), Vec3(2 * a, 0, 0))});
  s.position = Vec3(1, 2, 3);
  const RigidBody b = Build(s);
  const double m1 = kDefaultDensity * 8 * a * a * a;
  EXPECT_NEAR(b.mass, 2 * m1, kTol * m1);
  const double ixx = 2 * m1 * 2 * a * a / 3, iyy = 2 * (m1 * 2 * a * a / 3 + m1 * a * a);
  EXPECT_TRUE(b.inertia_body.isApprox(Vec3(ixx, iyy, iyy).asDiagonal().toDenseMatrix(), kTol));
  EXPECT_TRUE(b.x.isApprox(Vec3(1 + a, 2, 3), kTol));
  EXPECT_TRUE(b.frame_origin.isApprox(Vec3(-a, 0, 0), kTol));
  ASSERT_EQ(b.shape.type, ShapeType::kCompound);
  EXPECT_TRUE(b.shape.compound->children[0].position.isApprox(Vec3(-a, 0, 0), kTol));
  EXPECT_TRUE(b.shape.compound->children[1].position.isApprox(Vec3(a, 0, 0), kTol));
}

// Verifies a box with a sphere above it, the sphere's centre 0.5 m up: the
// centre of mass at z_c = m_s 0.5 / (m_b + m_s), and the parallel-axis sum
// I_xx = m_b (b^2 + c^2) / 3 + m_b z_c^2 + 2/5 m_s r^2 + m_s (0.5 - z_c)^2.
TEST(CompoundBody, BoxAndOffsetSphereMatchParallelAxisTheorem) {
  const Vec3 h(0.1, 0.2, 0.3);
  const double r = 0.1, rho = 700.0;
  BodySettings s = Compound({BoxPart(h, Vec3::Zero()), SpherePart(r, Vec3(0, 0, 0.5))});
  s.density = rho;
  const RigidBody b = Build(s);
  const double mb = rho * 8 * h.prod(), ms = rho * 4.0 / 3.0 * kPi * r * r * r;
  const double zc = ms * 0.5 / (mb + ms);
  const double ixx = mb * (h.y() * h.y() + h.z() * h.z()) / 3 + mb * zc * zc + 0.4 * ms * r * r +
                     ms * (0.5 - zc) * (0.5 - zc);
  const double iyy = mb * (h.x() * h.x() + h.z() * h.z()) / 3 + mb * zc * zc + 0.4 * ms * r * r +
                     ms * (0.5 - zc) * (0.5 - zc);
  const double izz = mb * (h.x() * h.x() + h.y() * h.y()) / 3 + 0.4 * ms * r * r;
  EXPECT_NEAR(b.mass, mb + ms, kTol * (mb + ms));
  EXPECT_TRUE(b.inertia_body.isApprox(Vec3(ixx, iyy, izz).asDiagonal().toDenseMatrix(), kTol));
  EXPECT_TRUE(b.x.isApprox(Vec3(0, 0, zc), kTol));
  // the same with the mass given: everything scales by it
  s.density.reset();
  s.mass = 2.5;
  const RigidBody scaled = Build(s);
  EXPECT_TRUE(scaled.inertia_body.isApprox(b.inertia_body * (2.5 / (mb + ms)), kTol));
}

// Verifies that a turned part's inertia is turned into the body axes, with
// the products of inertia that brings: a box turned 30 degrees about z has
// I = R diag(I') R^T, whose I_xy is not zero; a quarter turn swaps two
// moments.
TEST(CompoundBody, TurnedPartGivesProductsOfInertia) {
  const Vec3 h(0.3, 0.1, 0.05);
  const Quat turn(Eigen::AngleAxisd(kPi / 6, Vec3::UnitZ()));
  const RigidBody b = Build(Compound({BoxPart(h, Vec3::Zero(), turn)}));
  const MassProperties own = ComputeMassProperties(Shape::Box(h), kDefaultDensity);
  const Mat3 R = turn.toRotationMatrix();
  EXPECT_TRUE(b.inertia_body.isApprox(R * own.inertia * R.transpose(), kTol));
  EXPECT_GT(std::abs(b.inertia_body(0, 1)), 1e-4 * own.inertia.norm());
  const Quat quarter(Eigen::AngleAxisd(kPi / 2, Vec3::UnitZ()));
  const RigidBody swapped = Build(Compound({BoxPart(h, Vec3::Zero(), quarter)}));
  const MassProperties other = ComputeMassProperties(Shape::Box(Vec3(h.y(), h.x(), h.z())), kDefaultDensity);
  EXPECT_TRUE(swapped.inertia_body.isApprox(other.inertia, 1e-12));
}

// Verifies that a compound of one child off the frame's origin is the same
// body as the plain shape placed at that pose: same centre of mass, world
// inertia, mass, and the frame's origin kept.
TEST(CompoundBody, OneOffsetChildEqualsPlainShapeAtItsPose) {
  const Vec3 h(0.2, 0.1, 0.05), p(0.3, -0.2, 0.1);
  const Quat turn(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()));
  const Quat frame(Eigen::AngleAxisd(-0.4, Vec3(0, 1, 1).normalized()));
  BodySettings c = Compound({BoxPart(h, p, turn)});
  c.position = Vec3(1, 0, 2);
  c.orientation = Eigen::Vector4d(frame.w(), frame.x(), frame.y(), frame.z());
  c.mass = 3.0;
  BodySettings plain;
  plain.shape = ShapeType::kBox;
  plain.half_extents = h;
  plain.mass = 3.0;
  plain.position = c.position + frame * p;
  const Quat q = frame * turn;
  plain.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  const RigidBody bc = Build(c), bp = Build(plain);
  EXPECT_TRUE(bc.x.isApprox(bp.x, kTol));
  EXPECT_NEAR(bc.mass, bp.mass, kTol);
  EXPECT_TRUE(bc.InertiaWorld().isApprox(bp.InertiaWorld(), 1e-12));
  EXPECT_TRUE((bc.x + bc.q * bc.frame_origin).isApprox(c.position, kTol));
  // a plain shape at its centre of mass stays plain: no indirection
  EXPECT_EQ(bp.shape.type, ShapeType::kBox);
  EXPECT_TRUE(bp.frame_origin.isZero(0.0));
}

// Verifies explicit mass properties: the inertia is taken as given (with
// products of inertia), the explicit centre of mass becomes the body origin
// and a plain shape off it a compound of one child; SetMass scales the
// explicit inertia instead of recomputing it from the shape.
TEST(CompoundBody, ExplicitMassPropertiesAreTakenAsGiven) {
  BodySettings s;
  s.shape = ShapeType::kBox;
  s.half_extents = Vec3(0.1, 0.1, 0.1);
  s.mass = 2.0;
  s.center_of_mass = Vec3(0.02, 0, -0.03);
  Mat3 I;
  I << 0.02, 0.001, -0.002, 0.001, 0.03, 0.0005, -0.002, 0.0005, 0.025;
  s.inertia = I;
  s.position = Vec3(0, 0, 1);
  RigidBody b = Build(s);
  EXPECT_TRUE(b.inertia_body.isApprox(I, kTol));
  EXPECT_TRUE(b.x.isApprox(Vec3(0.02, 0, 0.97), kTol));
  EXPECT_TRUE(b.frame_origin.isApprox(Vec3(-0.02, 0, 0.03), kTol));
  ASSERT_EQ(b.shape.type, ShapeType::kCompound);
  ASSERT_EQ(b.shape.compound->children.size(), 1u);
  EXPECT_TRUE(b.shape.compound->children[0].position.isApprox(Vec3(-0.02, 0, 0.03), kTol));
  b.SetMass(4.0);
  EXPECT_TRUE(b.inertia_body.isApprox(2.0 * I, kTol));
  // a centre of mass alone: the shape's inertia shifted to it
  s.inertia.reset();
  const RigidBody shifted = Build(s);
  const MassProperties own = ComputeMassProperties(Shape::Box(s.half_extents), 1.0);
  const Mat3 expected = ShiftInertia(own.inertia * (2.0 / own.mass), 2.0, Vec3(0.02, 0, -0.03));
  EXPECT_TRUE(shifted.inertia_body.isApprox(expected, kTol));
}

// Verifies the checks of an explicit inertia, with the text of each refusal.
TEST(CompoundBody, InertiaChecksNameTheProblem) {
  Mat3 ok = Vec3(1, 2, 2.5).asDiagonal();
  EXPECT_TRUE(CheckInertiaTensor("inertia", ok).ok());
  Mat3 flat = Vec3(1, 1, 0).asDiagonal();
  Mat3 negative = Vec3(1, -1, 1).asDiagonal();
  Mat3 triangle = Vec3(1, 1, 3).asDiagonal();
  Mat3 skew = ok;
  skew(0, 1) = 0.1;
  Mat3 nan = ok;
  nan(2, 2) = std::nan("");
  EXPECT_NE(CheckInertiaTensor("inertia", flat).message().find("positive definite"), std::string::npos);
  EXPECT_NE(CheckInertiaTensor("inertia", negative).message().find("positive definite"), std::string::npos);
  EXPECT_NE(CheckInertiaTensor("inertia", triangle).message().find("triangle inequality"), std::string::npos);
  EXPECT_NE(CheckInertiaTensor("inertia", skew).message().find("symmetric"), std::string::npos);
  EXPECT_NE(CheckInertiaTensor("inertia", nan).message().find("finite"), std::string::npos);
  // a thin rod is the triangle inequality's edge, I1 + I2 = I3 turned: allowed
  EXPECT_TRUE(CheckInertiaTensor("inertia", Mat3(Vec3(1, 1, 2).asDiagonal())).ok());
}

// Verifies that malformed compounds are refused with a message that names
// the field, and that the body is left untouched.
TEST(CompoundBody, GarbageIsRefusedAndNothingBuilt) {
  const ShapePart box = BoxPart(Vec3::Constant(0.1), Vec3::Zero());
  ShapePart plane;
  plane.type = ShapeType::kPlane;
  ShapePart nested;
  nested.type = ShapeType::kCompound;
  ShapePart nan_pose = box;
  nan_pose.position.x() = std::nan("");
  ShapePart zero_turn = box;
  zero_turn.orientation = Quat(0, 0, 0, 0);
  ShapePart flat_hull;
  flat_hull.type = ShapeType::kConvex;
  flat_hull.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  ShapePart bad_radius = SpherePart(-1, Vec3::Zero());
  struct Case {
    BodySettings settings;
    std::string says;
  };
  BodySettings no_mass = Compound({box});
  no_mass.inertia = Mat3::Identity();
  BodySettings triangle = Compound({box});
  triangle.mass = 1.0;
  triangle.inertia = Mat3(Vec3(1, 1, 3).asDiagonal());
  BodySettings not_spd = Compound({box});
  not_spd.mass = 1.0;
  not_spd.inertia = Mat3(Vec3(1, 1, -1).asDiagonal());
  BodySettings parts_on_box;
  parts_on_box.shape = ShapeType::kBox;
  parts_on_box.half_extents = Vec3::Constant(0.1);
  parts_on_box.parts = {box};
  BodySettings nan_com = Compound({box});
  nan_com.center_of_mass = Vec3(0, std::nan(""), 0);
  const std::vector<Case> cases = {
      {Compound({}), "a compound takes 1 to 64 parts, got 0"},
      {Compound(std::vector<ShapePart>(65, box)), "got 65"},
      {Compound({box, plane}), "parts[1].type must be sphere, box, capsule or convex, got plane"},
      {Compound({nested}), "parts[0].type must be sphere, box, capsule or convex, got compound"},
      {Compound({box, nan_pose}), "parts[1].position must be finite"},
      {Compound({zero_turn}), "parts[0].orientation must be a unit quaternion"},
      {Compound({flat_hull}), "parts[0].points: "},
      {Compound({bad_radius}), "parts[0].radius must be a finite number > 0, got -1"},
      {no_mass, "an explicit inertia needs an explicit mass"},
      {triangle, "triangle inequality"},
      {not_spd, "positive definite"},
      {parts_on_box, "parts are for a compound shape"},
      {nan_com, "center_of_mass must be finite"},
  };
  for (const Case& c : cases) {
    RigidBody b;
    b.name = "untouched";
    const Status st = CreateBody(c.settings, Material{}, &b);
    EXPECT_EQ(st.code(), StatusCode::kInvalidArgument) << c.says;
    EXPECT_NE(st.message().find(c.says), std::string::npos) << st.message();
    EXPECT_EQ(b.name, "untouched");
  }
}

// Verifies the volume of a compound is the sum of its parts' (overlap
// counted twice, as PyBullet does), and a hull part sits at its centroid.
TEST(CompoundBody, VolumeSumsPartsAndHullSitsAtItsCentroid) {
  ShapePart hull;
  hull.type = ShapeType::kConvex;
  hull.points = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};  // centroid (1/4, 1/4, 1/4)
  hull.position = Vec3(1, 0, 0);
  const RigidBody b = Build(Compound({hull, BoxPart(Vec3::Constant(0.5), Vec3::Zero())}));
  EXPECT_NEAR(ShapeVolume(b.shape), 1.0 / 6.0 + 1.0, kTol);
  // centre of mass of a tetrahedron (1/6 m^3) at (1.25, .25, .25) and a unit cube at 0
  const Vec3 c = (1.0 / 6.0 * Vec3(1.25, 0.25, 0.25)) / (1.0 + 1.0 / 6.0);
  EXPECT_TRUE(b.x.isApprox(c, kTol));
  EXPECT_TRUE((b.shape.compound->children[0].position + c).isApprox(Vec3(1.25, 0.25, 0.25), kTol));
}

}  // namespace
}  // namespace contactsim
