// Edge pairs that form Minkowski faces, by a grid over the Gauss map (see
// minkowski_edge_pairs.h).
#include "service/collision/minkowski_edge_pairs.h"

#include <algorithm>
#include <cmath>

namespace contactsim {
namespace {

using ArcBox = EdgePairScratch::ArcBox;

// Added to every arc's box: a pair that IsMinkowskiFace accepts by round-off
// although its arcs miss each other misses by round-off only (~1e-16 on unit
// vectors, ~1e-10 along arcs crossing at the 1e-6 angle below which edge
// pairs are skipped as parallel, kSatParallelSin), so 1e-6 keeps every pair
// the test accepts in the candidates.
constexpr double kArcPad = 1e-6;

// Grid cells per axis at most: 24^3 cells of which ~1,800 touch the sphere.
constexpr int kMaxCells = 24;

// The box of the shorter arc from unit p to unit q: a point of the arc lies
// within 1 - cos(theta/2) = 1 - |p + q|/2 of the chord pq.
ArcBox ArcBounds(const Vec3& p, const Vec3& q) {
  const double pad = std::max(0.0, 1.0 - 0.5 * (p + q).norm()) + kArcPad;
  return {p.cwiseMin(q) - Vec3::Constant(pad), p.cwiseMax(q) + Vec3::Constant(pad), -1};
}

// The arc from unit p to unit q as pieces no longer than `piece` (chord),
// each with its box (a long arc's one box would cover a slab of cells the arc
// never crosses). The pieces' ends p + (q - p) t, normalised, lie on the arc.
// A nearly half-circle arc (|p + q| small: only a flat hull's rim) stays
// whole: its midpoints would be normalised from near zero.
void AddArcPieces(const Vec3& p, const Vec3& q, int arc, double piece, std::vector<ArcBox>* boxes) {
  const bool whole = (p + q).norm() < 0.1;
  const int count = whole ? 1 : std::max(1, static_cast<int>(std::ceil((q - p).norm() / piece)));
  Vec3 from = p;
  for (int i = 1; i <= count; ++i) {
    const Vec3 to = i == count ? q : Vec3((p + (q - p) * (static_cast<double>(i) / count)).normalized());
    ArcBox box = ArcBounds(from, to);
    box.arc = arc;
    boxes->push_back(box);
    from = to;
  }
}

// A uniform grid of k^3 cells over [-1, 1]^3; coordinates outside fall in
// the border cells (monotone, so a box's cells stay a contiguous range).
struct Grid {
  int k = 1;
  int Cell(double x) const {
    const int c = static_cast<int>(std::floor((x + 1.0) * 0.5 * k));
    return std::clamp(c, 0, k - 1);
  }
  int Index(int ix, int iy, int iz) const { return (ix * k + iy) * k + iz; }
  int Index(const Vec3& p) const { return Index(Cell(p.x()), Cell(p.y()), Cell(p.z())); }
};

bool Overlap(const ArcBox& s, const ArcBox& t) {
  return s.lo.x() <= t.hi.x() && t.lo.x() <= s.hi.x() && s.lo.y() <= t.hi.y() && t.lo.y() <= s.hi.y() &&
         s.lo.z() <= t.hi.z() && t.lo.z() <= s.hi.z();
}

// Calls fn(cell) for every cell the box covers.
template <typename Fn>
void ForCells(const Grid& g, const ArcBox& box, Fn fn) {
  const int x0 = g.Cell(box.lo.x()), x1 = g.Cell(box.hi.x());
  const int y0 = g.Cell(box.lo.y()), y1 = g.Cell(box.hi.y());
  const int z0 = g.Cell(box.lo.z()), z1 = g.Cell(box.hi.z());
  for (int ix = x0; ix <= x1; ++ix) {
    for (int iy = y0; iy <= y1; ++iy) {
      for (int iz = z0; iz <= z1; ++iz) fn(g.Index(ix, iy, iz));
    }
  }
}

// The pieces of A by cell (counting sort into compressed rows).
void FillGrid(const Grid& g, EdgePairScratch* s) {
  const int cells = g.k * g.k * g.k;
  s->cell_start.assign(cells + 1, 0);
  for (const ArcBox& box : s->boxes_a) ForCells(g, box, [&](int c) { ++s->cell_start[c + 1]; });
  for (int c = 0; c < cells; ++c) s->cell_start[c + 1] += s->cell_start[c];
  s->cell_arcs.resize(s->cell_start[cells]);
  s->fill.assign(s->cell_start.begin(), s->cell_start.end() - 1);
  for (int i = 0; i < static_cast<int>(s->boxes_a.size()); ++i) {
    ForCells(g, s->boxes_a[i], [&](int c) { s->cell_arcs[s->fill[c]++] = i; });
  }
}

}  // namespace

bool IsMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const Vec3 b_x_a = b.cross(a);
  const Vec3 d_x_c = d.cross(c);
  const double cba = c.dot(b_x_a);
  const double dba = d.dot(b_x_a);
  const double adc = a.dot(d_x_c);
  const double bdc = b.dot(d_x_c);
  return cba * dba < 0.0 && adc * bdc < 0.0 && cba * bdc > 0.0;
}

