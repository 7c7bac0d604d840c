// Tessellated flat surfaces for the mesh and heightfield tests: an n x n
// grid of square cells, two triangles each, centred on the origin in the
// z = 0 plane, counter-clockwise seen from +z.
#pragma once

#include <memory>
#include <vector>

#include "service/collision/triangle_mesh.h"
#include "service/physics/math.h"

namespace contactsim {
namespace testing {

struct MeshData {
  std::vector<Vec3> vertices;
  std::vector<int> indices;
};

// (n + 1)^2 vertices, 2 n^2 triangles of side `cell` (m); `flip` splits
// each cell along the other diagonal.
inline MeshData GridMesh(int n, double cell, bool flip = false) {
  MeshData m;
  const double origin = -0.5 * n * cell;
  for (int r = 0; r <= n; ++r) {
    for (int c = 0; c <= n; ++c) m.vertices.emplace_back(origin + c * cell, origin + r * cell, 0.0);
  }
  auto id = [n](int r, int c) { return r * (n + 1) + c; };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      const int a = id(r, c), b = id(r, c + 1), d = id(r + 1, c + 1), e = id(r + 1, c);
      if (flip) {
        m.indices.insert(m.indices.end(), {a, b, e, b, d, e});
      } else {
        m.indices.insert(m.indices.end(), {a, b, d, a, d, e});
      }
    }
  }
  return m;
}

inline std::shared_ptr<const TriangleMesh> BuildGrid(int n, double cell, bool flip = false) {
  const MeshData m = GridMesh(n, cell, flip);
  std::shared_ptr<const TriangleMesh> mesh;
  const Status st = BuildTriangleMesh(m.vertices, m.indices, 1.0, &mesh);
  EXPECT_TRUE(st.ok()) << st.message();
  return mesh;
}

}  // namespace testing
}  // namespace contactsim
