// The edge pairs of two convex polyhedra that form faces of their Minkowski
// difference A - B, found without testing every pair.
//
// An edge of A, between faces with normals a and b, maps to the arc a-b on
// the unit sphere (the Gauss map); an edge of B maps to the arc -c..-d. The
// pair is a face of A - B iff the two arcs cross (Gregorius, "The Separating
// Axis Test between Convex Polyhedra", GDC 2013), which IsMinkowskiFace
// tests. A fine hull has short arcs, so few of the E_a E_b pairs cross: the
// arcs of A go into a uniform grid over the sphere's bounding cube by their
// bounding boxes, and each arc of B is tested only against the arcs of A that
// share a cell with it (a bounding box of each arc: the box of its ends grown
// by its sagitta 1 - cos(theta/2) = 1 - |a + b|/2, which holds the whole
// arc; an arc longer than a cell is split into pieces of a cell, each with
// its box, so that it covers only cells along its path). The pairs come out sorted by (edge of A, edge of B), the order of the
// double loop they replace, and are exactly the pairs for which
// IsMinkowskiFace holds, so the separating-axis test over them gives the same
// result bit for bit.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "service/collision/posed_polyhedron.h"

namespace contactsim {

// True when the arcs a-b and c-d (unit vectors, each arc shorter than a half
// circle) cross on the unit sphere: edges of A with face normals a, b and of
// B with face normals -c, -d make a face of A - B (Gregorius 2013).
bool IsMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

// True when every edge of the polyhedron has both its faces (a closed
// topology), which MinkowskiEdgePairs needs.
bool HasClosedTopology(const PosedPolyhedron& poly);

// IsMinkowskiFace for every edge pair of two small closed polyhedra, read
// from tables: an arc's plane is crossed by the other's arc iff the other
// arc's ends lie on opposite sides of it, and those ends are face normals,
// so each arc's plane (b x a for an edge of A between faces a and b; the
// same of -c, -d for B) is dotted once with each face normal of the other
// polyhedron. That is E_a F_b + E_b F_a products where testing each pair
// costs two cross and four dot products of E_a E_b pairs (a box against a
// triangle's prism: 114 products for 108 pairs), and the entries are
// IsMinkowskiFace's own products, so the answers are the same bit for bit.
class GaussArcTable {
 public:
  // Entries of each table at most (16 KB on the stack in all).
  static constexpr int kMaxEntries = 1024;

  // Fills the tables; false when a topology is open or a table would hold
  // more than kMaxEntries (then test the pairs with IsMinkowskiFace).
  bool Build(const PosedPolyhedron& a, const PosedPolyhedron& b);

  // IsMinkowskiFace of edge ea of A and edge eb of B (after Build).
  bool IsMinkowskiFace(int ea, int eb) const {
    const double cba = arc_a_face_b_[ea * faces_b_ + faces_of_b_[eb][0]];
    const double dba = arc_a_face_b_[ea * faces_b_ + faces_of_b_[eb][1]];
    const double adc = arc_b_face_a_[eb * faces_a_ + faces_of_a_[ea][0]];
    const double bdc = arc_b_face_a_[eb * faces_a_ + faces_of_a_[ea][1]];
    return cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0;
  }

 private:
  const std::array<int, 2>* faces_of_a_ = nullptr;  // edge -> its two faces
  const std::array<int, 2>* faces_of_b_ = nullptr;
  int faces_a_ = 0, faces_b_ = 0;
  double arc_a_face_b_[kMaxEntries];  // [ea F_b + fb]: -n_B[fb] . (arc plane of ea)
  double arc_b_face_a_[kMaxEntries];  // [eb F_a + fa]: n_A[fa] . (arc plane of eb)
};

// Buffers of MinkowskiEdgePairs, reused between calls so that a warmed-up
// step allocates nothing.
struct EdgePairScratch {
  struct ArcBox {  // the box of a piece of an edge's arc
    Vec3 lo, hi;
    int arc = -1;   // the edge
  };
  std::vector<ArcBox> boxes_a, boxes_b;
  std::vector<int> cell_start;  // per grid cell: first entry in cell_arcs
  std::vector<int> cell_arcs;   // pieces of A (boxes_a) by cell
  std::vector<int> fill;
  std::vector<int64_t> pairs;   // ea * E_b + eb, sorted
};

// Every edge pair (ea, eb) of closed polyhedra a and b for which
// IsMinkowskiFace(a's normals of ea, -b's normals of eb) holds, as
// ea * E_b + eb in increasing order, in scratch->pairs.
void MinkowskiEdgePairs(const PosedPolyhedron& a, const PosedPolyhedron& b, EdgePairScratch* scratch);

}  // namespace contactsim
