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

// A rail's directions turn with B when B cannot move (RowWriter::Line
// says why), with A otherwise.
bool RailInB(const End& b) { return !b.dynamic; }

// The slider's axis in the world, from the body its rail is fixed in. The
// weld keeps q_A = q_B rest^-1 (RowWriter::Weld: q_A rest q_B^-1 = 1), so
// taken from B the axis is q_B rest^-1 axis_A.
Vec3 SliderAxis(const Joint& j, const End& a, const End& b) {
  if (RailInB(b)) return BodyOrientation(b.body) * (j.rest.conjugate() * j.axis_a);
  return a.body->q * j.axis_a;
}

// Writes a joint's rows (rows_), or only their errors (rows_ null: the
// projection's check, AppendJointErrors) or only their rhs (rhs_only_:
// SetJointVelocityProducts); the two partial writers skip the Jacobians of
// the equality rows and compute what they keep by the same arithmetic.
class RowWriter {
 public:
  RowWriter(const End& a, const End& b, double h, JointRowMode mode, std::vector<ConstraintRow>* rows,
            std::vector<double>* errors)
      : a_(a), b_(b), h_(h), mode_(mode), rows_(rows), errors_(errors) {}
  // Writes only the rhs of the rows from `first` on, which are there
  // already (SetJointVelocityProducts): the geometry rows, a joint's first.
  RowWriter(const End& a, const End& b, double h, ConstraintRow* first)
      : a_(a), b_(b), h_(h), mode_(JointRowMode::kVelocity), rows_(nullptr), errors_(nullptr), rhs_only_(first) {}

  // a row with J = (lin, r_A x lin + ang | -lin, -(r_B x lin) - ang)
  ConstraintRow Make(const Vec3& lin, const Vec3& ang, double velocity_product) const {
    ConstraintRow row;
    row.a = a_.index;
    row.b = b_.index;
    row.lin_a = lin;
    row.ang_a = a_.r.cross(lin) + ang;
    row.lin_b = -lin;
    row.ang_b = -(b_.r.cross(lin)) - ang;
    row.rhs = mode_ != JointRowMode::kPosition ? -0.5 * h_ * velocity_product : 0.0;
    return row;
  }

  ConstraintRow& Push(const ConstraintRow& row, double error) {
    if (rhs_only_ != nullptr) {
      rhs_only_->rhs = row.rhs;
      return *rhs_only_++;
    }
    if (errors_ != nullptr) errors_->push_back(error);
    if (rows_ == nullptr) return scratch_ = row;
    rows_->push_back(row);
    return rows_->back();
  }

  // an equality row (Make); a partial writer keeps its error or rhs only
  void Add(const Vec3& lin, const Vec3& ang, double error, double velocity_product) {
    if (rhs_only_ != nullptr) {
      (rhs_only_++)->rhs = mode_ != JointRowMode::kPosition ? -0.5 * h_ * velocity_product : 0.0;
    } else if (rows_ == nullptr) {
      errors_->push_back(error);
    } else {
      Push(Make(lin, ang, velocity_product), error);
    }
  }

  // True when the joint's coordinate (HingeCoordinate, SlideCoordinate)
  // feeds a row: always in velocity mode, only for the limits in position
  // mode.
  bool WantsCoordinate(const Joint& j) const { return mode_ != JointRowMode::kPosition || j.limited; }

