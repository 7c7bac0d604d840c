// Tests of height map files: 16-bit PNG and raw samples to heights, the
// row order and byte order, and every refusal naming the file and the
// problem; a scene file naming a height map beside it.
#include "service/scene/height_map_file.h"

#include <gtest/gtest.h>
#include <png.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "service/collision/height_field.h"
#include "service/scene/scene_spec.h"

namespace contactsim {
namespace {

namespace fs = std::filesystem;

// 2 rows x 3 cols; 258 = 0x0102 tells the byte orders apart, 0 and 65535 are the ends
const std::vector<uint16_t> kSamples = {0, 258, 65535, 1000, 30000, 65534};
constexpr int kRows = 2, kCols = 3;

class HeightMapFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("contactsim-height-maps-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A PNG written with libpng's simplified API: `format` PNG_FORMAT_LINEAR_Y
  // is 16-bit greyscale, PNG_FORMAT_GRAY 8-bit, PNG_FORMAT_LINEAR_RGB 16-bit colour.
  std::string Png(const std::string& name, png_uint_32 format, const std::vector<uint16_t>& samples) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = kCols;
    image.height = kRows;
    image.format = format;
    const std::string path = (dir_ / name).string();
    std::vector<uint16_t> wide;
    std::vector<uint8_t> narrow;
    const int channels = PNG_IMAGE_SAMPLE_CHANNELS(format);
    for (uint16_t s : samples) {
      for (int k = 0; k < channels; ++k) wide.push_back(s), narrow.push_back(static_cast<uint8_t>(s >> 8));
    }
    const void* data = (format & PNG_FORMAT_FLAG_LINEAR) ? static_cast<const void*>(wide.data()) : narrow.data();
    EXPECT_TRUE(png_image_write_to_file(&image, path.c_str(), 0, data, 0, nullptr)) << image.message;
    return path;
  }

  // Raw little-endian uint16 bytes.
  std::string Raw(const std::string& name, const std::vector<uint16_t>& samples, size_t drop = 0) {
    const std::string path = (dir_ / name).string();
    std::ofstream out(path, std::ios::binary);
    for (uint16_t s : samples) out.put(static_cast<char>(s & 0xff)).put(static_cast<char>(s >> 8));
    out.close();
    fs::resize_file(path, 2 * samples.size() - drop);
    return path;
  }

