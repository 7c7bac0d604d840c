// Box-box face clipping and edge contacts without posing (see box_box_manifold.h).
#include "service/collision/box_box_manifold.h"

#include <limits>

#include "service/collision/face_clip.h"
#include "service/collision/manifold_reduction.h"
#include "service/collision/polyhedron_manifold.h"

namespace contactsim {
namespace {

// A quad clipped by a quad's four side planes (face_clip.h).
using BoxClipPolygon = FixedClipPolygon<64>;

void BoxFaceManifold(const BoxPose& pa, const BoxPose& pb, const SatResult& sat, double margin, ContactSet* out) {
  const ConvexHull& topo = UnitBoxTopology();
  const bool ref_is_a = sat.axis.kind == SeparatingAxis::Kind::kFaceA;
  const BoxPose& ref = ref_is_a ? pa : pb;
  const BoxPose& inc = ref_is_a ? pb : pa;
  const int ref_face = ref_is_a ? sat.axis.a : sat.axis.b;
  const Vec3 n_ref = BoxFaceNormal(ref.R, ref_face);
  const ReferenceFace face{n_ref, BoxFaceOffset(n_ref, ref.x, ref.h, ref_face), ref_is_a ? n_ref : Vec3(-n_ref),
                           ref_is_a, ref_face};

  // incident face: most anti-parallel to the reference normal (first of equals)
  int inc_face = 0;
  double min_dot = std::numeric_limits<double>::infinity();
  for (int g = 0; g < 6; ++g) {
    const double d = BoxFaceNormal(inc.R, g).dot(n_ref);
    if (d < min_dot) {
      min_dot = d;
      inc_face = g;
    }
  }

  BoxClipPolygon incident, clipped;
  for (int v : topo.faces[inc_face].vertices) incident.push_back({BoxVertex(inc, v), static_cast<uint32_t>(v)});
  const std::vector<int>& loop_ids = topo.faces[ref_face].vertices;
  const Vec3 loop[4] = {BoxVertex(ref, loop_ids[0]), BoxVertex(ref, loop_ids[1]), BoxVertex(ref, loop_ids[2]),
                        BoxVertex(ref, loop_ids[3])};
  const BoxClipPolygon& poly =
      *ClipToReferenceFace([&](size_t j) -> const Vec3& { return loop[j]; }, 4, n_ref, &incident, &clipped);

  const size_t first = out->size();
  const double deepest = AppendFacePoints(face, inc_face, poly.data(), poly.size(), margin, out);
  if (ClippingLostTheDepth(deepest, -sat.separation)) {
    const auto inside_ref = [&](const Vec3& p) {
      for (int f = 0; f < 6; ++f) {
        const Vec3 n = BoxFaceNormal(ref.R, f);
        if (n.dot(p) - BoxFaceOffset(n, ref.x, ref.h, f) > kClipDepthTol) return false;
      }
      return true;
    };
    AppendDeepestIncidentVertex(
        8, [&](int v) { return BoxVertex(inc, v); }, inside_ref, face, first, margin, out);
  }
  ReduceManifold(first, out);
}

}  // namespace

void BoxBoxManifold(const BoxPose& pa, const BoxPose& pb, const SatResult& sat, double margin, ContactSet* out) {
  if (sat.axis.kind == SeparatingAxis::Kind::kEdges) {
    const auto& edge_a = UnitBoxTopology().edges[sat.axis.a];
    const auto& edge_b = UnitBoxTopology().edges[sat.axis.b];
    AppendEdgeContact(BoxVertex(pa, edge_a[0]), BoxVertex(pa, edge_a[1]), BoxVertex(pb, edge_b[0]),
                      BoxVertex(pb, edge_b[1]), sat, margin, out);
  } else if (sat.axis.kind != SeparatingAxis::Kind::kNone) {
    BoxFaceManifold(pa, pb, sat, margin, out);
  }
}

}  // namespace contactsim