  // C = u . (p_A - p_B) for a direction u fixed in A (world now): B's
  // anchor kept on a line or plane of A. Cdot = u . ddot + (w_A x u) . d,
  // so A's lever arm reaches B's anchor: J = (u, (p_B - x_A) x u | -u,
  // -r_B x u); vp = (w_A x (w_A x u)) . d + 2 (w_A x u) . ddot +
  // u . (w_A x (w_A x r_A) - w_B x (w_B x r_B)).
  // When B cannot move (the world, a static or kinematic body), u is taken
  // fixed in B instead (the weld rows keep the two directions one): then
  // Cdot = u . ddot + (w_B x u) . d, J = (u, r_A x u | -u, -(p_A - x_B) x u),
  // vp = (w_B x (w_B x u)) . d + 2 (w_B x u) . ddot + the same centripetal
  // terms, and A's lever arm stays r_A. Fixed in A, A's lever |p_B - x_A|
  // grows with the slide s, and with it the rows' coupling to the weld
  // rows (A's line-row diagonal 1/m + s^2/I against the weld's 1/I): a
  // 0.5 kg plank 15 m down its rail left the sweeps' rail rows off by
  // 0.1 m/s, and past 16 m they pumped energy into it (docs/physics.md,
  // "Prismatic joints, limits, damping and friction").
  // The caller takes u from the same body (SliderAxis), so the error and
  // the Jacobian describe one function and a position projection converges.
  ConstraintRow Line(const Vec3& u, double* error) const {
    const Vec3 d = a_.p - b_.p;
    const Vec3 ddot = a_.PointVelocity() - b_.PointVelocity();
    const bool in_b = RailInB(b_);
    const Vec3 w = RailSpin();
    const Vec3 turn = w.cross(u);
    const double vp = w.cross(turn).dot(d) + 2.0 * turn.dot(ddot) + u.dot(a_.Centripetal() - b_.Centripetal());
    ConstraintRow row = Make(u, Vec3::Zero(), vp);
    if (!in_b) {
      row.ang_a = (b_.p - a_.body->x).cross(u);
    } else if (b_.body != nullptr) {
      row.ang_b = -(a_.p - b_.body->x).cross(u);
    }
    *error = u.dot(d);
    return row;
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

  // The joint coordinate (hinge angle, prismatic slide) as a row with
  // J qdot = its rate (JointVelocity, physics/joint.h).
  struct Coordinate {
    ConstraintRow row;    // rhs from the velocity product, bounds free
    double value = 0.0;   // rad or m
    double rate = 0.0;    // rad/s or m/s
  };

  // hinge: J = (0, -a | 0, a), vp = (w_A x a) . (w_B - w_A)
  Coordinate HingeCoordinate(const Joint& j, const Vec3& axis) const {
    const double vp = a_.w.cross(axis).dot(b_.w - a_.w);
    return {Make(Vec3::Zero(), -axis, vp), HingeAngle(j, *a_.body, b_.body), axis.dot(b_.w - a_.w)};
  }

  // prismatic: s = a . (p_B - p_A), the line row of u = -a
  Coordinate SlideCoordinate(const Vec3& axis) const {
    Coordinate c;
    c.row = Line(-axis, &c.value);  // C = -a . (p_A - p_B) = s
    c.rate = axis.dot(b_.PointVelocity() - a_.PointVelocity()) + RailSpin().cross(axis).dot(b_.p - a_.p);
    return c;
  }

  // Limit rows of the coordinate. Lower limit: lambda >= 0, active when the
  // coordinate would pass it within the step; rhs = min(0, (lower - q) / h),
  // so the joint may still reach the limit but not cross it (speculative,
  // as the contact methods' margins). Upper: mirrored, lambda <= 0.
  // Position rows only when violated, C = q - limit.
  void Limits(const Joint& j, const Coordinate& c) {
    if (!j.limited) return;
    if (mode_ == JointRowMode::kPosition) {
      if (c.value < j.lower) Push(c.row, c.value - j.lower).lo = 0.0;
      if (c.value > j.upper) Push(c.row, c.value - j.upper).hi = 0.0;
      return;
    }
    if (LowerActive(j, c)) {
      ConstraintRow& row = Push(c.row, c.value - j.lower);
      row.rhs = std::min(0.0, (j.lower - c.value) / h_);
      row.lo = 0.0;
    }
    if (UpperActive(j, c)) {
      ConstraintRow& row = Push(c.row, c.value - j.upper);
      row.rhs = std::max(0.0, (j.upper - c.value) / h_);
      row.hi = 0.0;
    }
  }

  bool LowerActive(const Joint& j, const Coordinate& c) const { return j.limited && c.value + h_ * c.rate <= j.lower; }
  bool UpperActive(const Joint& j, const Coordinate& c) const { return j.limited && c.value + h_ * c.rate >= j.upper; }

  // Velocity rows of the joint's damping and friction, J qdot = the
  // coordinate's rate, target 0:
  //   damping c: implicit viscous impulse lambda = -c h (J qdot_new), i.e.
  //     a row with compliance cfm = 1 / (c h): (J M^-1 J^T + 1/(c h))
  //     lambda = -J qdot*, the backward-Euler damper, stable for any c
  //     (Baraff and Witkin 1998, implicit damping forces; ODE's CFM);
  //   friction f: a row bounded by |lambda| <= f h, Coulomb friction of the
  //     joint (stick below f, slide at f), the bounded rows of Erleben 2013.
  // A friction row is left out while a limit row of the same coordinate is
  // active: the two would have the same Jacobian (a singular pair), and the
  // stop itself holds the joint there.
  void Dynamics(const Joint& j, const Coordinate& c) {
    if (mode_ != JointRowMode::kVelocity || h_ <= 0.0) return;
    ConstraintRow row = c.row;
    row.rhs = 0.0;
    if (j.damping > 0.0) {
      ConstraintRow& damper = Push(row, 0.0);
      damper.cfm = 1.0 / (j.damping * h_);
    }
    if (j.friction > 0.0 && !LowerActive(j, c) && !UpperActive(j, c)) {
      ConstraintRow& friction = Push(row, 0.0);
      friction.lo = -j.friction * h_;
      friction.hi = j.friction * h_;
    }
  }

  // The actuator's drive row (joint_rows.h); returns its row index, -1 for
  // none. A hinge without limits drives the wrapped error.
  int Drive(const Joint& j, const Coordinate& c) {
    const JointActuator& act = j.actuator;
    if (mode_ != JointRowMode::kVelocity || h_ <= 0.0 || !HasDriveGains(act)) return -1;
    const bool wrap = j.kind == JointKind::kHinge && !j.limited;
    const DriveTarget d = MakeDriveTarget(act, ActuatorPositionError(act, c.value, wrap), h_);
    ConstraintRow& row = Push(c.row, 0.0);
    row.rhs = d.rate;
    row.cfm = d.cfm;
    row.lo = -d.max_impulse;
    row.hi = d.max_impulse;
    return static_cast<int>(rows_->size()) - 1;
  }

  // prismatic: two line rows across the axis, then the weld
  void Slider(const Vec3& axis, const Quat& q_a, const Quat& rest, const Quat& q_b) {
    Vec3 t[2];
    PerpendicularBasis(axis, &t[0], &t[1]);
    for (const Vec3& tk : t) {
      double error = 0.0;
      const ConstraintRow row = Line(tk, &error);
      Push(row, error);
    }
    Weld(q_a, rest, q_b);
  }

 private:
  // the angular velocity of the body the rail's directions are fixed in
  Vec3 RailSpin() const { return RailInB(b_) ? b_.w : a_.w; }

  const End& a_;
  const End& b_;
  double h_;
  JointRowMode mode_;
  std::vector<ConstraintRow>* rows_;
  std::vector<double>* errors_;
  ConstraintRow* rhs_only_ = nullptr;
  ConstraintRow scratch_;  // a row an errors-only writer hands back unstored
};

// The rows of the joint's geometry (the equality rows, a joint's first).
// Returns the axis of a hinge or slider in the world (zero for the others).
Vec3 GeometryRows(const Joint& j, const End& a, const End& b, RowWriter* writer) {
  const Quat q_a = a.body->q;
  const Quat q_b = BodyOrientation(b.body);
  switch (j.kind) {
    case JointKind::kDistance: writer->Distance(j.length); break;
    case JointKind::kBall: writer->Point(); break;
    case JointKind::kHinge: {
      const Vec3 axis_a = q_a * j.axis_a;
      writer->Point();
      writer->HingeAxis(axis_a, q_b * j.axis_b);
      return axis_a;
    }
    case JointKind::kFixed:
      writer->Point();
      writer->Weld(q_a, j.rest, q_b);
      break;
    case JointKind::kPrismatic: {
      const Vec3 axis = SliderAxis(j, a, b);
      writer->Slider(axis, q_a, j.rest, q_b);
      return axis;
    }
  }
  return Vec3::Zero();
}

// The coordinate row of a hinge or slider; false when neither of its
// bodies can move.
bool CoordinateRow(const World& world, const std::vector<SolverBody>& bodies, const Joint& j, double h,
                   JointRowMode mode, RowWriter::Coordinate* out) {
  const End a = MakeEnd(world, bodies, j.body_a, j.anchor_a);
  const End b = MakeEnd(world, bodies, j.body_b, j.anchor_b);
  std::vector<ConstraintRow> unused;
  const RowWriter writer(a, b, h, mode, &unused, nullptr);
  *out = j.kind == JointKind::kHinge ? writer.HingeCoordinate(j, a.body->q * j.axis_a)
                                     : writer.SlideCoordinate(SliderAxis(j, a, b));
  return a.dynamic || b.dynamic;
}

}  // namespace

