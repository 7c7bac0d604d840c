#include "service/contact/xpbd/xpbd_contact.h"

#include <algorithm>
#include <cmath>

#include "service/contact/contact_row.h"
#include "service/contact/sweep_order.h"

namespace contactsim {
namespace {

// The rounding of a shape: its surface lies this far out from its core.
double CoreRadius(const Shape& shape) {
  return shape.type == ShapeType::kSphere || shape.type == ShapeType::kCapsule ? shape.radius : 0.0;
}

// K^-1 of the points idx[0..n) of block m (K^+ for a face's four); the
// tangents are the first point's (PerpendicularBasis depends on n alone).
bool InvertPoints(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies, const NormalBlock& m,
                  const int* idx, int n, Eigen::Matrix4d* inv) {
  const XpbdPoint& p0 = points[m.first + idx[0]];
  // the tangents serve a face's four points only (normal_block.h)
  Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();
  if (n == kMaxNormalBlock) PerpendicularBasis(p0.n, &t1, &t2);
  if (p0.jointed) {  // K_ij = k_lin_j + (r_Ai x n) . ia_n_j + (r_Bi x n) . ib_n_j (XpbdPoint)
    Eigen::Matrix4d k = Eigen::Matrix4d::Zero();
    Vec3 plane[kMaxNormalBlock];
    for (int i = 0; i < n; ++i) {
      const XpbdPoint& pi = points[m.first + idx[i]];
      plane[i] = pi.ra;
      for (int j = 0; j < n; ++j) {
        const XpbdPoint& pj = points[m.first + idx[j]];
        k(i, j) = pj.k_lin + pi.ra_n.dot(pj.ia_n) + pi.rb_n.dot(pj.ib_n);
      }
    }
    return p0.k_lin > 0.0 && InvertNormalBlockK(0.5 * (k + k.transpose()), n, plane, t1, t2, inv);
  }
  NormalBlockPoint block[kMaxNormalBlock];
  for (int k = 0; k < n; ++k) {
    const XpbdPoint& p = points[m.first + idx[k]];
    block[k] = {p.ra, p.ra_n, p.rb_n, p.ia_n, p.ib_n};
  }
  const double k_lin = bodies[p0.a].inv_mass + bodies[p0.b].inv_mass;
  return k_lin > 0.0 && InvertNormalBlock(block, n, k_lin, t1, t2, inv);
}

// K^-1 of all of a block's points sharing one normal (K^+ for a face's four).
bool InvertBlock(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies, const NormalBlock& m,
                 Eigen::Matrix4d* inv) {
  const XpbdPoint& p0 = points[m.first];
  int idx[kMaxNormalBlock];
  for (int i = 0; i < m.count; ++i) {
    if (points[m.first + i].n.dot(p0.n) < 1.0 - 1e-9) return false;
    idx[i] = i;
  }
  return InvertPoints(points, bodies, m, idx, m.count, inv);
}

// Points this close to touching join a block's active set: a resting face's
// corners sit at s = 0 up to round-off, and with all four active the block's
// K^+ is the one inverted at the step's start (a subset needs its own).
constexpr double kTouching = 1e-9;  // m

// Turns q by the small rotation vector theta (first order, renormalised):
// q += (0, theta) q / 2, the product written out for the pure quaternion
// (0, theta), whose zero part drops four of the sixteen products. (0, theta) q
// is orthogonal to q, so a unit q's sum has the norm sqrt(1 + |theta|^2 / 4):
// the renormalisation comes from theta alone, and the chain of turns through
// q (block after block) waits on no square root or division. q's own
// rounding is renormalised away at each sub-step's prediction
// (IntegrateSoftPositions). The sum is formed in registers and stored once
// (writing q's parts one by one stalled the read of the whole).
void Turn(Quat& q, const Vec3& theta) {
  const double scale = 1.0 / std::sqrt(1.0 + 0.25 * theta.squaredNorm());
  const Vec3 v = q.vec();
  const double w = q.w() - 0.5 * theta.dot(v);
  const Vec3 u = v + 0.5 * (q.w() * theta + theta.cross(v));
  q = Quat(scale * w, scale * u.x(), scale * u.y(), scale * u.z());
}

// One point's non-penetration update (Gauss-Seidel).
void SolvePointNormal(World& world, const std::vector<SoftBody>& bodies, const XpbdSolve& solve, XpbdPoint& p) {
  const double depth = std::min(-XpbdSeparation(p, world) - XpbdSlack(p, solve.elapsed), solve.max_push);
  if (depth <= 0.0 && p.lambda_n == 0.0) return;
  const double alpha_tilde = solve.alpha_tilde;
  const double dl = std::max((depth - alpha_tilde * p.lambda_n) / (p.w_n + alpha_tilde), -p.lambda_n);
  p.lambda_n += dl;
  if (p.jointed) {
    solve.articulation->Displace(world, bodies, p.a, -dl * p.n, -dl * p.ra_n);
    solve.articulation->Displace(world, bodies, p.b, dl * p.n, dl * p.rb_n);
    return;
  }
  auto& all = world.bodies();
  const SoftBody& sa = bodies[p.a];
  const SoftBody& sb = bodies[p.b];
  DisplaceXpbdBody(all[p.a], sa, -sa.inv_mass * dl * p.n, -dl * p.ia_n);
  DisplaceXpbdBody(all[p.b], sb, sb.inv_mass * dl * p.n, dl * p.ib_n);
}

// K^-1 of a subset of two or three points (or K^+ of four), 1 / K of one.
bool InvertSubset(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies, const NormalBlock& m,
                  const int* idx, int n, Eigen::Matrix4d* inv) {
  const XpbdPoint& p0 = points[m.first + idx[0]];
  if (n == 1) {
    if (!(p0.w_n > 0.0)) return false;
    inv->setZero();
    (*inv)(0, 0) = 1.0 / p0.w_n;
    return true;
  }
  return InvertPoints(points, bodies, m, idx, n, inv);
}

// A block's non-penetration at once (rigid rows) over its active points,
// those penetrating or already pushing: the least-norm push of the active
// set, a point whose push would turn into a pull dropped and the rest solved
// again (at most four times). A point just touching (s = 0 to round-off)
// then never pulls a face off its corners, which one corner after another
// did, tilting aligned stacks. False when no block applies (three points on
// a line) and the caller sweeps the points.
bool SolveBlockNormals(World& world, const std::vector<SoftBody>& bodies, const XpbdSolve& solve,
                       const NormalBlock& m, XpbdSubsetCache& cache, std::vector<XpbdPoint>& points) {
  XpbdPoint& p0 = points[m.first];
  RigidBody& A = world.bodies()[p0.a];
  RigidBody& B = world.bodies()[p0.b];
  // n . R a = (R^T n) . a: each body's turn is applied to n once per block
  const Vec3& n = p0.n;
  const double shift = n.dot(B.x - A.x);
  const Vec3 na = A.q.conjugate() * n, nb = B.q.conjugate() * n;
  double depth[kMaxNormalBlock];
  int idx[kMaxNormalBlock];
  int active = 0;
  for (int i = 0; i < m.count; ++i) {
    const XpbdPoint& p = points[m.first + i];
    depth[i] = -(shift + nb.dot(p.anchor_b) - na.dot(p.anchor_a) - p.radius_a - p.radius_b);
    depth[i] = std::min(depth[i] - XpbdSlack(p, solve.elapsed), solve.max_push);
    if (depth[i] > -kTouching || p.lambda_n > 0.0) idx[active++] = i;
  }
  Eigen::Vector4d step = Eigen::Vector4d::Zero();
  while (active > 0) {
    const Eigen::Matrix4d* inv = XpbdSubsetInverse(points, bodies, m, idx, active, cache);
    if (inv == nullptr) return false;
    Eigen::Vector4d d = Eigen::Vector4d::Zero();
    for (int k = 0; k < active; ++k) d[k] = depth[idx[k]];
    step.noalias() = *inv * d;
    int worst = -1;
    for (int k = 0; k < active; ++k) {
      const double total = points[m.first + idx[k]].lambda_n + step[k];
      if (total < 0.0 && (worst < 0 || total < points[m.first + idx[worst]].lambda_n + step[worst])) worst = k;
    }
    if (worst < 0) break;
    for (int k = worst; k + 1 < active; ++k) idx[k] = idx[k + 1];
    --active;
  }
  double sum = 0.0;
  Vec3 wa = Vec3::Zero(), wb = Vec3::Zero();
  for (int k = 0; k < active; ++k) {
    XpbdPoint& p = points[m.first + idx[k]];
    p.lambda_n += step[k];
    sum += step[k];
    wa += step[k] * p.ia_n;
    wb += step[k] * p.ib_n;
  }
  if (active == 0) return true;
  if (p0.jointed) {
    Vec3 ta = Vec3::Zero(), tb = Vec3::Zero();  // the pushes' torques
    for (int k = 0; k < active; ++k) {
      const XpbdPoint& p = points[m.first + idx[k]];
      ta += step[k] * p.ra_n;
      tb += step[k] * p.rb_n;
    }
    solve.articulation->Displace(world, bodies, p0.a, -sum * n, -ta);
    solve.articulation->Displace(world, bodies, p0.b, sum * n, tb);
    return true;
  }
  DisplaceXpbdBody(A, bodies[p0.a], -bodies[p0.a].inv_mass * sum * n, -wa);
  DisplaceXpbdBody(B, bodies[p0.b], bodies[p0.b].inv_mass * sum * n, wb);
  return true;
}

}  // namespace

const Eigen::Matrix4d* XpbdSubsetInverseFind(const std::vector<XpbdPoint>& points, const std::vector<SoftBody>& bodies,
                                             const NormalBlock& m, const int* idx, int n, XpbdSubsetCache& cache) {
  if (n == m.count && m.count >= 2) {
    // the whole block's, inverted when a sub-step first needs it (K is the
    // step start's): a block that never touches is never inverted
    if (cache.full < 0) cache.full = InvertBlock(points, bodies, m, &cache.full_inv) ? 1 : 0;
    if (cache.full == 1) return &cache.full_inv;
  }
  int mask = 0;
  for (int k = 0; k < n; ++k) mask |= 1 << idx[k];
  for (int c = 0; c < 2; ++c) {
    if (cache.mask[c] == mask) return cache.ok[c] ? &cache.inv[c] : nullptr;
  }
  const int slot = cache.next;
  cache.next ^= 1;
  cache.mask[slot] = mask;
  cache.ok[slot] = InvertSubset(points, bodies, m, idx, n, &cache.inv[slot]);
  return cache.ok[slot] ? &cache.inv[slot] : nullptr;
}

void DisplaceXpbdBody(RigidBody& body, const SoftBody& s, const Vec3& dx, const Vec3& theta) {
  if (s.inv_mass == 0.0) return;
  body.x += dx;
  // A push through a round body's centre turns it by round-off alone (r x n
  // of a lever arm along n, ~1e-20 rad): below 1e-18 rad the turn moves no
  // part of q by more than its renormalisation's own rounding (1.1e-16), so
  // the sqrt and divisions of Turn are skipped.
  constexpr double kRoundOffTurn = 1e-18;  // rad
  if (theta.squaredNorm() >= kRoundOffTurn * kRoundOffTurn) Turn(body.q, theta);
}

namespace {

// A jointed point's responses and K along n through its bodies' mobility.
void SetJointedResponse(const std::vector<SoftBody>& bodies, const XpbdArticulation& articulation, XpbdPoint& p) {
  const Vec6 resp_a = articulation.Response(p.a, bodies[p.a], p.n, p.ra_n);
  const Vec6 resp_b = articulation.Response(p.b, bodies[p.b], p.n, p.rb_n);
  p.k_lin = p.n.dot(resp_a.head<3>() + resp_b.head<3>());
  p.ia_n = resp_a.tail<3>();
  p.ib_n = resp_b.tail<3>();
  p.w_n = p.k_lin + p.ra_n.dot(p.ia_n) + p.rb_n.dot(p.ib_n);
}

// Contact c's point and frame at the step's start.
void PreparePoint(const Contact& c, const World& world, const std::vector<SoftBody>& bodies,
                  const XpbdArticulation& articulation, XpbdPoint& p, XpbdPointFrame& f) {
  const RigidBody& A = world.bodies()[c.a];
  const RigidBody& B = world.bodies()[c.b];
  const SoftBody& sa = bodies[c.a];
  const SoftBody& sb = bodies[c.b];
  p.lambda_n = 0.0;
  p.impulse.setZero();
  p.a = c.a;
  p.b = c.b;
  p.n = c.normal;
  p.radius_a = CoreRadius(A.shape);
  p.radius_b = CoreRadius(B.shape);
  // the surface points lie depth/2 either side of the midpoint (conventions.md)
  const Vec3 pa = c.point + 0.5 * c.depth * c.normal;
  const Vec3 pb = c.point - 0.5 * c.depth * c.normal;
  // into the bodies' frames by R^T of the step's start, kept by LoadSoftBodies
  p.anchor_a = sa.R0t * (pa - p.radius_a * p.n - A.x);
  p.anchor_b = sb.R0t * (pb + p.radius_b * p.n - B.x);
  f.material_a = sa.R0t * (pa - A.x);
  f.material_b = sb.R0t * (pb - B.x);
  p.ra = c.point - A.x;
  f.rb = c.point - B.x;
  p.ra_n = p.ra.cross(p.n);
  p.rb_n = f.rb.cross(p.n);
  p.ia_n = sa.inv_inertia * p.ra_n;
  p.ib_n = sb.inv_inertia * p.rb_n;
  p.k_lin = sa.inv_mass + sb.inv_mass;
  p.w_n = p.k_lin + p.ra_n.dot(p.ia_n) + p.rb_n.dot(p.ib_n);
  p.jointed = articulation.Applies(c.a, c.b);
  if (p.jointed) SetJointedResponse(bodies, articulation, p);
  f.friction = CombineFriction(A.material, B.material);
  p.restitution = CombineRestitution(A.material, B.material);
}

// What sweep_order.h needs of a point to place its block.
struct PointHeight {
  int a;
  Vec3 ra;
};

}  // namespace

void PrepareXpbdPoints(const ContactSet& contacts, const World& world, const std::vector<SoftBody>& bodies,
                       const XpbdArticulation& articulation, std::vector<XpbdPoint>* points, std::vector<XpbdPointFrame>* frames,
                       std::vector<NormalBlock>* blocks, BlockColours* colours, std::vector<int>* point_of) {
  GroupNormalBlocks(contacts, &Contact::normal, blocks);
  std::vector<PointHeight> heights(contacts.size());
  for (size_t k = 0; k < contacts.size(); ++k) {
    heights[k] = {contacts[k].a, contacts[k].point - world.bodies()[contacts[k].a].x};
  }
  OrderBlocksFromTheTop(world, heights, blocks);
  std::vector<ColourRole> roles(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) {
    roles[i] = bodies[i].inv_mass == 0.0             ? ColourRole::kFixed
               : articulation.InComponent(static_cast<int>(i)) ? ColourRole::kSerial
                                                               : ColourRole::kColoured;
  }
  *colours = ColourBlocks(contacts, roles, blocks);
  points->resize(contacts.size());
  frames->resize(contacts.size());
  point_of->resize(contacts.size());
  int next = 0;
  for (NormalBlock& m : *blocks) {
    for (int i = 0; i < m.count; ++i) {
      PreparePoint(contacts[m.first + i], world, bodies, articulation, (*points)[next + i], (*frames)[next + i]);
      (*point_of)[m.first + i] = next + i;
    }
    m.first = next;
    next += m.count;
  }
}

double XpbdSeparation(const XpbdPoint& p, const World& world, Vec3* pa_out, Vec3* pb_out) {
  const RigidBody& A = world.bodies()[p.a];
  const RigidBody& B = world.bodies()[p.b];
  // a sphere's anchor is its centre: no turn to apply
  const Vec3 ca = p.anchor_a.isZero(0.0) ? A.x : Vec3(A.x + A.q * p.anchor_a);
  const Vec3 cb = p.anchor_b.isZero(0.0) ? B.x : Vec3(B.x + B.q * p.anchor_b);
  if (pa_out) *pa_out = ca + p.radius_a * p.n;
  if (pb_out) *pb_out = cb - p.radius_b * p.n;
  return p.n.dot(cb - ca) - p.radius_a - p.radius_b;
}

void AllowXpbdStartOverlaps(const ContactSet& contacts, const std::vector<int>& point_of,
                            const std::vector<double>& most, double velocity, double settle_time, double h,
                            std::vector<XpbdPoint>* points) {
  for (size_t k = 0; k < contacts.size(); ++k) {
    XpbdPoint& p = (*points)[point_of[k]];
    const double depth = std::min(contacts[k].depth, most[k]);
    const double rate = std::max(velocity, depth / settle_time);
    // what the first sub-step would remove anyway is no start overlap: a
    // resting contact's sweeps leave round-off of that order
    const bool lasts = depth > rate * h;
    p.slack0 = lasts ? depth : 0.0;
    p.slack_rate = lasts ? rate : 0.0;
  }
}

void BeginXpbdSubstep(const NormalBlock& m, std::vector<XpbdPoint>* points) {
  for (int i = m.first; i < m.first + m.count; ++i) (*points)[i].lambda_n = 0.0;
}

void SolveXpbdBlockNormals(World& world, const std::vector<SoftBody>& bodies, const XpbdSolve& solve,
                           const NormalBlock& m, XpbdSubsetCache& cache, std::vector<XpbdPoint>& points) {
  const bool solved =
      m.count > 1 && solve.alpha_tilde == 0.0 && SolveBlockNormals(world, bodies, solve, m, cache, points);
  if (solved) return;
  for (int i = 0; i < m.count; ++i) SolvePointNormal(world, bodies, solve, points[m.first + i]);
}

void RefreshJointedXpbdBlock(const std::vector<SoftBody>& bodies, const XpbdArticulation& articulation,
                             const NormalBlock& m, XpbdSubsetCache* cache, std::vector<XpbdPoint>* points) {
  for (int i = m.first; i < m.first + m.count; ++i) SetJointedResponse(bodies, articulation, (*points)[i]);
  *cache = XpbdSubsetCache{};
}

}  // namespace contactsim
