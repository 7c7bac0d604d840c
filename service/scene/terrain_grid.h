// A generated rolling terrain (scene.proto's Terrain): the heights of a
// regular grid from a closed formula, and the same grid as a triangle mesh
// split as a heightfield splits its cells, so the standard terrain
// benchmarks put a mesh and a heightfield of exactly one surface under the
// same bodies without storing either in the repository.
//
// Height of the sample at (x, y) (x, y as HeightField::Sample places it):
//   z = amplitude sin(2 pi x / wavelength_x) cos(2 pi y / wavelength_y) + bowl (x^2 + y^2)
// with portable::Sin and Cos, so every build and machine makes the same
// bits. The bowl term makes the surface rise towards its border, so bodies
// that land on it stay on it.
#pragma once

#include <vector>

#include "service/physics/math.h"
#include "service/physics/status.h"

namespace contactsim {

struct TerrainSpec {
  int rows = 0;               // samples along y, >= 2
  int cols = 0;               // samples along x, >= 2
  double spacing_x = 0.0;     // m, > 0
  double spacing_y = 0.0;     // m, > 0
  double amplitude = 0.0;     // m
  double wavelength_x = 1.0;  // m, > 0
  double wavelength_y = 1.0;  // m, > 0
  double bowl = 0.0;          // 1/m
};

// The rows x cols heights, row-major, row 0 at the smallest y
// (height_field.h's layout). Fails, naming the field and value, on fewer
// than 2 samples along an axis, more than kMaxHeightSamples, a spacing or
// wavelength not finite and > 0, or a non-finite amplitude or bowl.
Status TerrainHeights(const TerrainSpec& spec, std::vector<double>* heights);

// The grid of `heights` (TerrainHeights' layout) as vertices and three
// indices per triangle: cell (r, c) split along its diagonal from (r, c) to
// (r + 1, c + 1) into the heightfield's half 0 and half 1, both
// counter-clockwise seen from +z, so 2 (rows - 1) (cols - 1) triangles
// sharing their edges.
void GridTriangles(int rows, int cols, double spacing_x, double spacing_y, const std::vector<double>& heights,
                   std::vector<Vec3>* vertices, std::vector<int>* indices);

}  // namespace contactsim
