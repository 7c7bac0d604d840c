// Per-pair separating-axis memory (see separating_axis_cache.h).
#include "service/collision/separating_axis_cache.h"

#include <algorithm>
#include <limits>

#include "service/collision/posed_polyhedron.h"

namespace contactsim {
namespace {

// A box or hull in its own frame: the topology scaled by `scale` (a box's
// half extents, 1 for a hull), placed by R and x.
struct BodyFrame {
  const ConvexHull* topology = nullptr;
  Vec3 scale = Vec3::Ones();
  bool is_box = false;
  Mat3 R = Mat3::Identity();
  Vec3 x = Vec3::Zero();
};

bool MakeBodyFrame(const RigidBody& body, BodyFrame* f) {
  if (body.shape.type == ShapeType::kBox) {
    f->topology = &UnitBoxTopology();
    f->scale = body.shape.half_extents;
    f->is_box = true;
  } else if (body.shape.type == ShapeType::kConvex && body.shape.hull != nullptr) {
    f->topology = body.shape.hull.get();
  } else {
    return false;
  }
  f->R = body.Rotation();
  f->x = body.x;
  return true;
}

// max over the body of u . p, for u and p in its own frame.
double Support(const BodyFrame& f, const Vec3& u) {
  if (f.is_box) return f.scale.dot(u.cwiseAbs());
  double best = -std::numeric_limits<double>::infinity();
  for (const Vec3& v : f.topology->vertices) best = std::max(best, u.dot(v));
  return best;
}

// Interval of the body projected on the world axis u.
void Project(const BodyFrame& f, const Vec3& u, double* lo, double* hi) {
  const Vec3 u_body = f.R.transpose() * u;
  const double centre = u.dot(f.x);
  *lo = centre - Support(f, -u_body);
  *hi = centre + Support(f, u_body);
}

// Outward unit normal (world) of face `face` and its plane offset. Scaling
// the unit box keeps its axis-aligned normals, and a hull is not scaled, so
// the topology's normal is the body's (PosePolyhedron's general S^-1 n
// reduces to it).
bool FacePlane(const BodyFrame& f, int face, Vec3* n_W, double* offset_W) {
  if (face < 0 || face >= static_cast<int>(f.topology->faces.size())) return false;
  const ConvexHull::Face& topo_face = f.topology->faces[face];
  const Vec3& n = topo_face.normal;
  *n_W = f.R * n;
  *offset_W = n.dot(f.topology->vertices[topo_face.vertices.front()].cwiseProduct(f.scale)) + n_W->dot(f.x);
  return true;
}

// Separation along face `face` of `ref`, its outward normal pointing at `other`.
bool FaceSeparation(const BodyFrame& ref, int face, const BodyFrame& other, Vec3* n_W, double* separation) {
  double offset;
  if (!FacePlane(ref, face, n_W, &offset)) return false;
  double lo, hi;
  Project(other, *n_W, &lo, &hi);
  *separation = lo - offset;
  return true;
}

bool EdgeDirection(const BodyFrame& f, int edge, Vec3* d_W) {
  if (edge < 0 || edge >= static_cast<int>(f.topology->edges.size())) return false;
  const auto& e = f.topology->edges[edge];
  *d_W = f.R * (f.topology->vertices[e[1]] - f.topology->vertices[e[0]]).cwiseProduct(f.scale).normalized();
  return true;
}

// Separation along one cached axis (AxisSeparation in polyhedron_sat.h on
// posed polyhedra gives the same value up to round-off).
bool BodyFrameSeparation(const BodyFrame& a, const BodyFrame& b, const SeparatingAxis& axis, double* separation) {
  Vec3 n;
  switch (axis.kind) {
    case SeparatingAxis::Kind::kFaceA: return FaceSeparation(a, axis.a, b, &n, separation);
    case SeparatingAxis::Kind::kFaceB: return FaceSeparation(b, axis.b, a, &n, separation);
    case SeparatingAxis::Kind::kEdges: {
      Vec3 da, db;
      if (!EdgeDirection(a, axis.a, &da) || !EdgeDirection(b, axis.b, &db)) return false;
      const Vec3 c = da.cross(db);
      const double len = c.norm();
      if (len < kSatParallelSin) return false;
      double lo_a, hi_a, lo_b, hi_b;
      Project(a, c / len, &lo_a, &hi_a);
      Project(b, c / len, &lo_b, &hi_b);
      *separation = std::max(lo_b - hi_a, lo_a - hi_b);
      return true;
    }
    case SeparatingAxis::Kind::kNone: break;
  }
  return false;
}

}  // namespace

const SeparatingAxis* SeparatingAxisCache::StillSeparatingAxis(const RigidBody& a, const RigidBody& b,
                                                               double margin) const {
  const SeparatingAxis* axis = Find(a.id, b.id);
  BodyFrame fa, fb;
  double separation;
  const bool separates = axis != nullptr && MakeBodyFrame(a, &fa) && MakeBodyFrame(b, &fb) &&
                         BodyFrameSeparation(fa, fb, *axis, &separation) && separation > margin;
  return separates ? axis : nullptr;
}

bool SeparatingAxisCache::Separates(const RigidBody& a, const RigidBody& b, double margin) const {
  return StillSeparatingAxis(a, b, margin) != nullptr;
}

bool SeparatingAxisCache::StillSeparates(const RigidBody& a, const RigidBody& b, double margin) {
  const bool hit = Separates(a, b, margin);
  ++(hit ? hits_ : misses_);
  return hit;
}

size_t SeparatingAxisCache::Place(BodyId a, BodyId b) const {
  Entry key;
  key.a = a;
  key.b = b;
  return std::lower_bound(entries_.begin(), entries_.end(), key) - entries_.begin();
}

const SeparatingAxis* SeparatingAxisCache::Find(BodyId a, BodyId b) const {
  const size_t place = Place(a, b);
  return At(place, a, b) ? &entries_[place].axis : nullptr;
}

void SeparatingAxisCache::Store(BodyId a, BodyId b, const SeparatingAxis& axis) {
  const size_t place = Place(a, b);
  if (At(place, a, b)) {
    entries_[place].axis = axis;
  } else {
    entries_.insert(entries_.begin() + place, Entry{a, b, axis});
  }
}

void SeparatingAxisCache::Erase(BodyId a, BodyId b) {
  const size_t place = Place(a, b);
  if (At(place, a, b)) entries_.erase(entries_.begin() + place);
}

void SeparatingAxisCache::Apply(const AxisCacheUpdate& update) {
  if (update.kind == AxisCacheUpdate::Kind::kStore) Store(update.a, update.b, update.axis);
  if (update.kind == AxisCacheUpdate::Kind::kErase) Erase(update.a, update.b);
  hits_ += update.hits;
  misses_ += update.misses;
}

void SeparatingAxisCache::Rebuild(const std::vector<AxisCacheUpdate>& updates) {
  next_.clear();
  for (const AxisCacheUpdate& u : updates) {
    hits_ += u.hits;
    misses_ += u.misses;
    if (u.kind == AxisCacheUpdate::Kind::kStore) next_.push_back(Entry{u.a, u.b, u.axis});
  }
  // the broadphase's pairs come sorted by body index, which follows the ids
  // in most worlds, so the sort rarely has anything to do
  if (!std::is_sorted(next_.begin(), next_.end())) std::sort(next_.begin(), next_.end());
  entries_.swap(next_);
}

void SeparatingAxisCache::Clear() {
  entries_.clear();
  hits_ = 0;
  misses_ = 0;
}

}  // namespace contactsim
