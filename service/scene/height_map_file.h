// The heights of a heightfield from a file: a 16-bit greyscale PNG (read
// with libpng) or a raw file of little-endian uint16 samples, the two forms
// terrain tools export (a 16-bit heightmap). A sample s in [0, 65535] is the
// height offset + scale s / 65535, so `scale` is the terrain's relief in
// metres and `offset` the height of its lowest possible sample.
//
// Rows: the file's first row is the grid's last one (largest body y), as
// an image seen from above with x to the right and y up; the grid's row r
// is at y_r (service/collision/height_field.h). PNG and raw files of the
// same samples therefore give the same terrain.
//
// Refused, each with a message naming the file: a missing or unreadable
// file; a PNG that is not 16-bit greyscale (an 8-bit image has 256 levels,
// too coarse for terrain, and a colour image has no one height per pixel:
// convert it first, e.g. `convert in.png -colorspace Gray -depth 16 out.png`
// with ImageMagick); a raw file whose size is not 2 rows cols bytes; more
// than kMaxHeightSamples samples, checked before any sample is read.
#pragma once

#include <string>
#include <vector>

#include "service/physics/status.h"

namespace contactsim {

struct HeightMap {
  int rows = 0;                 // along body y
  int cols = 0;                 // along body x
  std::vector<double> heights;  // m, rows * cols, row-major, row 0 at the smallest y
};

// Reads `path`: a PNG (by its signature) gives its size, and rows and cols
// must be 0 or equal to it; any other file is raw, rows x cols samples.
Status ReadHeightMap(const std::string& path, int rows, int cols, double scale, double offset, HeightMap* out);

}  // namespace contactsim
