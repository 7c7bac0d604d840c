#include "service/contact/joints/joint_rows.h"

#include <algorithm>
#include <cmath>

namespace contactsim {
namespace {

// One end of a joint as the rows see it.
struct End {
  int index = -1;                // solver body index; -1: the world
  const RigidBody* body = nullptr;
  bool dynamic = false;
  Vec3 p = Vec3::Zero();         // m, world: the anchor
  Vec3 r = Vec3::Zero();         // m, world: anchor minus centre of mass
  Vec3 v = Vec3::Zero();         // m/s, centre of mass
  Vec3 w = Vec3::Zero();         // rad/s
  Vec3 PointVelocity() const { return v + w.cross(r); }
  Vec3 Centripetal() const { return w.cross(w.cross(r)); }
};

End MakeEnd(const World& world, const std::vector<SolverBody>& bodies, BodyId id, const Vec3& anchor) {
  End e;
  if (id != kWorldBody) {
    e.index = world.IndexOf(id);
    e.body = &world.bodies()[e.index];
    e.dynamic = bodies[e.index].inv_mass > 0.0;
    e.v = bodies[e.index].v;
    e.w = bodies[e.index].w;
  }
  e.p = AnchorWorld(anchor, e.body);
  if (e.body != nullptr) e.r = e.p - e.body->x;
  return e;
}

class RowWriter {
 public:
  RowWriter(const End& a, const End& b, double h, JointRowMode mode, std::vector<ConstraintRow>* rows,
            std::vector<double>* errors)
      : a_(a), b_(b), h_(h), mode_(mode), rows_(rows), errors_(errors) {}

  // a row with J = (lin, r_A x lin + ang | -lin, -(r_B x lin) - ang)
  ConstraintRow& Add(const Vec3& lin, const Vec3& ang, double error, double velocity_product) {
    ConstraintRow row;
    row.a = a_.index;
    row.b = b_.index;
    row.lin_a = lin;
    row.ang_a = a_.r.cross(lin) + ang;
    row.lin_b = -lin;
    row.ang_b = -(b_.r.cross(lin)) - ang;
    row.rhs = mode_ == JointRowMode::kVelocity ? -0.5 * h_ * velocity_product : 0.0;
    rows_->push_back(row);
    if (errors_ != nullptr) errors_->push_back(error);
    return rows_->back();
  }

  void Point() {
    const Vec3 d = a_.p - b_.p;
    const Vec3 centripetal = a_.Centripetal() - b_.Centripetal();
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = Vec3::Unit(k);
      Add(e, Vec3::Zero(), d[k], centripetal[k]);
    }
  }

  void Distance(double length) {
    const Vec3 d = a_.p - b_.p;
    const Vec3 ddot = a_.PointVelocity() - b_.PointVelocity();
    const double vp = ddot.squaredNorm() + d.dot(a_.Centripetal() - b_.Centripetal());
    Add(d / length, Vec3::Zero(), (d.squaredNorm() - length * length) / (2.0 * length), vp / length);
  }

  void HingeAxis(const Vec3& axis_a, const Vec3& axis_b) {
    Vec3 t[2];
    PerpendicularBasis(axis_a, &t[0], &t[1]);
    const Vec3 misalignment = axis_b.cross(axis_a);
    for (const Vec3& tk : t) Add(Vec3::Zero(), tk, tk.dot(misalignment), a_.w.cross(tk).dot(a_.w - b_.w));
  }

  void Weld(const Quat& q_a, const Quat& rest, const Quat& q_b) {
    Quat e = q_a * rest * q_b.conjugate();
    if (e.w() < 0.0) e.coeffs() = -e.coeffs();
    const Vec3 error = 2.0 * e.vec();
    for (int k = 0; k < 3; ++k) Add(Vec3::Zero(), Vec3::Unit(k), error[k], 0.0);
  }

  // hinge angle rows: J qdot = angle rate = a . (w_B - w_A)
  void Limits(const Joint& j, const Vec3& axis) {
    const double angle = HingeAngle(j, *a_.body, b_.body);
    const double rate = axis.dot(b_.w - a_.w);
    const double vp = a_.w.cross(axis).dot(b_.w - a_.w);
    if (mode_ == JointRowMode::kPosition) {
      if (angle < j.lower) Add(Vec3::Zero(), -axis, angle - j.lower, 0.0).lo = 0.0;
      if (angle > j.upper) Add(Vec3::Zero(), -axis, angle - j.upper, 0.0).hi = 0.0;
      return;
    }
    if (angle + h_ * rate <= j.lower) {
      ConstraintRow& row = Add(Vec3::Zero(), -axis, angle - j.lower, vp);
      row.rhs = std::min(0.0, (j.lower - angle) / h_);
      row.lo = 0.0;
    }
    if (angle + h_ * rate >= j.upper) {
      ConstraintRow& row = Add(Vec3::Zero(), -axis, angle - j.upper, vp);
      row.rhs = std::max(0.0, (j.upper - angle) / h_);
      row.hi = 0.0;
    }
  }

 private:
  const End& a_;
  const End& b_;
  double h_;
  JointRowMode mode_;
  std::vector<ConstraintRow>* rows_;
  std::vector<double>* errors_;
};

}  // namespace

void AppendJointRows(const World& world, const std::vector<SolverBody>& bodies, double h, JointRowMode mode,
                     std::vector<ConstraintRow>* rows, std::vector<JointBlock>* blocks,
                     std::vector<double>* errors) {
  for (const Joint& j : world.joints()) {
    const End a = MakeEnd(world, bodies, j.body_a, j.anchor_a);
    const End b = MakeEnd(world, bodies, j.body_b, j.anchor_b);
    if (!a.dynamic && !b.dynamic) continue;  // nothing can move
    const int first = static_cast<int>(rows->size());
    RowWriter writer(a, b, h, mode, rows, errors);
    const Quat q_a = a.body->q;
    const Quat q_b = BodyOrientation(b.body);
    switch (j.kind) {
      case JointKind::kDistance: writer.Distance(j.length); break;
      case JointKind::kBall: writer.Point(); break;
      case JointKind::kHinge: {
        const Vec3 axis_a = q_a * j.axis_a;
        writer.Point();
        writer.HingeAxis(axis_a, q_b * j.axis_b);
        if (j.limited) writer.Limits(j, axis_a);
        break;
      }
      case JointKind::kFixed:
        writer.Point();
        writer.Weld(q_a, j.rest, q_b);
        break;
    }
    if (blocks != nullptr) blocks->push_back({j.id, first, static_cast<int>(rows->size()) - first, a.index, b.index});
  }
}

}  // namespace contactsim
