// The triangulated hull of a point cloud by qhull (Barber, Dobkin and
// Huhdanpaa 1996, "The quickhull algorithm for convex hulls", ACM TOMS
// 22(4); libqhull_r, the reentrant library, so several threads may build
// hulls at once). Options:
//   Qt   triangulated output: merged facets come as triangles, which
//        BuildConvexHull merges back into polygon faces;
//   Q5   no check of the outer planes after the hull is built
//        (qh_check_maxout): it moves qhull's bound on how far a point lies
//        outside its facet, which no output here uses, and was 5% of
//        loading R2D2 (BENCHMARKS.md, "Robot models: load time");
//   C-t  pre-merge facets whose centrums lie within t of their neighbours'
//        planes, t the caller's tolerance, so nearly coplanar points do not
//        make slivers.
// A cloud that spans no volume is refused before qhull sees it, with the
// reason (InitialTetrahedron).
#include "service/physics/quickhull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <sstream>
#include <string>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace contactsim {
namespace {

// Relative distance tolerance of HullTolerance (quickhull.h).
constexpr double kRelativeTolerance = 1e-9;

// qhull's messages go to a memory stream, so a refusal carries them in its
// Status instead of printing to the server's stderr.
class MessageStream {
 public:
  MessageStream() : file_(open_memstream(&text_, &size_)) {}
  ~MessageStream() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(text_);
  }
  FILE* file() const { return file_; }
  // The first line qhull wrote, without its "QH6154 " style code.
  std::string FirstLine() {
    if (file_ == nullptr) return "";
    std::fflush(file_);
    std::string all(text_ == nullptr ? "" : text_, size_);
    std::string line = all.substr(0, all.find('\n'));
    if (line.size() > 7 && line[0] == 'Q' && line[1] == 'H') line = line.substr(line.find(' ') + 1);
    return line;
  }

 private:
  char* text_ = nullptr;
  size_t size_ = 0;
  FILE* file_ = nullptr;
};

// The triangles of qhull's facets as point indices, counter-clockwise seen
// from outside (each against qhull's outward facet normal), the largest
// first: BuildConvexHull floods coplanar groups from the first triangle of
// each, and a sliver that Qt leaves in a merged facet must not seed one.
std::vector<std::array<int, 3>> FacetTriangles(qhT* qh, const std::vector<Vec3>& points) {
  std::vector<std::array<int, 3>> out;
  std::vector<double> area;
  facetT* facet;
  FORALLfacets {
    if (qh_setsize(qh, facet->vertices) != 3) continue;
    std::array<int, 3> t;
    int k = 0;
    vertexT *vertex, **vertexp;
    FOREACHvertex_(facet->vertices) t[k++] = qh_pointid(qh, vertex->point);
    const Vec3 n = (points[t[1]] - points[t[0]]).cross(points[t[2]] - points[t[0]]);
    if (n.dot(Vec3(facet->normal[0], facet->normal[1], facet->normal[2])) < 0.0) std::swap(t[1], t[2]);
    out.push_back(t);
    area.push_back(n.norm());
  }
  std::vector<int> order(out.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return area[a] > area[b]; });
  std::vector<std::array<int, 3>> sorted;
  for (int i : order) sorted.push_back(out[i]);
  return sorted;
}

}  // namespace

Status InitialTetrahedron(const std::vector<Vec3>& p, double tol, std::array<int, 4>* corners) {
  int extreme[6] = {0, 0, 0, 0, 0, 0};
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    for (int k = 0; k < 3; ++k) {
      if (p[i][k] < p[extreme[2 * k]][k]) extreme[2 * k] = i;
      if (p[i][k] > p[extreme[2 * k + 1]][k]) extreme[2 * k + 1] = i;
    }
  }
  std::array<int, 4>& t = *corners;
  t = {0, 0, 0, 0};
  double best = -1.0;
  for (int i = 0; i < 6; ++i) {
    for (int j = i + 1; j < 6; ++j) {
      const double d = (p[extreme[i]] - p[extreme[j]]).norm();
      if (d > best) best = d, t[0] = extreme[i], t[1] = extreme[j];
    }
  }
  auto degenerate = [tol](const std::string& why) {
    std::ostringstream msg;
    msg << "points are coplanar: " << why << " (tolerance " << tol << " m)";
    return Status::InvalidArgument(msg.str());
  };
  if (best <= tol) return degenerate("all points coincide");
  const Vec3 axis = (p[t[1]] - p[t[0]]).normalized();
  best = -1.0;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    const double d = (p[i] - p[t[0]]).cross(axis).norm();
    if (d > best) best = d, t[2] = i;
  }
  if (best <= tol) return degenerate("they are collinear");
  const Vec3 n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).normalized();
  best = -1.0;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    const double d = std::abs(n.dot(p[i] - p[t[0]]));
    if (d > best) best = d, t[3] = i;
  }
  if (best <= tol) return degenerate("they span no volume");
  return Status::Ok();
}

double HullTolerance(const std::vector<Vec3>& points) {
  if (points.empty()) return 0.0;
  Vec3 lo = points[0], hi = points[0];
  for (const Vec3& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double scale = (hi - lo).norm() + 1e-3 * std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
  return kRelativeTolerance * std::max(scale, std::numeric_limits<double>::min());
}

Status Quickhull(const std::vector<Vec3>& points, double tolerance,
                 std::vector<std::array<int, 3>>* triangles) {
  std::array<int, 4> corners;
  Status span = InitialTetrahedron(points, tolerance, &corners);
  if (!span.ok()) return span;
  std::vector<coordT> coords;
  coords.reserve(3 * points.size());
  for (const Vec3& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  std::ostringstream flags;
  flags.precision(17);
  flags << "qhull Qt Q5 C-" << tolerance;
  std::string options = flags.str();
  MessageStream messages;
  qhT qh_qh;
  qhT* qh = &qh_qh;
  qh_zero(qh, messages.file());
  const int exit_code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, &options[0],
                                     nullptr, messages.file());
  if (exit_code == 0) *triangles = FacetTriangles(qh, points);
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  if (exit_code == 0) return Status::Ok();
  const std::string why = messages.FirstLine();
  return Status::InvalidArgument("convex hull: qhull failed (code " + std::to_string(exit_code) + ")" +
                                 (why.empty() ? "" : ": " + why));
}

}  // namespace contactsim