void AppendCouplingRows(const World& world, const std::vector<SolverBody>& bodies, double h, JointRowMode mode,
                        std::vector<CouplingRow>* rows) {
  for (const Joint& j : world.joints()) {
    const Joint* m = j.mimic.master != 0 ? world.FindJoint(j.mimic.master) : nullptr;
    if (m == nullptr) continue;
    RowWriter::Coordinate qf, qm;
    const bool moves = CoordinateRow(world, bodies, j, h, mode, &qf);
    if (!(CoordinateRow(world, bodies, *m, h, mode, &qm) || moves)) continue;
    const double k = -j.mimic.multiplier;
    CouplingRow row;
    row.follower = qf.row;
    row.master = qm.row;
    for (Vec3* v : {&row.master.lin_a, &row.master.ang_a, &row.master.lin_b, &row.master.ang_b}) *v *= k;
    row.rhs = qf.row.rhs + k * qm.row.rhs;
    row.follower.rhs = row.master.rhs = 0.0;
    row.error = qf.value + k * qm.value - j.mimic.offset;
    if (j.kind == JointKind::kHinge) row.error = std::remainder(row.error, 2.0 * kPi);
    rows->push_back(row);
  }
}

bool HasJointDynamics(const World& world) {
  for (const Joint& j : world.joints()) {
    if (j.damping > 0.0 || j.friction > 0.0 || HasDriveGains(j.actuator)) return true;
  }
  return false;
}

