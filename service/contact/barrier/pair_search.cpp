#include "service/contact/barrier/pair_search.h"

#include <algorithm>

#include "service/collision/triangle_surface.h"

namespace contactsim {
namespace {

// Box of a body-frame point X at both ends of the motion, grown by `grow`.
Aabb SweptPoint(const SearchBody& b, const Vec3& X, double grow) {
  const Vec3 x0 = AffinePoint(b.q, X), x1 = AffinePoint(b.q_end, X);
  Aabb box{x0.cwiseMin(x1), x0.cwiseMax(x1)};
  box.Inflate(grow);
  return box;
}

Aabb Merge(const Aabb& a, const Aabb& b) { return {a.min.cwiseMin(b.min), a.max.cwiseMax(b.max)}; }

}  // namespace

const PrimitivePairSearch::Boxes& PrimitivePairSearch::PrimitiveBoxes(const std::vector<SearchBody>& bodies, int i,
                                                                      double half) {
  Boxes& out = boxes_[i];
  if (out.ready) return out;
  const SearchBody& b = bodies[i];
  const BodyGeometry& g = *b.geometry;
  out.points.resize(g.points.size());
  for (size_t k = 0; k < g.points.size(); ++k) out.points[k] = SweptPoint(b, g.points[k], half + g.radius);
  out.edges.resize(g.edges.size());
  for (size_t k = 0; k < g.edges.size(); ++k) out.edges[k] = Merge(out.points[g.edges[k][0]], out.points[g.edges[k][1]]);
  out.triangles.resize(g.triangles.size());
  for (size_t k = 0; k < g.triangles.size(); ++k) {
    const auto& t = g.triangles[k];
    out.triangles[k] = Merge(Merge(out.points[t[0]], out.points[t[1]]), out.points[t[2]]);
  }
  out.ready = true;
  return out;
}

void PrimitivePairSearch::AddPlanePairs(const std::vector<SearchBody>& bodies, int plane, int solid, double reach,
                                        std::vector<CandidatePair>* out) const {
  const SearchBody& P = bodies[plane];
  const SearchBody& S = bodies[solid];
  const BodyGeometry& g = *S.geometry;
  // the plane's world normal and offset, as EvaluatePair takes them
  const Vec3 n = (AffineMatrix(P.q) * P.geometry->plane_normal).normalized();
  const double offset = P.geometry->plane_offset + n.dot(AffinePosition(P.q));
  // the body's box first: its lowest corner along n
  const Aabb& box = body_boxes_[solid];
  const Vec3 centre = 0.5 * (box.min + box.max), extent = 0.5 * (box.max - box.min);
  if (n.dot(centre) - n.cwiseAbs().dot(extent) - offset > reach) return;
  const int a = std::min(plane, solid), b = std::max(plane, solid);
  for (int i = 0; i < static_cast<int>(g.points.size()); ++i) {
    const double s0 = n.dot(AffinePoint(S.q, g.points[i])), s1 = n.dot(AffinePoint(S.q_end, g.points[i]));
    if (std::min(s0, s1) - offset - g.radius < reach) out->push_back({a, b, {PrimitiveKind::kPointPlane, i, 0, plane == a}});
  }
}

void PrimitivePairSearch::AddSurfacePairs(const std::vector<SearchBody>& bodies, int surface, int solid, double half,
                                          std::vector<CandidatePair>* out) {
  const SearchBody& F = bodies[surface];
  const Shape& shape = *F.geometry->surface.shape;
  const Mat3 R = AffineMatrix(F.q);
  const Vec3 x = AffinePosition(F.q);
  // whether a world box grown by the other half of the reach (the
  // triangles' boxes are not grown) holds part of a triangle
  // (`convex`: only triangles with a convex edge, the only ones an edge or
  // a triangle of the body is paired with: surface_primitives.h)
  auto near = [&](Aabb box, bool convex) {
    box.Inflate(half);
    bool any = false;
    ForEachSurfaceTriangle(shape, BoxInBodyFrame(box, R, x),
                           [&](const SurfaceTriangle& t) { any = any || !convex || t.convex_edges != 0; });
    return any;
  };
  if (!near(body_boxes_[solid], false)) return;
  const Boxes& B = PrimitiveBoxes(bodies, solid, half);
  const int a = std::min(surface, solid), b = std::max(surface, solid);
  const bool swapped = surface == a;
  const std::vector<Aabb>* boxes[3] = {&B.points, &B.edges, &B.triangles};
  const PrimitiveKind kinds[3] = {PrimitiveKind::kPointSurface, PrimitiveKind::kEdgeSurface,
                                  PrimitiveKind::kTriangleSurface};
  for (int k = 0; k < 3; ++k) {
    for (int i = 0; i < static_cast<int>(boxes[k]->size()); ++i) {
      if (near((*boxes[k])[i], k > 0)) out->push_back({a, b, {kinds[k], i, 0, swapped}});
    }
  }
}

void PrimitivePairSearch::AddSolidPairs(const std::vector<SearchBody>& bodies, int a, int b, double half,
                                        std::vector<CandidatePair>* out) {
  const BodyGeometry& ga = *bodies[a].geometry;
  const BodyGeometry& gb = *bodies[b].geometry;
  const Boxes& A = PrimitiveBoxes(bodies, a, half);
  const Boxes& B = PrimitiveBoxes(bodies, b, half);
  // the primitives of each side whose boxes reach the other body's box
  auto keep = [](const std::vector<Aabb>& boxes, const Aabb& other, std::vector<int>* kept) {
    kept->clear();
    for (int k = 0; k < static_cast<int>(boxes.size()); ++k) {
      if (boxes[k].Overlaps(other)) kept->push_back(k);
    }
  };
  const std::vector<Aabb>* boxes_a[3] = {&A.points, &A.edges, &A.triangles};
  const std::vector<Aabb>* boxes_b[3] = {&B.points, &B.edges, &B.triangles};
  for (int k = 0; k < 3; ++k) {
    keep(*boxes_a[k], body_boxes_[b], &kept_a_[k]);
    keep(*boxes_b[k], body_boxes_[a], &kept_b_[k]);
  }
  // (first side's primitives kind ka, second side's kind kb)
  auto pairs = [&](const std::vector<int>& first, const std::vector<Aabb>& first_boxes, const std::vector<int>& second,
                   const std::vector<Aabb>& second_boxes, PrimitiveKind kind, bool swapped) {
    for (int i : first) {
      for (int j : second) {
        if (first_boxes[i].Overlaps(second_boxes[j])) out->push_back({a, b, {kind, i, j, swapped}});
      }
    }
  };
  // the kinds and order of EnumeratePrimitivePairs
  pairs(kept_a_[0], A.points, kept_b_[2], B.triangles, PrimitiveKind::kPointTriangle, false);
  pairs(kept_b_[0], B.points, kept_a_[2], A.triangles, PrimitiveKind::kPointTriangle, true);
  pairs(kept_a_[1], A.edges, kept_b_[1], B.edges, PrimitiveKind::kEdgeEdge, false);
  if (gb.triangles.empty()) pairs(kept_a_[0], A.points, kept_b_[1], B.edges, PrimitiveKind::kPointEdge, false);
  if (ga.triangles.empty()) pairs(kept_b_[0], B.points, kept_a_[1], A.edges, PrimitiveKind::kPointEdge, true);
  if (ga.edges.empty() && gb.edges.empty()) pairs(kept_a_[0], A.points, kept_b_[0], B.points, PrimitiveKind::kPointPoint, false);
}

void PrimitivePairSearch::Find(const std::vector<SearchBody>& bodies, double reach, const JointPairSet& joined,
                               std::vector<CandidatePair>* out) {
  out->clear();
  const double half = 0.5 * reach;
  const int n = static_cast<int>(bodies.size());
  body_boxes_.assign(n, Aabb{});
  boxes_.resize(n);
  for (Boxes& b : boxes_) b.ready = false;
  std::vector<Aabb> solid_boxes;
  movable_.clear();
  solid_index_.clear();
  std::vector<int> planes, surfaces;
  for (int i = 0; i < n; ++i) {
    const SearchBody& b = bodies[i];
    if (b.geometry->plane) {
      planes.push_back(i);
      continue;
    }
    if (b.geometry->surface.shape != nullptr) {
      surfaces.push_back(i);
      continue;
    }
    if (b.geometry->points.empty()) continue;
    Aabb box = SweptPoint(b, b.geometry->points[0], half + b.geometry->radius);
    for (const Vec3& X : b.geometry->points) box = Merge(box, SweptPoint(b, X, half + b.geometry->radius));
    body_boxes_[i] = box;
    solid_index_.push_back(i);
    solid_boxes.push_back(box);
    movable_.push_back(b.movable);
  }
  sap_.FindPairs(solid_boxes, movable_, &body_pairs_);
  for (BodyPair& p : body_pairs_) p = {solid_index_[p.first], solid_index_[p.second]};
  for (const std::vector<int>* statics : {&planes, &surfaces}) {
    for (int p : *statics) {
      for (int s : solid_index_) {
        if (bodies[s].movable) body_pairs_.emplace_back(std::min(p, s), std::max(p, s));
      }
    }
  }
  body_pairs_.erase(std::remove_if(body_pairs_.begin(), body_pairs_.end(),
                                   [&](const BodyPair& p) {
                                     const RigidBody* a = bodies[p.first].body;
                                     const RigidBody* b = bodies[p.second].body;
                                     return a != nullptr && b != nullptr && !ShouldCollide(*a, *b, joined);
                                   }),
                    body_pairs_.end());
  std::sort(body_pairs_.begin(), body_pairs_.end());
  for (const BodyPair& p : body_pairs_) {
    const bool a_plane = bodies[p.first].geometry->plane, b_plane = bodies[p.second].geometry->plane;
    const bool a_surface = bodies[p.first].geometry->surface.shape != nullptr;
    const bool b_surface = bodies[p.second].geometry->surface.shape != nullptr;
    if (a_surface || b_surface) {
      AddSurfacePairs(bodies, a_surface ? p.first : p.second, a_surface ? p.second : p.first, half, out);
    } else if (a_plane || b_plane) {
      AddPlanePairs(bodies, a_plane ? p.first : p.second, a_plane ? p.second : p.first, reach, out);
    } else {
      AddSolidPairs(bodies, p.first, p.second, half, out);
    }
  }
}

}  // namespace contactsim
