#include "service/scene/height_map_file.h"

#include <png.h>

#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>

#include "service/collision/height_field.h"

namespace contactsim {
namespace {

constexpr double kMaxSample = 65535.0;

// libpng reports errors through a callback that must not return; it jumps
// back to the setjmp in ReadPngSamples with the message kept here.
struct PngErrors {
  std::jmp_buf jump;
  char message[256] = "";
};

void OnPngError(png_structp png, png_const_charp message) {
  auto* errors = static_cast<PngErrors*>(png_get_error_ptr(png));
  std::snprintf(errors->message, sizeof(errors->message), "is not a readable PNG: %s", message);
  std::longjmp(errors->jump, 1);
}

void OnPngWarning(png_structp, png_const_charp) {}  // ancillary-chunk trouble; the samples are still read

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

// What a PNG's header says, before any sample is decoded.
struct PngHeader {
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, colour_type = 0;
};

const char* ColourName(int colour_type) {
  switch (colour_type) {
    case PNG_COLOR_TYPE_GRAY: return "greyscale";
    case PNG_COLOR_TYPE_GRAY_ALPHA: return "greyscale with alpha";
    case PNG_COLOR_TYPE_RGB: return "RGB";
    case PNG_COLOR_TYPE_RGB_ALPHA: return "RGBA";
    case PNG_COLOR_TYPE_PALETTE: return "palette";
    default: return "unknown colour type";
  }
}

// The whole libpng exchange, in one function without C++ objects of its
// own, since a longjmp out of libpng must skip no destructor. `check` sees
// the header and may refuse; it sizes `bytes`. Returns false with
// errors->message set when libpng or `check` refused.
template <class Check>
bool ReadPngSamples(std::FILE* file, PngErrors* errors, Check&& check, std::vector<uint8_t>* bytes) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, errors, OnPngError, OnPngWarning);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(errors->jump)) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_init_io(png, file);
  png_read_info(png, info);
  PngHeader h;
  h.width = png_get_image_width(png, info);
  h.height = png_get_image_height(png, info);
  h.bit_depth = png_get_bit_depth(png, info);
  h.colour_type = png_get_color_type(png, info);
  if (!check(h, errors->message, sizeof(errors->message))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  const int passes = png_set_interlace_handling(png);  // an interlaced image is read in its seven passes
  png_read_update_info(png, info);
  const size_t stride = 2 * static_cast<size_t>(h.width);
  for (int pass = 0; pass < passes; ++pass) {
    for (png_uint_32 r = 0; r < h.height; ++r) png_read_row(png, bytes->data() + r * stride, nullptr);
  }
  png_read_end(png, nullptr);  // the rest of the stream and its checksums: a cut file is refused, not half read
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// rows x cols samples within kMaxHeightSamples, checked before any memory is taken.
Status CheckCount(const std::string& path, long long rows, long long cols) {
  if (rows * cols > kMaxHeightSamples) {
    return Status::ResourceExhausted("height map '" + path + "' has " + std::to_string(rows) + " x " +
                                     std::to_string(cols) + " samples, over the limit of " +
                                     std::to_string(kMaxHeightSamples) + " (kMaxHeightSamples)");
  }
  return Status::Ok();
}

// A PNG's samples, big-endian 16-bit as PNG stores them, into `bytes`.
Status ReadPng(const std::string& path, std::FILE* file, int rows, int cols, int* out_rows, int* out_cols,
               std::vector<uint8_t>* bytes) {
  PngErrors errors;
  bool too_many = false;
  auto check = [&](const PngHeader& h, char* message, size_t size) {
    if (h.bit_depth != 16 || h.colour_type != PNG_COLOR_TYPE_GRAY) {
      std::snprintf(message, size, "is a PNG of %d-bit %s samples; heights need 16-bit greyscale", h.bit_depth,
                    ColourName(h.colour_type));
      return false;
    }
    if ((rows != 0 || cols != 0) && (static_cast<png_uint_32>(rows) != h.height ||
                                     static_cast<png_uint_32>(cols) != h.width)) {
      std::snprintf(message, size, "is %u rows x %u cols, but height_rows x height_cols is %d x %d", h.height,
                    h.width, rows, cols);
      return false;
    }
    if (static_cast<long long>(h.height) * h.width > kMaxHeightSamples) {
      too_many = true;
      std::snprintf(message, size, "has %u x %u samples, over the limit of %d (kMaxHeightSamples)", h.height,
                    h.width, kMaxHeightSamples);
      return false;
    }
    *out_rows = static_cast<int>(h.height);
    *out_cols = static_cast<int>(h.width);
    bytes->resize(2 * static_cast<size_t>(h.height) * h.width);
    return true;
  };
  if (!ReadPngSamples(file, &errors, check, bytes)) {
    const std::string what = "height map '" + path + "' " + errors.message;
    return too_many ? Status::ResourceExhausted(what) : Status::InvalidArgument(what);
  }
  return Status::Ok();
}

// A raw file's samples, little-endian, into `bytes`: exactly rows x cols of them.
Status ReadRaw(const std::string& path, uintmax_t file_bytes, int rows, int cols, std::vector<uint8_t>* bytes) {
  if (rows < 2 || cols < 2) {
    return Status::InvalidArgument("raw height map '" + path + "' needs height_rows and height_cols >= 2, got " +
                                   std::to_string(rows) + " x " + std::to_string(cols));
  }
  Status st = CheckCount(path, rows, cols);
  if (!st.ok()) return st;
  const uintmax_t want = 2ull * rows * cols;
  if (file_bytes != want) {
    return Status::InvalidArgument("raw height map '" + path + "' is " + std::to_string(file_bytes) +
                                   " bytes, but " + std::to_string(rows) + " x " + std::to_string(cols) +
                                   " uint16 samples are " + std::to_string(want));
  }
  std::ifstream in(path, std::ios::binary);
  bytes->resize(want);
  if (!in.read(reinterpret_cast<char*>(bytes->data()), static_cast<std::streamsize>(want))) {
    return Status::NotFound("raw height map '" + path + "' cannot be read");
  }
  return Status::Ok();
}

}  // namespace