void AddDriveImpulses(const std::vector<JointBlock>& blocks, const std::vector<double>& lambda,
                      std::vector<double>* impulses) {
  for (const JointBlock& blk : blocks) {
    if (blk.drive < 0) continue;
    if (static_cast<int>(impulses->size()) <= blk.joint) impulses->resize(blk.joint + 1, 0.0);
    (*impulses)[blk.joint] += lambda[blk.drive];
  }
}

void AddDriveEfforts(const std::vector<double>& impulses, double duration, World& world) {
  const auto& joints = world.joints();
  for (size_t k = 0; k < impulses.size() && k < joints.size(); ++k) {
    if (impulses[k] != 0.0) world.SetJointEffort(k, joints[k].effort + impulses[k] / duration);
  }
}

namespace {

// AppendJointRows, or with rows null only the errors (AppendJointErrors).
void WriteJointRows(const World& world, const std::vector<SolverBody>& bodies, double h, JointRowMode mode,
                    std::vector<ConstraintRow>* rows, std::vector<JointBlock>* blocks, std::vector<double>* errors) {
  const auto& joints = world.joints();
  for (size_t index = 0; index < joints.size(); ++index) {
    const Joint& j = joints[index];
    const End a = MakeEnd(world, bodies, j.body_a, j.anchor_a);
    const End b = MakeEnd(world, bodies, j.body_b, j.anchor_b);
    if (!a.dynamic && !b.dynamic) continue;  // nothing can move
    const int first = rows != nullptr ? static_cast<int>(rows->size()) : 0;
    RowWriter writer(a, b, h, mode, rows, errors);
    const Vec3 axis_a = GeometryRows(j, a, b, &writer);
    int drive = -1;
    if ((j.kind == JointKind::kHinge || j.kind == JointKind::kPrismatic) && writer.WantsCoordinate(j)) {
      const auto coordinate =
          j.kind == JointKind::kHinge ? writer.HingeCoordinate(j, axis_a) : writer.SlideCoordinate(axis_a);
      writer.Dynamics(j, coordinate);
      drive = writer.Drive(j, coordinate);
      writer.Limits(j, coordinate);
    }
    if (blocks != nullptr && rows != nullptr) {
      blocks->push_back(
          {j.id, first, static_cast<int>(rows->size()) - first, a.index, b.index, static_cast<int>(index), drive});
    }
  }
}

}  // namespace

void AppendJointRows(const World& world, const std::vector<SolverBody>& bodies, double h, JointRowMode mode,
                     std::vector<ConstraintRow>* rows, std::vector<JointBlock>* blocks,
                     std::vector<double>* errors) {
  WriteJointRows(world, bodies, h, mode, rows, blocks, errors);
}

void AppendJointErrors(const World& world, const std::vector<SolverBody>& bodies, std::vector<double>* errors) {
  WriteJointRows(world, bodies, 0.0, JointRowMode::kPosition, nullptr, nullptr, errors);
}

void SetJointVelocityProducts(const World& world, const std::vector<SolverBody>& bodies, double h,
                              const std::vector<JointBlock>& blocks, std::vector<ConstraintRow>* rows) {
  const auto& joints = world.joints();
  for (const JointBlock& blk : blocks) {
    const Joint& j = joints[blk.joint];
    const End a = MakeEnd(world, bodies, j.body_a, j.anchor_a);
    const End b = MakeEnd(world, bodies, j.body_b, j.anchor_b);
    RowWriter writer(a, b, h, rows->data() + blk.first);
    GeometryRows(j, a, b, &writer);
  }
}

}  // namespace contactsim
