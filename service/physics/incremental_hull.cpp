#include "service/physics/incremental_hull.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include "service/physics/quickhull.h"

namespace contactsim {
namespace {

constexpr double kBelow = -std::numeric_limits<double>::infinity();

int64_t ConeEdgeKey(int a, int b) { return (static_cast<int64_t>(a) << 32) | static_cast<uint32_t>(b); }

}  // namespace

IncrementalHull::IncrementalHull(const std::vector<Vec3>& points, double tolerance)
    : points_(points), tol_(tolerance), height_(points.size(), kBelow), top_face_(points.size(), -1) {}

int IncrementalHull::AddFace(int a, int b, int c) {
  Face f;
  f.v = {a, b, c};
  f.nb = {-1, -1, -1};
  f.a = points_[a];
  f.n = (points_[b] - f.a).cross(points_[c] - f.a);
  f.len = f.n.norm();
  faces_.push_back(f);
  stamp_.push_back(-1);
  return static_cast<int>(faces_.size()) - 1;
}

// as the budget measured it: the distance above the plane through the
// face's first corner
double IncrementalHull::Height(int point, const Face& f) const {
  return f.n.dot(points_[point] - f.a) / f.len;
}

void IncrementalHull::CollectLive() {
  live_.clear();
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
    if (faces_[f].alive && faces_[f].len > 0.0) live_.push_back(f);
  }
}

// the largest height whichever face attains it: the face kept only tells
// when the height must be measured again
void IncrementalHull::MeasureAll(int p) {
  double best = kBelow;
  int top = -1;
  for (int f : live_) {
    const double h = Height(p, faces_[f]);
    if (h > best) best = h, top = f;
  }
  // a point within the tolerance of the hull stays inside it as it grows
  height_[p] = best > tol_ ? best : kBelow;
  top_face_[p] = best > tol_ ? top : -1;
}

bool IncrementalHull::Connect() {
  std::unordered_map<int64_t, int> edge_face;
  for (int f = 0; f < static_cast<int>(faces_.size()); ++f) {
    for (int k = 0; k < 3; ++k) edge_face[ConeEdgeKey(faces_[f].v[k], faces_[f].v[(k + 1) % 3])] = f;
  }
  bool ok = true;
  for (Face& f : faces_) {
    for (int k = 0; k < 3; ++k) {
      const auto twin = edge_face.find(ConeEdgeKey(f.v[(k + 1) % 3], f.v[k]));
      f.nb[k] = twin == edge_face.end() ? -1 : twin->second;
      ok = ok && f.nb[k] >= 0;
    }
    ok = ok && f.len > 0.0;
  }
  return ok;
}

void IncrementalHull::Start(const std::array<int, 4>& corners) {
  faces_.clear();
  stamp_.clear();
  added_.assign(corners.begin(), corners.end());
  // each face wound so that the fourth corner lies below it
  for (int skip = 0; skip < 4; ++skip) {
    std::array<int, 3> t;
    for (int k = 0, j = 0; k < 4; ++k) {
      if (k != skip) t[j++] = corners[k];
    }
    const Vec3 n = (points_[t[1]] - points_[t[0]]).cross(points_[t[2]] - points_[t[0]]);
    if (n.dot(points_[corners[skip]] - points_[t[0]]) > 0.0) std::swap(t[1], t[2]);
    AddFace(t[0], t[1], t[2]);
  }
  cone_ok_ = Connect();
  CollectLive();
  for (int p = 0; p < static_cast<int>(points_.size()); ++p) MeasureAll(p);
  for (int c : corners) height_[c] = kBelow, top_face_[c] = -1;
}

int IncrementalHull::Highest() const {
  int eye = -1;
  double highest = tol_;
  for (int p = 0; p < static_cast<int>(height_.size()); ++p) {
    if (height_[p] > highest) highest = height_[p], eye = p;
  }
  return eye;
}

