#include "service/scene/terrain_grid.h"

#include <string>

#include "service/collision/height_field.h"
#include "service/physics/portable_math.h"
#include "service/physics/validation.h"

namespace contactsim {
namespace {

constexpr double kTwoPi = 6.283185307179586;

Status CheckTerrain(const TerrainSpec& s) {
  if (s.rows < 2 || s.cols < 2) {
    return Status::InvalidArgument("terrain rows and cols must be >= 2, got " + std::to_string(s.rows) + " x " +
                                   std::to_string(s.cols));
  }
  if (static_cast<long long>(s.rows) * s.cols > kMaxHeightSamples) {
    return Status::InvalidArgument("terrain has " + std::to_string(static_cast<long long>(s.rows) * s.cols) +
                                   " samples, more than " + std::to_string(kMaxHeightSamples));
  }
  for (const auto& [field, v] : {std::pair<const char*, double>{"terrain spacing_x", s.spacing_x},
                                 {"terrain spacing_y", s.spacing_y},
                                 {"terrain wavelength_x", s.wavelength_x},
                                 {"terrain wavelength_y", s.wavelength_y}}) {
    Status st = CheckPositive(field, v);
    if (!st.ok()) return st;
  }
  Status st = CheckFinite("terrain amplitude", s.amplitude);
  return st.ok() ? CheckFinite("terrain bowl", s.bowl) : st;
}

}  // namespace

Status TerrainHeights(const TerrainSpec& s, std::vector<double>* heights) {
  Status st = CheckTerrain(s);
  if (!st.ok()) return st;
  heights->assign(static_cast<size_t>(s.rows) * s.cols, 0.0);
  for (int r = 0; r < s.rows; ++r) {
    const double y = (r - 0.5 * (s.rows - 1)) * s.spacing_y;
    const double wave_y = portable::Cos(kTwoPi * y / s.wavelength_y);
    for (int c = 0; c < s.cols; ++c) {
      const double x = (c - 0.5 * (s.cols - 1)) * s.spacing_x;
      (*heights)[static_cast<size_t>(r) * s.cols + c] =
          s.amplitude * portable::Sin(kTwoPi * x / s.wavelength_x) * wave_y + s.bowl * (x * x + y * y);
    }
  }
  return Status::Ok();
}

void GridTriangles(int rows, int cols, double spacing_x, double spacing_y, const std::vector<double>& heights,
                   std::vector<Vec3>* vertices, std::vector<int>* indices) {
  vertices->clear();
  indices->clear();
  vertices->reserve(static_cast<size_t>(rows) * cols);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      vertices->emplace_back((c - 0.5 * (cols - 1)) * spacing_x, (r - 0.5 * (rows - 1)) * spacing_y,
                             heights[static_cast<size_t>(r) * cols + c]);
    }
  }
  indices->reserve(6 * static_cast<size_t>(rows - 1) * (cols - 1));
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c + 1 < cols; ++c) {
      const int a = r * cols + c, b = a + 1, d = a + cols, e = d + 1;  // (r, c), (r, c+1), (r+1, c), (r+1, c+1)
      indices->insert(indices->end(), {a, b, e, a, e, d});
    }
  }
}

}  // namespace contactsim
