// Closest points between a point and a segment, between two segments and
// between a point and a triangle (Ericson, "Real-Time Collision Detection",
// 2005, sections 5.1.2, 5.1.9 and 5.1.5).
// Capsules are segments with a radius, and edge-edge contacts of polyhedra are
// the closest points of the two edges, so both families use these.
#pragma once

#include "service/physics/math.h"

namespace contactsim {

// Closest point to p on the segment [a, b]; `t` in [0, 1] receives its parameter.
Vec3 ClosestPointOnSegment(const Vec3& p, const Vec3& a, const Vec3& b, double* t = nullptr);

struct SegmentClosestPoints {
  double s = 0.0;            // parameter on the first segment, [0, 1]
  double t = 0.0;            // parameter on the second segment, [0, 1]
  Vec3 c1 = Vec3::Zero();    // closest point on the first segment
  Vec3 c2 = Vec3::Zero();    // closest point on the second segment
};

// Closest points of [p1, q1] and [p2, q2]. For parallel segments the choice is
// Ericson's (s = 0 when the whole overlap is equally close).
SegmentClosestPoints ClosestPointsOfSegments(const Vec3& p1, const Vec3& q1, const Vec3& p2,
                                             const Vec3& q2);

// Closest point to p on the triangle (a, b, c); `bary` receives its
// barycentric weights (u, v, w), closest = u a + v b + w c, all in [0, 1].
Vec3 ClosestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, Vec3* bary = nullptr);

}  // namespace contactsim
