// Tests of the float path's transposes (soft_wide_transpose.h) in the
// build's own instruction set: LoadColumns gives lane l of batch k as row
// l's float k, and StoreRows6 writes six batches back to the rows whose
// lanes are written, leaving the others and every row's seventh float.
#include "service/contact/soft/wide/soft_wide_transpose.h"

#include <gtest/gtest.h>

#include <xsimd/xsimd.hpp>

namespace contactsim {
namespace wide {
namespace {

using Batch = xsimd::batch<float>;
constexpr int kW = static_cast<int>(Batch::size);
constexpr int kRow = 18;  // a WideBody's floats

float Value(int row, int k) { return 100.0f * static_cast<float>(row) + static_cast<float>(k) + 0.25f; }

// Verifies that every column of rows of 18 floats, from any offset, comes
// out lane by lane as the rows hold it.
TEST(SoftWideTransposeTest, LoadColumnsGivesEachRowsFloatsInItsLane) {
  if (!TransposesInRegisters<Batch>()) GTEST_SKIP() << "no transpose in registers for this instruction set";
  float data[kW][kRow];
  const float* rows[kW];
  for (int l = 0; l < kW; ++l) {
    for (int k = 0; k < kRow; ++k) data[l][k] = Value(l, k);
    rows[l] = data[l];
  }
  for (int offset = 0; offset + kW <= kRow; ++offset) {
    Batch out[kW];
    LoadColumns(rows, offset, out);
    for (int k = 0; k < kW; ++k) {
      alignas(64) float lanes[kW];
      out[k].store_aligned(lanes);
      for (int l = 0; l < kW; ++l) EXPECT_EQ(lanes[l], Value(l, offset + k)) << "offset " << offset << " k " << k;
    }
  }
}

// Verifies that StoreRows6 writes floats 0..5 of the written lanes' rows
// only.
TEST(SoftWideTransposeTest, StoreRows6WritesTheWrittenLanesFirstSixFloats) {
  if (!TransposesInRegisters<Batch>()) GTEST_SKIP() << "no transpose in registers for this instruction set";
  float data[kW][kRow];
  float* rows[kW];
  unsigned char write[kW];
  for (int l = 0; l < kW; ++l) {
    for (int k = 0; k < kRow; ++k) data[l][k] = -1.0f;
    rows[l] = data[l];
    write[l] = l % 3 == 1 ? 0 : 1;
  }
  Batch c[6];
  for (int k = 0; k < 6; ++k) {
    alignas(64) float lanes[kW];
    for (int l = 0; l < kW; ++l) lanes[l] = Value(l, k);
    c[k] = Batch::load_aligned(lanes);
  }
  StoreRows6(c, rows, write);
  for (int l = 0; l < kW; ++l) {
    for (int k = 0; k < kRow; ++k) {
      const float expected = write[l] != 0 && k < 6 ? Value(l, k) : -1.0f;
      EXPECT_EQ(data[l][k], expected) << "lane " << l << " float " << k;
    }
  }
}

}  // namespace
}  // namespace wide
}  // namespace contactsim