bool HasClosedTopology(const PosedPolyhedron& poly) {
  for (int e = 0; e < static_cast<int>(poly.edge_dirs.size()); ++e) {
    if (EdgeFaces(poly, e) == nullptr) return false;
  }
  return true;
}

bool GaussArcTable::Build(const PosedPolyhedron& a, const PosedPolyhedron& b) {
  if (!HasClosedTopology(a) || !HasClosedTopology(b)) return false;
  const int edges_a = static_cast<int>(a.edge_dirs.size());
  const int edges_b = static_cast<int>(b.edge_dirs.size());
  faces_a_ = static_cast<int>(a.normals.size());
  faces_b_ = static_cast<int>(b.normals.size());
  if (edges_a * faces_b_ > kMaxEntries || edges_b * faces_a_ > kMaxEntries) return false;
  faces_of_a_ = a.topology->edge_faces.data();
  faces_of_b_ = b.topology->edge_faces.data();
  // the products of IsMinkowskiFace(a, b, c, d) with a, b of A and c, d = -n_B
  for (int ea = 0; ea < edges_a; ++ea) {
    const Vec3 b_x_a = a.normals[faces_of_a_[ea][1]].cross(a.normals[faces_of_a_[ea][0]]);
    for (int f = 0; f < faces_b_; ++f) arc_a_face_b_[ea * faces_b_ + f] = (-b.normals[f]).dot(b_x_a);
  }
  for (int eb = 0; eb < edges_b; ++eb) {
    const Vec3 d_x_c = (-b.normals[faces_of_b_[eb][1]]).cross(-b.normals[faces_of_b_[eb][0]]);
    for (int f = 0; f < faces_a_; ++f) arc_b_face_a_[eb * faces_a_ + f] = a.normals[f].dot(d_x_c);
  }
  return true;
}

void MinkowskiEdgePairs(const PosedPolyhedron& a, const PosedPolyhedron& b, EdgePairScratch* s) {
  const int edges_a = static_cast<int>(a.edge_dirs.size());
  const int edges_b = static_cast<int>(b.edge_dirs.size());
  const auto& edge_faces_a = a.topology->edge_faces;
  const auto& edge_faces_b = b.topology->edge_faces;
  // ~2 arcs of A per cell touching the sphere (pi k^2 of them)
  Grid g;
  g.k = std::clamp(static_cast<int>(std::sqrt(edges_a / (2.0 * M_PI))) + 1, 1, kMaxCells);
  const double piece = 2.0 / g.k;
  s->boxes_a.clear();
  s->boxes_b.clear();
  for (int e = 0; e < edges_a; ++e) {
    AddArcPieces(a.normals[edge_faces_a[e][0]], a.normals[edge_faces_a[e][1]], e, piece, &s->boxes_a);
  }
  for (int e = 0; e < edges_b; ++e) {
    AddArcPieces(-b.normals[edge_faces_b[e][0]], -b.normals[edge_faces_b[e][1]], e, piece, &s->boxes_b);
  }
  FillGrid(g, s);
  s->pairs.clear();
  for (const ArcBox& box_b : s->boxes_b) {
    const int eb = box_b.arc;
    const Vec3 c = -b.normals[edge_faces_b[eb][0]];
    const Vec3 d = -b.normals[edge_faces_b[eb][1]];
    ForCells(g, box_b, [&](int cell) {
      for (int k = s->cell_start[cell]; k < s->cell_start[cell + 1]; ++k) {
        const ArcBox& box_a = s->boxes_a[s->cell_arcs[k]];
        // each overlapping pair of pieces once: in the cell of its overlap's lower corner
        if (!Overlap(box_a, box_b) || g.Index(box_a.lo.cwiseMax(box_b.lo)) != cell) continue;
        const int ea = box_a.arc;
        if (!IsMinkowskiFace(a.normals[edge_faces_a[ea][0]], a.normals[edge_faces_a[ea][1]], c, d)) continue;
        s->pairs.push_back(static_cast<int64_t>(ea) * edges_b + eb);
      }
    });
  }
  // two arcs crossing near a joint of their pieces meet in more than one pair of pieces
  std::sort(s->pairs.begin(), s->pairs.end());
  s->pairs.erase(std::unique(s->pairs.begin(), s->pairs.end()), s->pairs.end());
}

}  // namespace contactsim
