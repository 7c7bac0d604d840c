// Contacts on jointed bodies: the joint rows and the contact rows of the
// bodies they hold solved together, directly (docs/physics.md, "Jointed
// supports").
//
// Why: a method that solves its contacts and its joints as two blocks of a
// Gauss-Seidel iteration (impulse, soft) or sweeps both with projected
// Gauss-Seidel (lcp pgs) pushes a jointed plank under a load as a free
// body; the joint solve takes the plank's share of each push back, and the
// load's error shrinks by about m_plank / m_load a sweep (the same rate as
// a heavy body on a light free one; Erleben, "Velocity-based shock
// propagation", ACM TOG 2007). Twenty sweeps left 50 kg on a 0.5 kg hinged
// plank creeping 0.6-1 mm in 3 s under impulse, the soft step's eight
// turns up to 31 mm. The subspace solve (subspace_solve.h; Silcowitz,
// Niebe and Erleben 2010) takes the active set the sweeps found and solves
// the component's sticking friction, pushing normals and joint rows (with
// their limits' and friction's bounds) as one linear system, so the load
// and its support end the solve moving as the joints and static friction
// allow together: the Schur complement of the joint rows is inside that
// solve, the constrained mobility of joint_mobility.h without forming it.
//
// Which components: those with a contact on a jointed dynamic body,
// whatever their mass ratio. Worlds without joints mark nothing and keep
// their results bit for bit.
#pragma once

#include <vector>

#include "service/contact/union_find.h"

namespace contactsim {

// Per body: the root of its jointed component (dynamic bodies joined by
// `blocks`, anything with body indices a and b, -1 the world; `bodies`
// anything with an inv_mass), or -1 for a body no joint holds.
template <class Block, class Body>
std::vector<int> JointedComponents(const std::vector<Block>& blocks, const std::vector<Body>& bodies) {
  const int n = static_cast<int>(bodies.size());
  auto dynamic = [&bodies](int i) { return i >= 0 && bodies[i].inv_mass > 0.0; };
  UnionFind sets(n);
  for (const Block& blk : blocks) {
    if (dynamic(blk.a) && dynamic(blk.b)) sets.Join(blk.a, blk.b);
  }
  std::vector<int> component(n, -1);
  for (const Block& blk : blocks) {
    for (int i : {blk.a, blk.b}) {
      if (dynamic(i)) component[i] = sets.Root(i);
    }
  }
  return component;
}

// Marks (per body, `count` bodies) the bodies of `rows` (anything with
// body indices a and b, -1 the world) that `jointed(i)` says are jointed;
// true when it marked any.
template <class Row, class Jointed>
bool MarkJointedContacts(const std::vector<Row>& rows, size_t count, Jointed jointed, std::vector<char>* marked) {
  marked->assign(count, 0);
  bool any = false;
  for (const Row& r : rows) {
    for (int i : {r.a, r.b}) {
      if (i < 0 || !jointed(i)) continue;
      (*marked)[static_cast<size_t>(i)] = 1;
      any = true;
    }
  }
  return any;
}

// The same from per-body components (JointedComponents), marking nothing
// when a row joins two bodies of one component: an articulated body
// touching itself, whose contact and joint rows can ask for motions no
// velocity meets (joint_block.h, SelfContact).
template <class Row>
bool MarkJointedContacts(const std::vector<Row>& rows, const std::vector<int>& component, std::vector<char>* marked) {
  for (const Row& r : rows) {
    if (r.a >= 0 && r.b >= 0 && component[r.a] >= 0 && component[r.a] == component[r.b]) {
      marked->assign(component.size(), 0);
      return false;
    }
  }
  return MarkJointedContacts(rows, component.size(), [&component](int i) { return component[i] >= 0; }, marked);
}

}  // namespace contactsim