Status ReadHeightMap(const std::string& path, int rows, int cols, double scale, double offset, HeightMap* out) {
  if (!std::isfinite(scale) || !std::isfinite(offset)) {
    return Status::InvalidArgument("height map '" + path + "': scale and offset must be finite, got " +
                                   std::to_string(scale) + " and " + std::to_string(offset));
  }
  if (rows < 0 || cols < 0) {
    return Status::InvalidArgument("height map '" + path + "': rows and cols must be >= 0, got " +
                                   std::to_string(rows) + " x " + std::to_string(cols));
  }
  std::error_code ec;
  const uintmax_t file_bytes = std::filesystem::file_size(path, ec);
  std::unique_ptr<std::FILE, FileCloser> file(ec ? nullptr : std::fopen(path.c_str(), "rb"));
  if (!file) {
    return Status::NotFound("height map '" + path + "' cannot be read: " +
                            (ec ? ec.message() : std::string(std::strerror(errno))));
  }
  png_byte signature[8] = {};
  const bool png = std::fread(signature, 1, 8, file.get()) == 8 && png_sig_cmp(signature, 0, 8) == 0;
  std::rewind(file.get());
  std::vector<uint8_t> bytes;
  // a PNG's 16-bit samples are big-endian, a raw file's little-endian
  const int high = png ? 0 : 1;
  Status st = png ? ReadPng(path, file.get(), rows, cols, &out->rows, &out->cols, &bytes)
                  : ReadRaw(path, file_bytes, rows, cols, &bytes);
  if (!st.ok()) return st;
  if (!png) out->rows = rows, out->cols = cols;
  out->heights.assign(static_cast<size_t>(out->rows) * out->cols, 0.0);
  for (int r = 0; r < out->rows; ++r) {
    const uint8_t* line = bytes.data() + 2 * static_cast<size_t>(out->rows - 1 - r) * out->cols;  // first row: largest y
    for (int c = 0; c < out->cols; ++c) {
      const unsigned s = (line[2 * c + high] << 8) | line[2 * c + 1 - high];
      out->heights[static_cast<size_t>(r) * out->cols + c] = offset + scale * (s / kMaxSample);
    }
  }
  return Status::Ok();
}

}  // namespace contactsim
