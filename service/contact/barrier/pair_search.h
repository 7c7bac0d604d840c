// Candidate primitive pairs of the barrier method: the pairs whose distance
// can be below `reach` somewhere on a linear motion of the affine bodies
// from q to q_end (Li et al. 2020, IPC sec. 4 and its supplemental: a
// spatial broadphase over the primitives' swept boxes before any distance is
// computed). Affine maps are linear in q, so every vertex moves on the
// segment from its start to its end and a primitive (a convex combination of
// its vertices) stays inside the box of its vertices at both ends; two
// primitives that come within `reach` therefore have boxes, each grown by
// reach / 2, that overlap. Two levels:
//  * bodies: sweep and prune (sweep_and_prune.h) over the bodies' swept
//    boxes; a plane is tested against every body directly (a point's
//    distance to a static plane is linear in the motion, so its smallest
//    value is at an end); a triangle mesh or heightfield too, each point,
//    edge and triangle of the body whose box, grown by reach, reaches one
//    of the surface's triangles (for an edge or triangle, one with a
//    convex edge) through the surface's own search
//    (ForEachSurfaceTriangle) becoming a pair with the whole surface
//    (surface_primitives.h);
//  * primitives of a body pair: only the points, edges and triangles whose
//    own boxes overlap the other body's box, then the pairs of those whose
//    boxes overlap (of the kinds contact_primitives.h enumerates).
// Body pairs that ShouldCollide refuses (collision_filter.h) are dropped
// before any primitive is looked at, as the collision detector drops them.
// The order of the output is deterministic: body pairs ascending, then the
// enumeration order of EnumeratePrimitivePairs.
#pragma once

#include <vector>

#include "service/collision/aabb.h"
#include "service/collision/sweep_and_prune.h"
#include "service/contact/barrier/affine_body.h"
#include "service/contact/barrier/contact_primitives.h"
#include "service/physics/collision_filter.h"

namespace contactsim {

struct SearchBody {
  const BodyGeometry* geometry = nullptr;
  Vec12 q = Vec12::Zero();       // affine coordinates now
  Vec12 q_end = Vec12::Zero();   // at the end of the motion (q for none)
  bool movable = false;          // pairs of two bodies that cannot move are skipped
  const RigidBody* body = nullptr;  // its collision filter; null: touches every body
};

struct CandidatePair {
  int a = -1, b = -1;            // body indices, a < b
  PrimitivePair pair;
};

class PrimitivePairSearch {
 public:
  // Fills `out` (cleared first) with the candidates within `reach` (m) of
  // the body pairs the filters and `joined` accept.
  void Find(const std::vector<SearchBody>& bodies, double reach, const JointPairSet& joined,
            std::vector<CandidatePair>* out);
  // Drops the sweep order kept between calls (bodies added or removed).
  void Reset() { sap_.Reset(); }

 private:
  struct Boxes {                 // one body's primitive boxes, grown by reach / 2
    std::vector<Aabb> points, edges, triangles;
    bool ready = false;
  };
  const Boxes& PrimitiveBoxes(const std::vector<SearchBody>& bodies, int i, double half);
  void AddPlanePairs(const std::vector<SearchBody>& bodies, int plane, int solid, double reach,
                     std::vector<CandidatePair>* out) const;
  void AddSurfacePairs(const std::vector<SearchBody>& bodies, int surface, int solid, double half,
                       std::vector<CandidatePair>* out);
  void AddSolidPairs(const std::vector<SearchBody>& bodies, int a, int b, double half,
                     std::vector<CandidatePair>* out);

  SweepAndPrune sap_;
  std::vector<Aabb> body_boxes_;
  std::vector<bool> movable_;
  std::vector<int> solid_index_;   // bodies that are neither planes nor surfaces, in the order given to the sweep
  std::vector<BodyPair> body_pairs_;
  std::vector<Boxes> boxes_;
  std::vector<int> kept_a_[3], kept_b_[3];  // points, edges, triangles near the other body
};

}  // namespace contactsim