  fs::path dir_;
};

// The heights a file of kSamples gives: its first row at the grid's largest y.
std::vector<double> Expected(double scale, double offset) {
  std::vector<double> h;
  for (int r = kRows - 1; r >= 0; --r) {
    for (int c = 0; c < kCols; ++c) h.push_back(offset + scale * (kSamples[r * kCols + c] / 65535.0));
  }
  return h;
}

// Verifies that a 16-bit greyscale PNG gives its size and offset + scale
// s / 65535 per sample, its top row at the largest y, big-endian samples
// read as such (258 stays 258).
TEST_F(HeightMapFile, SixteenBitPngGivesScaledHeightsTopRowLast) {
  HeightMap map;
  ASSERT_TRUE(ReadHeightMap(Png("t.png", PNG_FORMAT_LINEAR_Y, kSamples), 0, 0, 2.5, -1.0, &map).ok());
  EXPECT_EQ(map.rows, kRows);
  EXPECT_EQ(map.cols, kCols);
  const std::vector<double> want = Expected(2.5, -1.0);
  ASSERT_EQ(map.heights.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_DOUBLE_EQ(map.heights[i], want[i]) << i;
  EXPECT_DOUBLE_EQ(map.heights[3 + 2], 1.5);  // sample 65535 at row 0 of the file, grid row 1
}

// Verifies that a raw file of the same samples gives the same grid as the
// PNG, read little-endian with the rows and cols given.
TEST_F(HeightMapFile, RawFileGivesTheSameGridAsThePng) {
  HeightMap png, raw;
  ASSERT_TRUE(ReadHeightMap(Png("t.png", PNG_FORMAT_LINEAR_Y, kSamples), kRows, kCols, 0.7, 0.2, &png).ok());
  const Status st = ReadHeightMap(Raw("t.raw", kSamples), kRows, kCols, 0.7, 0.2, &raw);
  ASSERT_TRUE(st.ok()) << st.message();
  EXPECT_EQ(raw.rows, kRows);
  EXPECT_EQ(raw.cols, kCols);
  EXPECT_EQ(raw.heights, png.heights);
}

// Expects a refusal of `code` whose message holds every one of `words`.
void ExpectRefused(const Status& st, StatusCode code, const std::vector<std::string>& words) {
  ASSERT_FALSE(st.ok());
  EXPECT_EQ(st.code(), code) << st.message();
  for (const std::string& w : words) EXPECT_NE(st.message().find(w), std::string::npos) << st.message();
}

// Verifies that 8-bit and colour PNGs are refused with what they are and
// what is needed, and a PNG whose size is not the rows and cols given.
TEST_F(HeightMapFile, RefusesEightBitColourAndMismatchedPngs) {
  HeightMap map;
  ExpectRefused(ReadHeightMap(Png("g8.png", PNG_FORMAT_GRAY, kSamples), 0, 0, 1, 0, &map),
                StatusCode::kInvalidArgument, {"g8.png", "8-bit greyscale", "16-bit greyscale"});
  ExpectRefused(ReadHeightMap(Png("rgb.png", PNG_FORMAT_LINEAR_RGB, kSamples), 0, 0, 1, 0, &map),
                StatusCode::kInvalidArgument, {"rgb.png", "16-bit RGB"});
  ExpectRefused(ReadHeightMap(Png("t.png", PNG_FORMAT_LINEAR_Y, kSamples), 3, 2, 1, 0, &map),
                StatusCode::kInvalidArgument, {"2 rows x 3 cols", "3 x 2"});
}

// Verifies that a PNG cut short is refused with libpng's reason, not read
// as a raw file or half a grid.
TEST_F(HeightMapFile, RefusesATruncatedPng) {
  const std::string png = Png("cut.png", PNG_FORMAT_LINEAR_Y, kSamples);
  fs::resize_file(png, fs::file_size(png) - 20);
  HeightMap map;
  ExpectRefused(ReadHeightMap(png, 0, 0, 1, 0, &map), StatusCode::kInvalidArgument,
                {"cut.png", "is not a readable PNG"});
}

// Verifies that a raw file must be exactly 2 rows cols bytes, needs its
// size, and that too many samples are refused before the file is read.
TEST_F(HeightMapFile, RefusesRawOfWrongSizeOrTooManySamples) {
  HeightMap map;
  const std::string raw = Raw("t.raw", kSamples, 1);
  ExpectRefused(ReadHeightMap(raw, kRows, kCols, 1, 0, &map), StatusCode::kInvalidArgument,
                {"t.raw", "11 bytes", "2 x 3", "12"});
  ExpectRefused(ReadHeightMap(raw, 0, 0, 1, 0, &map), StatusCode::kInvalidArgument, {"height_rows"});
  ExpectRefused(ReadHeightMap(raw, 4097, 4097, 1, 0, &map), StatusCode::kResourceExhausted,
                {"4097 x 4097", std::to_string(kMaxHeightSamples)});
}

// Verifies that a missing file, a negative size and a non-finite scale are refused.
TEST_F(HeightMapFile, RefusesMissingFileAndBadArguments) {
  HeightMap map;
  ExpectRefused(ReadHeightMap((dir_ / "none.png").string(), 0, 0, 1, 0, &map), StatusCode::kNotFound,
                {"none.png", "cannot be read"});
  const std::string png = Png("t.png", PNG_FORMAT_LINEAR_Y, kSamples);
  ExpectRefused(ReadHeightMap(png, -1, 3, 1, 0, &map), StatusCode::kInvalidArgument, {"-1 x 3"});
  ExpectRefused(ReadHeightMap(png, 0, 0, std::nan(""), 0, &map), StatusCode::kInvalidArgument, {"finite"});
}

// Verifies that a scene file's heightfield reads a height map beside it
// (a relative path against the scene's folder) with its scale and offset.
TEST_F(HeightMapFile, SceneFileNamesAHeightMapBesideIt) {
  Raw("terrain.r16", kSamples);
  SceneSpec scene;
  const Status st = ParseSceneText(
      "bodies { heightfield { path: \"terrain.r16\" rows: 2 cols: 3 scale: 4 offset: 0.5 spacing_x: 0.1 "
      "spacing_y: 0.2 } }\n",
      (dir_ / "scene.pbtxt").string(), &scene);
  ASSERT_TRUE(st.ok()) << st.message();
  ASSERT_EQ(scene.bodies.size(), 1u);
  const HeightField& f = *scene.bodies[0].heightfield;
  EXPECT_EQ(f.rows, kRows);
  EXPECT_EQ(f.cols, kCols);
  EXPECT_EQ(f.heights, Expected(4.0, 0.5));
  SceneSpec bad;
  ExpectRefused(ParseSceneText("bodies { heightfield { path: \"missing.png\" spacing_x: 1 spacing_y: 1 } }\n",
                               (dir_ / "scene.pbtxt").string(), &bad),
                StatusCode::kNotFound, {"missing.png"});
}

}  // namespace
}  // namespace contactsim