bool IncrementalHull::Horizon(int eye, int seed, std::vector<int>* visible, std::vector<HorizonEdge>* loop) {
  ++round_;
  visible->assign(1, seed);
  stamp_[seed] = round_;
  for (size_t q = 0; q < visible->size(); ++q) {
    for (int g : faces_[(*visible)[q]].nb) {
      if (stamp_[g] == round_ || !(Height(eye, faces_[g]) > tol_)) continue;
      stamp_[g] = round_;
      visible->push_back(g);
    }
  }
  // the edges between seen and unseen faces, chained head to tail
  std::unordered_map<int, HorizonEdge> from;
  for (int f : *visible) {
    for (int k = 0; k < 3; ++k) {
      const int g = faces_[f].nb[k];
      if (stamp_[g] == round_) continue;
      const HorizonEdge e{faces_[f].v[k], faces_[f].v[(k + 1) % 3], g};
      if (!from.emplace(e.a, e).second) return false;  // two loops touch at a vertex
    }
  }
  loop->clear();
  if (from.empty()) return false;
  int v = from.begin()->first;
  do {
    const auto it = from.find(v);
    if (it == from.end() || loop->size() > from.size()) return false;
    loop->push_back(it->second);
    v = it->second.b;
  } while (v != loop->front().a);
  return loop->size() == from.size();  // one loop, not several
}

bool IncrementalHull::Cone(int eye) {
  std::vector<int> visible;
  std::vector<HorizonEdge> loop;
  if (!cone_ok_ || !Horizon(eye, top_face_[eye], &visible, &loop)) return false;
  const int first = static_cast<int>(faces_.size());
  const int m = static_cast<int>(loop.size());
  for (int j = 0; j < m; ++j) {
    const int f = AddFace(loop[j].a, loop[j].b, eye);
    if (!(faces_[f].len > 0.0)) return false;
    Face& out = faces_[loop[j].outside];
    for (int k = 0; k < 3; ++k) {
      if (out.v[k] == loop[j].b && out.v[(k + 1) % 3] == loop[j].a) out.nb[k] = f;
    }
    faces_[f].nb = {loop[j].outside, first + (j + 1) % m, first + (j + m - 1) % m};
  }
  for (int f : visible) faces_[f].alive = false;
  CollectLive();
  // each remaining point: against the new faces only, unless its highest
  // face is gone
  for (int p = 0; p < static_cast<int>(points_.size()); ++p) {
    if (top_face_[p] < 0) continue;
    if (!faces_[top_face_[p]].alive) {
      MeasureAll(p);
      continue;
    }
    for (int f = first; f < first + m; ++f) {
      const double h = Height(p, faces_[f]);
      if (h > height_[p]) height_[p] = h, top_face_[p] = f;
    }
  }
  return true;
}

Status IncrementalHull::Rebuild() {
  ++rebuilds_;
  std::vector<Vec3> kept;
  for (int i : added_) kept.push_back(points_[i]);
  std::vector<std::array<int, 3>> triangles;
  if (Status st = Quickhull(kept, tol_, &triangles); !st.ok()) return st;
  faces_.clear();
  stamp_.clear();
  for (const auto& t : triangles) AddFace(added_[t[0]], added_[t[1]], added_[t[2]]);
  cone_ok_ = Connect();
  CollectLive();
  std::vector<bool> is_added(points_.size(), false);
  for (int i : added_) is_added[i] = true;
  for (int p = 0; p < static_cast<int>(points_.size()); ++p) {
    if (is_added[p]) {
      height_[p] = kBelow, top_face_[p] = -1;
    } else {
      MeasureAll(p);
    }
  }
  return Status::Ok();
}

Status IncrementalHull::Add(int i) {
  added_.push_back(i);
  const bool grown = top_face_[i] >= 0 && Cone(i);
  height_[i] = kBelow;
  top_face_[i] = -1;
  return grown ? Status::Ok() : Rebuild();
}

}  // namespace contactsim
