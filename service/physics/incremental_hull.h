// A triangulated convex hull of some of a cloud's points, grown one point
// at a time, with each remaining point's height above it kept up to date:
// the step of Quickhull (Barber, Dobkin and Huhdanpaa 1996, "The quickhull
// algorithm for convex hulls", ACM TOMS 22(4), section 3) that replaces the
// faces a new point sees by a cone from the point to their horizon. The
// hull vertex budget (hull_vertex_budget.h) asks it, round after round,
// for the point highest above the hull of those kept so far.
//
// A point's height is its largest signed distance to the hull's face
// planes. When a point is added, only the faces it sees are replaced, so a
// remaining point whose highest face survives keeps its height unless one
// of the new faces is higher; only the points whose highest face was
// replaced are measured against every face again. The heights are those
// of the hull built from scratch up to the rounding of a plane through
// other corners of the same (within the tolerance) coplanar face.
//
// Where the cone step cannot be taken safely (the faces the point sees do
// not form one disk, or a new face has no area: nearly coplanar points),
// the hull is built again from its points by qhull (quickhull.h) and every
// height measured anew, as a hull from scratch each round would.
#pragma once

#include <array>
#include <vector>

#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

class IncrementalHull {
 public:
  // `points` must outlive the hull; `tolerance` (m) as Quickhull takes it:
  // a point within it of a face plane is not above that face.
  IncrementalHull(const std::vector<Vec3>& points, double tolerance);

  // Starts from the tetrahedron of four of the points (InitialTetrahedron).
  void Start(const std::array<int, 4>& corners);

  // The point highest above the hull (the lowest index among equal
  // heights), or -1 when none is above it by more than the tolerance.
  int Highest() const;

  // Adds point `i` (a point Highest returned). Fails only when qhull does
  // on a rebuild.
  Status Add(int i);

  // How many times Add rebuilt the hull with qhull (the fallback above).
  int rebuilds() const { return rebuilds_; }

 private:
  struct Face {
    std::array<int, 3> v;   // point indices, counter-clockwise seen from outside
    std::array<int, 3> nb;  // the face across edge v[k] -> v[k + 1]
    Vec3 a;                 // the point v0
    Vec3 n;                 // (v1 - v0) x (v2 - v0), unnormalised
    double len = 0.0;       // |n|
    bool alive = true;
  };
  struct HorizonEdge {
    int a, b, outside;  // a -> b as the visible face held it; the face beyond
  };

  int AddFace(int a, int b, int c);
  double Height(int point, const Face& f) const;
  // live_ from faces_ (after faces were added or killed).
  void CollectLive();
  // Re-measures point p against every live face.
  void MeasureAll(int p);
  // The faces `eye` sees, flooded from `seed`; false when their horizon is
  // not one loop (then nothing changed).
  bool Horizon(int eye, int seed, std::vector<int>* visible, std::vector<HorizonEdge>* loop);
  // The cone step; false when it cannot be taken (see above).
  bool Cone(int eye);
  // The hull of the added points by qhull, every height measured anew.
  Status Rebuild();
  // Fills the faces' neighbours from their edges; false when an edge has
  // no twin.
  bool Connect();

  const std::vector<Vec3>& points_;
  double tol_;
  std::vector<Face> faces_;
  std::vector<int> live_;       // the faces alive, so that a point is measured against them alone
  std::vector<int> added_;
  std::vector<double> height_;  // -inf for a point added or within the tolerance
  std::vector<int> top_face_;   // the face of each point's height
  std::vector<int> stamp_;      // per face: the round that found it visible
  int round_ = 0;
  bool cone_ok_ = true;         // false after a rebuild gave a hull the cone step cannot grow
  int rebuilds_ = 0;
};

}  // namespace contactsim
