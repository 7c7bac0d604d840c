#include "service/collision/height_field.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "service/collision/triangle_surface.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

// Grid offsets (dr, dc) of a cell's two triangles, per half, counter-clockwise.
constexpr int kCorner[2][3][2] = {{{0, 0}, {0, 1}, {1, 1}}, {{0, 0}, {1, 1}, {1, 0}}};
// Per half and edge: the grid offset (from the cell) of the vertex across
// the edge, in the neighbouring triangle (height_field.h's split).
constexpr int kAcross[2][3][2] = {{{-1, 0}, {1, 2}, {1, 0}}, {{0, 1}, {2, 1}, {0, -1}}};

// Bits of a cell's edge_bits entry per half.
constexpr int kBitsPerHalf = 6;

}  // namespace

SurfaceTriangle HeightField::Triangle(int r, int c, int half) const {
  if (edge_bits.empty()) return TriangleWithNeighbours(r, c, half);
  SurfaceTriangle tri = Corners(r, c, half);
  const unsigned bits = edge_bits[tri.index / 2] >> (kBitsPerHalf * half);
  tri.active_edges = static_cast<uint8_t>(bits & 7u);
  tri.convex_edges = static_cast<uint8_t>((bits >> 3) & 7u);
  return tri;
}

SurfaceTriangle HeightField::Corners(int r, int c, int half) const {
  SurfaceTriangle tri;
  for (int k = 0; k < 3; ++k) tri.v[k] = Sample(r + kCorner[half][k][0], c + kCorner[half][k][1]);
  const Vec3 n = (tri.v[1] - tri.v[0]).cross(tri.v[2] - tri.v[0]);
  tri.normal = n.normalized();  // never degenerate: the x-y projection has area dx dy / 2
  tri.index = static_cast<uint32_t>(2 * (r * (cols - 1) + c) + half);
  return tri;
}

SurfaceTriangle HeightField::TriangleWithNeighbours(int r, int c, int half) const {
  SurfaceTriangle tri = Corners(r, c, half);
  tri.active_edges = 0;
  tri.convex_edges = 0;
  for (int k = 0; k < 3; ++k) {
    const int rr = r + kAcross[half][k][0], cc = c + kAcross[half][k][1];
    const bool open = rr < 0 || rr >= rows || cc < 0 || cc >= cols;
    if (open || EdgeIsActive(tri.normal, tri.v[k], tri.v[(k + 1) % 3], Sample(rr, cc))) {
      tri.active_edges |= 1u << k;
    }
    if (open || EdgeIsActive(tri.normal, tri.v[k], tri.v[(k + 1) % 3], Sample(rr, cc), kConvexEdgeAngle)) {
      tri.convex_edges |= 1u << k;
    }
  }
  return tri;
}

Aabb HeightField::Bounds() const {
  const Vec3 half(0.5 * (cols - 1) * spacing_x, 0.5 * (rows - 1) * spacing_y, 0.0);
  return Aabb{Vec3(-half.x(), -half.y(), min_height), Vec3(half.x(), half.y(), max_height)};
}

bool HeightField::CellRange(double min, double max, double spacing, int samples, int* lo, int* hi) const {
  const double origin = -0.5 * (samples - 1) * spacing;
  const double a = std::floor((min - origin) / spacing);
  const double b = std::floor((max - origin) / spacing);
  // A box whose low side lies exactly on the upper border still touches the
  // last cell, as one whose high side lies on the lower border touches the first.
  if (!(b >= 0.0) || !(a <= samples - 1)) return false;
  *lo = static_cast<int>(std::min(std::max(a, 0.0), static_cast<double>(samples - 2)));
  *hi = static_cast<int>(std::min(b, static_cast<double>(samples - 2)));
  return *lo <= *hi;
}

Status BuildHeightField(int rows, int cols, const std::vector<double>& heights, double spacing_x, double spacing_y,
                        std::shared_ptr<const HeightField>* field) {
  if (rows < 2 || cols < 2) {
    return Status::InvalidArgument("a heightfield needs at least 2 x 2 heights, got " + std::to_string(rows) + " x " +
                                   std::to_string(cols));
  }
  if (static_cast<long long>(rows) * cols > kMaxHeightSamples) {
    return Status::ResourceExhausted("a heightfield has at most " + std::to_string(kMaxHeightSamples) +
                                     " heights, got " + std::to_string(rows) + " x " + std::to_string(cols));
  }
  if (heights.size() != static_cast<size_t>(rows) * cols) {
    return Status::InvalidArgument("heights must hold rows x cols = " + std::to_string(rows) + " x " +
                                   std::to_string(cols) + " values, got " + std::to_string(heights.size()));
  }
  for (double s : {spacing_x, spacing_y}) {
    if (!(std::isfinite(s) && s > 0.0 && s < 1e6)) {
      return Status::InvalidArgument("heightfield spacing must be finite and in (0, 1e6) m, got " + FormatValue(s));
    }
  }
  for (size_t i = 0; i < heights.size(); ++i) {
    if (!std::isfinite(heights[i]) || std::abs(heights[i]) > 1e6) {
      return Status::InvalidArgument("height " + std::to_string(i) + " (row " + std::to_string(i / cols) + ", col " +
                                     std::to_string(i % cols) + ") must be finite and within 1e6 m");
    }
  }
  auto f = std::make_shared<HeightField>();
  f->rows = rows;
  f->cols = cols;
  f->spacing_x = spacing_x;
  f->spacing_y = spacing_y;
  f->heights = heights;
  const auto [lo, hi] = std::minmax_element(heights.begin(), heights.end());
  f->min_height = *lo;
  f->max_height = *hi;
  f->edge_bits.resize(static_cast<size_t>(rows - 1) * (cols - 1));
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      unsigned bits = 0;
      for (int half = 0; half < 2; ++half) {
        const SurfaceTriangle tri = f->TriangleWithNeighbours(r, c, half);
        bits |= (tri.active_edges | (tri.convex_edges << 3u)) << (kBitsPerHalf * half);
      }
      f->edge_bits[static_cast<size_t>(r) * (cols - 1) + c] = static_cast<uint16_t>(bits);
    }
  }
  *field = std::move(f);
  return Status::Ok();
}

}  // namespace contactsim
