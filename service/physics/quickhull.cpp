// Quickhull (Barber, Dobkin and Huhdanpaa 1996):
//   1. a tetrahedron of extreme points;
//   2. every other point goes to the outside set of the face it is furthest
//      above (points on or under every face are inside and dropped);
//   3. while a face has an outside set: take its furthest point (the eye),
//      flood the faces the eye sees, replace them by a cone of triangles from
//      the horizon to the eye, and redistribute their outside points.
// With a vertex budget the faces are not taken in stack order: each round
// takes the eye furthest above the current hull over all faces, and the
// build stops once it has added as many vertices as the budget (qhull's
// "TA" option, which MuJoCo's maxhullvert uses): the hull so far is a
// greedy inner approximation, spanned by points of the cloud.
// Faces are found across edges by a map from directed edge to face; each
// edge (a, b) of a counter-clockwise face has its twin (b, a) in the
// neighbour.
#include "service/physics/quickhull.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdint>
#include <sstream>
#include <string>
#include <unordered_map>
#include <utility>

namespace contactsim {
namespace {

// Relative distance tolerance of HullTolerance (quickhull.h).
constexpr double kRelativeTolerance = 1e-9;

struct Face {
  std::array<int, 3> v;
  Vec3 normal;
  double offset = 0.0;
  std::vector<int> outside;
  bool alive = true;
};

int64_t EdgeKey(int a, int b) { return (static_cast<int64_t>(a) << 32) | static_cast<uint32_t>(b); }

class Builder {
 public:
  Builder(const std::vector<Vec3>& points, double tolerance) : p_(points), tol_(tolerance) {}

  Status Run(int max_vertices, std::vector<std::array<int, 3>>* triangles) {
    int simplex[4] = {0, 0, 0, 0};
    Status status = InitialSimplex(simplex);
    if (!status.ok()) return status;
    std::vector<int> rest;
    for (int i = 0; i < static_cast<int>(p_.size()); ++i) {
      if (i != simplex[0] && i != simplex[1] && i != simplex[2] && i != simplex[3]) rest.push_back(i);
    }
    std::vector<int> first_faces;
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f) first_faces.push_back(f);
    Distribute(rest, first_faces);
    if (max_vertices > 0) {
      status = RunToBudget(max_vertices);
    } else {
      std::vector<int> stack = first_faces;
      while (status.ok() && !stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        if (!faces_[f].alive || faces_[f].outside.empty()) continue;
        status = AddEye(f, &stack);
      }
    }
    if (!status.ok()) return status;
    triangles->clear();
    for (const Face& face : faces_) {
      if (face.alive) triangles->push_back(face.v);
    }
    return Status::Ok();
  }

 private:
  double Distance(int f, int i) const { return faces_[f].normal.dot(p_[i]) - faces_[f].offset; }

  // The alive face whose furthest outside point is highest above it; -1
  // when no point is outside.
  int HighestOutside() const {
    int best_face = -1;
    double height = 0.0;
    for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
      if (!faces_[f].alive) continue;
      for (int i : faces_[f].outside) {
        const double d = Distance(f, i);
        if (d > height) height = d, best_face = f;
      }
    }
    return best_face;
  }

  // Adds the globally highest eye while fewer than `max_vertices` points
  // have been added (the simplex's four, then one per eye), so the hull has
  // at most that many vertices.
  Status RunToBudget(int max_vertices) {
    std::vector<int> cone;
    for (int added = 4; added < max_vertices; ++added) {
      const int f = HighestOutside();
      if (f < 0) break;
      Status status = AddEye(f, &cone);
      if (!status.ok()) return status;
      cone.clear();
    }
    return Status::Ok();
  }

  // The two furthest apart of the six axis extremes, the point furthest from
  // their line, and the point furthest from the plane of those three.
  Status InitialSimplex(int simplex[4]) {
    int extreme[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < static_cast<int>(p_.size()); ++i) {
      for (int k = 0; k < 3; ++k) {
        if (p_[i][k] < p_[extreme[2 * k]][k]) extreme[2 * k] = i;
        if (p_[i][k] > p_[extreme[2 * k + 1]][k]) extreme[2 * k + 1] = i;
      }
    }
    double best = -1.0;
    for (int a = 0; a < 6; ++a) {
      for (int b = a + 1; b < 6; ++b) {
        const double d = (p_[extreme[a]] - p_[extreme[b]]).norm();
        if (d > best) {
          best = d;
          simplex[0] = extreme[a];
          simplex[1] = extreme[b];
        }
      }
    }
    if (best <= tol_) return Degenerate("all points coincide");
    const Vec3 axis = (p_[simplex[1]] - p_[simplex[0]]).normalized();
    best = -1.0;
    for (int i = 0; i < static_cast<int>(p_.size()); ++i) {
      const double d = (p_[i] - p_[simplex[0]]).cross(axis).norm();
      if (d > best) {
        best = d;
        simplex[2] = i;
      }
    }
    if (best <= tol_) return Degenerate("they are collinear");
    const Vec3 n = (p_[simplex[1]] - p_[simplex[0]]).cross(p_[simplex[2]] - p_[simplex[0]]).normalized();
    best = -1.0;
    for (int i = 0; i < static_cast<int>(p_.size()); ++i) {
      const double d = std::abs(n.dot(p_[i] - p_[simplex[0]]));
      if (d > best) {
        best = d;
        simplex[3] = i;
      }
    }
    if (best <= tol_) return Degenerate("the furthest point is " + std::to_string(best) + " m off their plane");
    const int s0 = simplex[0], s1 = simplex[1], s2 = simplex[2], s3 = simplex[3];
    const int tri[4][4] = {{s0, s1, s2, s3}, {s0, s1, s3, s2}, {s0, s2, s3, s1}, {s1, s2, s3, s0}};
    for (const auto& t : tri) {
      // wind each face so that the opposite vertex is behind it
      const Vec3 normal = (p_[t[1]] - p_[t[0]]).cross(p_[t[2]] - p_[t[0]]);
      const bool flip = normal.dot(p_[t[3]] - p_[t[0]]) > 0.0;
      const int f = flip ? NewFace(t[0], t[2], t[1]) : NewFace(t[0], t[1], t[2]);
      if (f < 0) return Degenerate("the initial tetrahedron is inconsistent");
    }
    return Status::Ok();
  }

