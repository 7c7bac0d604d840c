// Separating-axis test (SAT) between two convex polyhedra.
//
// Two convex polyhedra are disjoint iff some plane separates them, and such a
// plane can be taken to contain a face of one, or an edge of one and be
// parallel to an edge of the other (Baraff 1989; Gottschalk, Lin and Manocha,
// "OBBTree", SIGGRAPH 1996). So the candidate axes are the face normals of both
// and the cross products of one edge of each. With u the axis oriented from A
// to B, the separation is
//   sep(u) = min_{v in B} u.v - max_{v in A} u.v,
// positive for a gap. Edge pairs are kept only when they form a face of the
// Minkowski difference A - B (a Gauss-map arc test, Gregorius, GDC 2013), so
// the candidates are exactly the face normals of A - B: when the bodies
// overlap the largest separation is minus the exact translational penetration
// depth, and when they do not it is the distance of the origin from the
// farthest face plane of A - B (a lower bound of the Euclidean distance).
//
// Face axes are preferred over edge axes, and faces of A over faces of B,
// unless the other beats them by a relative and an absolute tolerance (as Box2D
// b2CollidePolygons, ODE's dBoxBox), so that nearly tied axes do not make the
// manifold flicker. The relative part is capped (kSatMaxBias), so the chosen
// axis is never more than kSatMaxBias + kSatAbsTolerance deeper than the true
// penetration depth; the unbiased axis is reported alongside.
#pragma once

#include <cstdint>

#include "service/collision/minkowski_edge_pairs.h"
#include "service/collision/posed_polyhedron.h"

namespace contactsim {

// What defines a separating (or least-penetrating) axis: a face of A, a face
// of B, or an edge of A and an edge of B (topology indices).
struct SeparatingAxis {
  enum class Kind : uint8_t { kNone, kFaceA, kFaceB, kEdges };
  Kind kind = Kind::kNone;
  int a = -1;  // face or edge of A
  int b = -1;  // face or edge of B
  bool operator==(const SeparatingAxis& o) const { return kind == o.kind && a == o.a && b == o.b; }
};

struct SatResult {
  SeparatingAxis axis;
  Vec3 normal = Vec3::UnitZ();  // unit, world, from A to B
  double separation = 0.0;      // m, > 0 gap, < 0 overlap (minus the depth)
  // m, the largest separation over all candidates, without preferences:
  // minus the exact penetration depth, or a lower bound of the distance.
  // Continuous in the poses, so time-of-impact searches use it.
  double max_separation = 0.0;
  // unit, world, from A to B: the axis of max_separation (the exact
  // minimum-penetration direction when overlapping)
  Vec3 max_normal = Vec3::UnitZ();
};

// Preference tolerances: an edge axis (or a face of B) is chosen only when its
// depth d (= -separation) is below
//   d_ref - min((1 - rel) max(d_ref, 0), kSatMaxBias) - kSatAbsTolerance.
// 5% relative (ODE's and FCL's box-box "fudge factor" 1.05) keeps a resting
// box on its face under small rotations; the absolute 10 um is well below
// contact slop and below the time-of-impact tolerance, and bounds the jump in
// the manifold's depth when the choice switches near zero depth. The cap
// 0.5 mm leaves the full 5% for resting contacts (depths below 1 cm) and keeps
// deep contacts within 0.51 mm of the true depth: an uncapped 5% made the
// reported depth of a 25 cm overlap 12 mm too deep.
constexpr double kSatEdgeRelTolerance = 0.95;
constexpr double kSatFaceRelTolerance = 0.98;
constexpr double kSatAbsTolerance = 1e-5;  // m
constexpr double kSatMaxBias = 5e-4;       // m

// Edge pairs with |dA x dB| below this are skipped: sin(angle) < 1e-6 gives an
// ill-conditioned axis, and near-parallel edges are separated by face axes.
constexpr double kSatParallelSin = 1e-6;

// Separation along one axis; false when the axis does not exist for these
// polyhedra (index out of range, or parallel edges).
bool AxisSeparation(const PosedPolyhedron& a, const PosedPolyhedron& b, const SeparatingAxis& axis,
                    Vec3* normal, double* separation);

// Best axis over all candidates, with the preferences above. Returns at the
// first axis whose separation exceeds `early_out` (m): then no contact within
// that margin exists and the result need not be the best axis.
// Large hulls' face queries descend the vertex graph (MinProjection) and
// their edge queries visit only the edge pairs that form Minkowski faces
// (minkowski_edge_pairs.h), which give the same result as the scans; the
// pair search keeps its buffers in `scratch` (optional). Small closed pairs
// read the Gauss-map test of each edge pair from tables (GaussArcTable),
// the same answers for fewer products.
SatResult FindSeparatingAxis(const PosedPolyhedron& a, const PosedPolyhedron& b, double early_out,
                             EdgePairScratch* scratch = nullptr);

// The steps of a separating-axis test, shared by FindSeparatingAxis and the
// closed-form box-box test (box_box_sat.h):
// a candidate axis (its max_* equal to its own normal and separation);
SatResult MakeSatResult(const SeparatingAxis& axis, const Vec3& normal, double separation);
// an early-out result: its axis separates more than asked, which is all
// that is known of the maximum;
SatResult EarlyOutResult(SatResult r);
// the result from the best face of A, the best face of B and the best edge
// pair (separation -inf and kind kNone where there is none), with the
// preferences above and the unbiased maximum.
SatResult ChooseSeparatingAxis(const SatResult& face_a, const SatResult& face_b, const SatResult& edges);
// The separation (m) an edge axis must exceed for ChooseSeparatingAxis to
// prefer it over `faces`, the axis it chose from the faces alone.
double EdgeChoiceSeparation(const SatResult& faces);

}  // namespace contactsim
