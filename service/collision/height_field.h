// A static heightfield: a regular grid of heights, each cell two triangles
// made on the fly from its four samples, so no triangle list is stored.
//
// Sample (r, c) lies at x = (c - (cols - 1) / 2) spacing_x,
// y = (r - (rows - 1) / 2) spacing_y, z = heights[r cols + c] in the body
// frame (the grid is centred on the body's origin). Cell (r, c) is split
// along its diagonal from (r, c) to (r + 1, c + 1): half 0 is
// (r, c), (r, c + 1), (r + 1, c + 1) and half 1 is (r, c), (r + 1, c + 1),
// (r + 1, c), both counter-clockwise seen from +z. An edge's activity
// (triangle_surface.h) comes from the triangle across it; the grid's border
// edges are open, hence active. The edges' bits are found once, when the
// field is built (two bytes a cell beside its eight of height), since a
// query asks for the same cells' triangles step after step.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "service/collision/aabb.h"
#include "service/collision/surface_triangle.h"
#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

// Most samples of one heightfield (a 4,096 x 4,096 grid).
constexpr int kMaxHeightSamples = 1 << 24;

struct HeightField {
  int rows = 0;            // samples along y, >= 2
  int cols = 0;            // samples along x, >= 2
  double spacing_x = 1.0;  // m, > 0
  double spacing_y = 1.0;  // m, > 0
  std::vector<double> heights;  // m, rows * cols, row-major (row r at y_r)
  double min_height = 0.0, max_height = 0.0;  // m
  // per cell r (cols - 1) + c: bits 6 half + k the active edge k of the
  // half, bits 6 half + 3 + k its convex edge k (SurfaceTriangle's bits)
  std::vector<uint16_t> edge_bits;

  Vec3 Sample(int r, int c) const {
    return Vec3((c - 0.5 * (cols - 1)) * spacing_x, (r - 0.5 * (rows - 1)) * spacing_y, heights[r * cols + c]);
  }
  // Triangle `half` (0 or 1) of cell (r, c), with its active edges.
  SurfaceTriangle Triangle(int r, int c, int half) const;
  // The same with its edges' bits found from the triangles across them
  // (what fills edge_bits).
  SurfaceTriangle TriangleWithNeighbours(int r, int c, int half) const;
  Aabb Bounds() const;

  // Calls visit(const SurfaceTriangle&) for the triangles of every cell
  // whose x-y extent overlaps `box` (body frame) and that reach its z range.
  template <class Visit>
  void ForEachTriangle(const Aabb& box, Visit&& visit) const;

 private:
  // The triangle's vertices, normal and index, without its edges' bits.
  SurfaceTriangle Corners(int r, int c, int half) const;
  // Range of cells [lo, hi] whose extent overlaps [min, max] along one
  // axis; false when none does.
  bool CellRange(double min, double max, double spacing, int samples, int* lo, int* hi) const;
};

// Checks and builds the heightfield. Fails, naming the field and value, on
// fewer than 2 x 2 samples, more than kMaxHeightSamples, a heights count
// that is not rows x cols, a non-finite height, or a spacing not finite
// and > 0.
Status BuildHeightField(int rows, int cols, const std::vector<double>& heights, double spacing_x, double spacing_y,
                        std::shared_ptr<const HeightField>* field);

template <class Visit>
void HeightField::ForEachTriangle(const Aabb& box, Visit&& visit) const {
  if (box.max.z() < min_height || box.min.z() > max_height) return;
  int c0, c1, r0, r1;
  if (!CellRange(box.min.x(), box.max.x(), spacing_x, cols, &c0, &c1)) return;
  if (!CellRange(box.min.y(), box.max.y(), spacing_y, rows, &r0, &r1)) return;
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      const double h[4] = {heights[r * cols + c], heights[r * cols + c + 1], heights[(r + 1) * cols + c],
                           heights[(r + 1) * cols + c + 1]};
      const double lo = std::min(std::min(h[0], h[1]), std::min(h[2], h[3]));
      const double hi = std::max(std::max(h[0], h[1]), std::max(h[2], h[3]));
      if (box.max.z() < lo || box.min.z() > hi) continue;
      visit(Triangle(r, c, 0));
      visit(Triangle(r, c, 1));
    }
  }
}

}  // namespace contactsim