  Status Degenerate(const std::string& why) const {
    std::ostringstream msg;
    msg << "points are coplanar: " << why << " (tolerance " << tol_ << " m)";
    return Status::InvalidArgument(msg.str());
  }

  // Adds the face (a, b, c) and registers its directed edges; -1 when an
  // edge is already taken (inconsistent topology from round-off).
  int NewFace(int a, int b, int c) {
    Face face;
    face.v = {a, b, c};
    const Vec3 n = (p_[b] - p_[a]).cross(p_[c] - p_[a]);
    face.normal = n.normalized();
    // plane through the triangle's centroid: the least biased of its points
    face.offset = face.normal.dot((p_[a] + p_[b] + p_[c]) / 3.0);
    const int f = static_cast<int>(faces_.size());
    for (int k = 0; k < 3; ++k) {
      if (!edge_face_.emplace(EdgeKey(face.v[k], face.v[(k + 1) % 3]), f).second) return -1;
    }
    faces_.push_back(std::move(face));
    return f;
  }

  void KillFace(int f) {
    Face& face = faces_[f];
    face.alive = false;
    for (int k = 0; k < 3; ++k) edge_face_.erase(EdgeKey(face.v[k], face.v[(k + 1) % 3]));
  }

  // Each point joins the outside set of the face it is furthest above.
  void Distribute(const std::vector<int>& points, const std::vector<int>& faces) {
    for (int i : points) {
      int best_face = -1;
      double best = tol_;
      for (int f : faces) {
        const double d = Distance(f, i);
        if (d > best) {
          best = d;
          best_face = f;
        }
      }
      if (best_face >= 0) faces_[best_face].outside.push_back(i);
    }
  }

  Status AddEye(int start, std::vector<int>* stack) {
    int eye = faces_[start].outside.front();
    for (int i : faces_[start].outside) {
      if (Distance(start, i) > Distance(start, eye)) eye = i;
    }
    // flood the visible faces; a face seen from the eye within tol_ is not
    // visible, which keeps near-coplanar neighbours (merged later)
    ++stamp_;
    mark_.resize(faces_.size(), 0);
    visible_.resize(faces_.size(), false);
    std::vector<int> seen = {start};
    std::vector<std::pair<int, int>> horizon;
    mark_[start] = stamp_;
    visible_[start] = true;
    for (std::size_t q = 0; q < seen.size(); ++q) {
      const Face& face = faces_[seen[q]];
      for (int k = 0; k < 3; ++k) {
        const int a = face.v[k], b = face.v[(k + 1) % 3];
        const auto twin = edge_face_.find(EdgeKey(b, a));
        if (twin == edge_face_.end()) return Status::InvalidArgument("convex hull: open surface (round-off)");
        const int nb = twin->second;
        if (mark_[nb] != stamp_) {
          mark_[nb] = stamp_;
          visible_[nb] = Distance(nb, eye) > tol_;
          if (visible_[nb]) seen.push_back(nb);
        }
        if (!visible_[nb]) horizon.emplace_back(a, b);
      }
    }
    std::vector<int> orphans;
    for (int f : seen) {
      for (int i : faces_[f].outside) {
        if (i != eye) orphans.push_back(i);
      }
      faces_[f].outside.clear();
      KillFace(f);
    }
    std::vector<int> cone;
    for (const auto& edge : horizon) {
      const int f = NewFace(edge.first, edge.second, eye);
      if (f < 0) return Status::InvalidArgument("convex hull: non-manifold horizon (round-off); perturb the points");
      cone.push_back(f);
      stack->push_back(f);
    }
    Distribute(orphans, cone);
    return Status::Ok();
  }

  const std::vector<Vec3>& p_;
  const double tol_;
  std::vector<Face> faces_;
  std::unordered_map<int64_t, int> edge_face_;
  std::vector<int> mark_;
  std::vector<bool> visible_;
  int stamp_ = 0;
};

}  // namespace

double HullTolerance(const std::vector<Vec3>& points) {
  if (points.empty()) return 0.0;
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double scale = (hi - lo).norm() + 1e-3 * std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  return kRelativeTolerance * std::max(scale, std::numeric_limits<double>::min());
}

Status Quickhull(const std::vector<Vec3>& points, double tolerance,
                 std::vector<std::array<int, 3>>* triangles, int max_vertices) {
  Builder builder(points, tolerance);
  return builder.Run(max_vertices, triangles);
}

}  // namespace contactsim
