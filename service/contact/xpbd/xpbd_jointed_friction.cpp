#include "service/contact/xpbd/xpbd_jointed_friction.h"

#include <Eigen/Cholesky>
#include <cmath>

namespace contactsim {
namespace {

double Pushed(const XpbdPatch& patch, const std::vector<XpbdPoint>& points) {
  double pushed = 0.0;
  for (int i = 0; i < patch.count; ++i) pushed += points[patch.first + i].lambda_n;
  return pushed;
}

// Whether the patch's multipliers plus (d1, d2, d_twist) stay in its cone.
bool InCone(const XpbdPatch& patch, double pushed, const Vec3& d) {
  const double limit = patch.friction * pushed;
  const Vec3 lambda_t = patch.lambda_t + d[0] * patch.t1 + d[1] * patch.t2;
  if (lambda_t.norm() > limit) return false;
  return patch.twist_radius == 0.0 || std::abs(patch.lambda_twist + d[2]) <= limit * patch.twist_radius;
}

}  // namespace

void XpbdJointedFriction::BuildRows(const std::vector<XpbdPoint>& points, const std::vector<XpbdPatch>& patches) {
  rows_.clear();
  for (int k : members_) {
    const XpbdPatch& patch = patches[k];
    const Vec3& n = points[patch.first].n;
    const Vec3 lin[3] = {patch.t1, patch.t2, Vec3::Zero()};
    const Vec3 ang_a[3] = {patch.ra.cross(patch.t1), patch.ra.cross(patch.t2), n};
    const Vec3 ang_b[3] = {patch.rb.cross(patch.t1), patch.rb.cross(patch.t2), n};
    const int count = patch.twist_radius > 0.0 ? 3 : 2;
    for (int axis = 0; axis < count; ++axis) {
      Row r;
      r.patch = k;
      r.axis = axis;
      r.ja << -lin[axis], -ang_a[axis];
      r.jb << lin[axis], ang_b[axis];
      rows_.push_back(r);
    }
  }
}

void XpbdJointedFriction::BuildK(const std::vector<SoftBody>& bodies, const XpbdArticulation& articulation,
                                 const std::vector<XpbdPoint>& points, const std::vector<XpbdPatch>& patches) {
  const int m = static_cast<int>(rows_.size());
  k_.setZero(m, m);
  for (int col = 0; col < m; ++col) {
    const Row& c = rows_[col];
    const XpbdPoint& pc = points[patches[c.patch].first];
    for (int row = 0; row < m; ++row) {
      const Row& r = rows_[row];
      const XpbdPoint& pr = points[patches[r.patch].first];
      double sum = 0.0;
      for (const auto& [y, wy] : {std::pair<int, const Vec6*>{pc.a, &c.ja}, {pc.b, &c.jb}}) {
        sum += r.ja.dot(articulation.ResponseOf(pr.a, y, bodies[y], *wy));
        sum += r.jb.dot(articulation.ResponseOf(pr.b, y, bodies[y], *wy));
      }
      k_(row, col) = sum;
    }
  }
  k_ = 0.5 * (k_ + k_.transpose()).eval();
}

void XpbdJointedFriction::Solve(World& world, const std::vector<SoftBody>& bodies,
                                const XpbdArticulation& articulation, const std::vector<int>& jointed_blocks,
                                const std::vector<XpbdPoint>& points, std::vector<XpbdPatch>& patches) {
  members_.clear();
  for (int k : jointed_blocks) {
    const XpbdPatch& p = patches[k];
    // held at its cone too: the joint answer may bring it back inside
    if (p.valid && (p.sticking || p.clamped) && !p.origin_pending) members_.push_back(k);
  }
  if (members_.size() < 2 || static_cast<int>(members_.size()) > kMaxPatches) return;
  Eigen::VectorXd dl;
  for (;;) {
    BuildRows(points, patches);
    BuildK(bodies, articulation, points, patches);
    const int m = static_cast<int>(rows_.size());
    Eigen::VectorXd e(m);
    std::vector<Vec3> error(patches.size());
    for (int k : members_) error[k] = XpbdPatchError(world, patches[k], points);
    for (int i = 0; i < m; ++i) e[i] = error[rows_[i].patch][rows_[i].axis];
    const Eigen::LDLT<Eigen::MatrixXd> ldlt(k_);
    if (ldlt.info() != Eigen::Success) return;
    dl = ldlt.solve(e);
    if (!dl.allFinite()) return;
    // a patch the answer takes out of its cone keeps the sweep's answer
    std::vector<int> kept;
    for (int i = 0; i < m;) {
      const int k = rows_[i].patch;
      Vec3 d = Vec3::Zero();
      int j = i;
      for (; j < m && rows_[j].patch == k; ++j) d[rows_[j].axis] = dl[j];
      if (InCone(patches[k], Pushed(patches[k], points), d)) kept.push_back(k);
      i = j;
    }
    if (kept.size() == members_.size()) break;
    members_.swap(kept);
    if (members_.size() < 2) return;
  }
  for (size_t i = 0; i < rows_.size();) {
    const int k = rows_[i].patch;
    XpbdPatch& patch = patches[k];
    Vec3 d = Vec3::Zero();
    size_t j = i;
    for (; j < rows_.size() && rows_[j].patch == k; ++j) d[rows_[j].axis] = dl[static_cast<Eigen::Index>(j)];
    i = j;
    const Vec3 P = d[0] * patch.t1 + d[1] * patch.t2;
    const Vec3& n = points[patch.first].n;
    patch.lambda_t += P;
    patch.lambda_twist += d[2];
    const XpbdPoint& p0 = points[patch.first];
    articulation.Displace(world, bodies, p0.a, -P, -(patch.ra.cross(P) + d[2] * n));
    articulation.Displace(world, bodies, p0.b, P, patch.rb.cross(P) + d[2] * n);
  }
}

}  // namespace contactsim
