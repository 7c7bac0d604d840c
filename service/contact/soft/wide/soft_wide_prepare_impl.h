// The float path's prepare kernel (WideKernels::prepare), written once over
// the lanes of an instruction set like the passes (soft_wide_kernels_impl.h):
// from the packed anchors, frames and the bodies' inverse inertias at the
// step's start, each point's rows as PrepareSoftPoint makes them (Jacobians
// r x d, responses I^-1 (r x d), effective masses 1 / K) and each lane's
// block K^-1 (normal_block.h), in float, straight into the bundle, as
// Box2D v3 and Box3D prepare their wide contact constraints (box2d
// src/contact_solver.c, b2PrepareContactsTask).
//
// K^-1 by Cholesky over the lanes: K = L L^T, K^-1 = L^-T L^-1, 4 x 4 at
// most. A face's four points act on three velocities, so their
// K is singular and takes K^+ = (K + c c^T)^-1 - c c^T directly
// (normal_block.h); two or three points take K^-1. A lane takes the block
// solve when L's diagonal passes normal_block.cpp's test and K's estimated
// condition max K_ii max |K^-1_ij| is at most kMaxFloatBlockCondition;
// otherwise its points are swept one by one.
#pragma once

#include <limits>

#include "service/contact/soft/wide/soft_wide_kernels_impl.h"

namespace contactsim {
namespace wide {
namespace {

// The largest condition number, estimated as max K_ii max |K^-1_ij|, at
// which a manifold's normal rows take the block solve in single precision.
// The block's increment is K^-1 times the rows' velocities, whose float
// round-off (6e-8 relative) K^-1 amplifies by up to the condition: at 1e3
// that is 6e-5 of the bodies' speed. Worse blocks, such as the points of
// a triangle of a curved surface with two of them nearly in line with the
// third, are swept point by point, as the double path sweeps the blocks
// it cannot invert (normal_block.h). Taken as they came, such blocks gave a
// box landing on a curved 100,000-triangle terrain 4.8e8 m/s in one step.
constexpr float kMaxFloatBlockCondition = 1e3f;
// L's smallest diagonal against its largest (normal_block.cpp's
// InvertIfWellConditioned).
constexpr float kMinPivotRatio = 1e-5f;
// A face's four points lie on a line when their null vector's cofactors
// are below this part of their extent squared: the cofactors' float
// round-off is ~1e-7 of it, so 1e-5 keeps a hundred times that clear
// (normal_block.cpp's double test takes 1e-9).
constexpr float kMinFaceArea = 1e-5f;

template <class Arch>
struct PrepareLanes {
  using L = Lanes<Arch>;
  using B = typename L::B;
  using M = typename L::M;
  using V3 = typename L::V3;
  static constexpr int W = L::W;

  static V3 Cross(const V3& a, const V3& b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  }
  // I v with I column-major
  static V3 Times(const B* I, const V3& v) {
    return {I[0] * v.x + I[3] * v.y + I[6] * v.z, I[1] * v.x + I[4] * v.y + I[7] * v.z,
            I[2] * v.x + I[5] * v.y + I[8] * v.z};
  }
  // 1 / k, 0 where k <= 0 (soft_contact.cpp's MassOf)
  static B MassOf(const B& k) {
    const M positive = k > B(0.0f);
    return xsimd::select(positive, B(1.0f) / xsimd::select(positive, k, B(1.0f)), B(0.0f));
  }
  static void GatherInertia(const WideView& view, const int* index, B* I) {
    alignas(kAlign) float buf[9][W];
    for (int l = 0; l < W; ++l) {
      const float* from = view.inv_inertia + static_cast<size_t>(index[l]) * view.inertia_stride;
      for (int k = 0; k < 9; ++k) buf[k][l] = from[k];
    }
    for (int k = 0; k < 9; ++k) I[k] = B::load_aligned(buf[k]);
  }

  // What the block inversion reads of a lane's points.
  struct Rows {
    V3 ra[kSlots], ra_n[kSlots], rb_n[kSlots], ia_n[kSlots], ib_n[kSlots];
  };

  // Slot s's rows, as PrepareSoftPoint computes them.
  static void PreparePoint(const typename L::Fields& f, int s, bool friction_at_anchors, const B* Ia, const B* Ib,
                           const B& k_lin, Rows* rows) {
    const auto at = [s](int field) { return SlotAt(s, field); };
    const auto set3 = [&](int field, const V3& v) { f.Set(field, v.x), f.Set(field + 1, v.y), f.Set(field + 2, v.z); };
    const V3 n = f.Get3(kN), t1 = f.Get3(kT1), t2 = f.Get3(kT2);
    const V3 ra = f.Get3(at(kRa)), rb = f.Get3(at(kRb));
    const V3 fa = friction_at_anchors ? ra : f.Get3(at(kFa)), fb = friction_at_anchors ? rb : f.Get3(at(kFb));
    const V3 ra_n = Cross(ra, n), rb_n = Cross(rb, n);
    const V3 ia_n = Times(Ia, ra_n), ib_n = Times(Ib, rb_n);
    const V3 ra_t1 = Cross(fa, t1), ra_t2 = Cross(fa, t2), rb_t1 = Cross(fb, t1), rb_t2 = Cross(fb, t2);
    const V3 ia_t1 = Times(Ia, ra_t1), ia_t2 = Times(Ia, ra_t2), ib_t1 = Times(Ib, rb_t1), ib_t2 = Times(Ib, rb_t2);
    set3(at(kRaN), ra_n), set3(at(kRbN), rb_n), set3(at(kIaN), ia_n), set3(at(kIbN), ib_n);
    set3(at(kRaT1), ra_t1), set3(at(kRaT2), ra_t2), set3(at(kRbT1), rb_t1), set3(at(kRbT2), rb_t2);
    set3(at(kIaT1), ia_t1), set3(at(kIaT2), ia_t2), set3(at(kIbT1), ib_t1), set3(at(kIbT2), ib_t2);
    // a slot past its lane's points keeps no mass, so that it pushes nothing
    const M point = B(static_cast<float>(s)) < f.Get(kCount);
    const auto mass = [&](const B& k) { return xsimd::select(point, MassOf(k), B(0.0f)); };
    f.Set(at(kMassN), mass(k_lin + L::Dot(ra_n, ia_n) + L::Dot(rb_n, ib_n)));
    f.Set(at(kMassT1), mass(k_lin + L::Dot(ra_t1, ia_t1) + L::Dot(rb_t1, ib_t1)));
    f.Set(at(kMassT2), mass(k_lin + L::Dot(ra_t2, ia_t2) + L::Dot(rb_t2, ib_t2)));
    f.Set(at(kKT12), L::Dot(ra_t1, ia_t2) + L::Dot(rb_t1, ib_t2));
    rows->ra[s] = ra, rows->ra_n[s] = ra_n, rows->rb_n[s] = rb_n, rows->ia_n[s] = ia_n, rows->ib_n[s] = ib_n;
  }

  // The unit null vector c of a face's four points (normal_block.cpp's
  // FaceNullVector, by cofactors of their tangent coordinates); `valid`
  // false where they lie on a line.
  static void FaceNullVector(const Rows& rows, const V3& t1, const V3& t2, B* c, M* valid) {
    B u[4], v[4];
    B extent(0.0f);
    for (int i = 0; i < 4; ++i) {
      const V3 r = L::Sub(rows.ra[i], rows.ra[0]);
      u[i] = L::Dot(r, t1);
      v[i] = L::Dot(r, t2);
      extent = xsimd::max(extent, u[i] * u[i] + v[i] * v[i]);
    }
    const auto minor = [&](int i, int j, int k) {
      return (u[j] - u[i]) * (v[k] - v[i]) - (u[k] - u[i]) * (v[j] - v[i]);
    };
    c[0] = minor(1, 2, 3), c[1] = -minor(0, 2, 3), c[2] = minor(0, 1, 3), c[3] = -minor(0, 1, 2);
    const B norm = xsimd::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2] + c[3] * c[3]);
    *valid = norm > B(kMinFaceArea) * extent;
    const B scale = B(1.0f) / xsimd::select(*valid, norm, B(1.0f));
    for (int i = 0; i < 4; ++i) c[i] = c[i] * scale;
  }

  // inv = k^-1 of the symmetric `slots` x `slots` k (its lower triangle) by Cholesky; false
  // lanes where k is not positive definite or L's diagonal spreads too far.
  // As normal_block.cpp pads every block to 4 x 4 with the identity, a
  // lane of fewer than 4 points counts a diagonal of 1 in the spread,
  // whatever its bundle's slots (so the test does not depend on which
  // manifolds share its bundle, nor on the width).
  static M Invert(int slots, const B& count, const B (&k)[kSlots][kSlots], B (&inv)[kSlots][kSlots]) {
    const B zero(0.0f), one(1.0f);
    B l[kSlots][kSlots], d_inv[kSlots];
    M ok = zero == zero;
    const M padded = count < B(static_cast<float>(kSlots));
    B d_min = xsimd::select(padded, one, B(std::numeric_limits<float>::infinity()));
    B d_max = xsimd::select(padded, one, zero);
    for (int j = 0; j < slots; ++j) {
      B pivot = k[j][j];
      for (int m = 0; m < j; ++m) pivot = pivot - l[j][m] * l[j][m];
      ok = ok && (pivot > zero);
      const B d = xsimd::sqrt(xsimd::select(pivot > zero, pivot, one));
      d_min = xsimd::min(d_min, d);
      d_max = xsimd::max(d_max, d);
      d_inv[j] = one / d;
      l[j][j] = d;
      for (int i = j + 1; i < slots; ++i) {
        B sum = k[i][j];
        for (int m = 0; m < j; ++m) sum = sum - l[i][m] * l[j][m];
        l[i][j] = sum * d_inv[j];
      }
    }
    ok = ok && (d_min > B(kMinPivotRatio) * d_max);
    // L^-1, lower triangular, then K^-1 = L^-T L^-1
    B li[kSlots][kSlots];
    for (int j = 0; j < slots; ++j) {
      li[j][j] = d_inv[j];
      for (int i = j + 1; i < slots; ++i) {
        B sum = l[i][j] * li[j][j];
        for (int m = j + 1; m < i; ++m) sum = sum + l[i][m] * li[m][j];
        li[i][j] = -sum * d_inv[i];
      }
    }
    for (int i = 0; i < slots; ++i) {
      for (int j = 0; j <= i; ++j) {
        B sum = li[i][i] * li[i][j];
        for (int m = i + 1; m < slots; ++m) sum = sum + li[m][i] * li[m][j];
        inv[i][j] = inv[j][i] = sum;
      }
    }
    return ok;
  }

  // The lane's K^-1 or K^+ and whether it takes the block solve.
  static void PrepareBlock(const typename L::Fields& f, int slots, const Rows& rows, const B& k_lin) {
    const B zero(0.0f), one(1.0f);
    const B count = f.Get(kCount);
    B k[kSlots][kSlots], inv[kSlots][kSlots];
    B k_max = zero;
    M ok = count >= B(2.0f);
    for (int i = 0; i < slots; ++i) {
      const M point = B(static_cast<float>(i)) < count;
      // the lower triangle (Invert reads no other)
      for (int j = 0; j <= i; ++j) {
        const B kij = k_lin + L::Dot(rows.ra_n[i], rows.ia_n[j]) + L::Dot(rows.rb_n[i], rows.ib_n[j]);
        // a smaller block's unused rows and columns are the identity's
        const M used = point && (B(static_cast<float>(j)) < count);
        k[i][j] = xsimd::select(used, kij, i == j ? one : zero);
      }
      // K_ii = 1 / mass_n: every point must have a mass
      ok = ok && (k[i][i] > zero || !point);
      k_max = xsimd::select(point, xsimd::max(k_max, k[i][i]), k_max);
    }
    B c[kSlots] = {zero, zero, zero, zero};
    M face = count == B(4.0f);
    if (slots == kSlots && xsimd::any(face)) {
      M valid;
      FaceNullVector(rows, f.Get3(kT1), f.Get3(kT2), c, &valid);
      ok = ok && (valid || !face);
      for (int i = 0; i < kSlots; ++i) c[i] = xsimd::select(face, c[i], zero);
      for (int i = 0; i < kSlots; ++i) {
        for (int j = 0; j <= i; ++j) k[i][j] = k[i][j] + c[i] * c[j];
      }
    }
    ok = ok && Invert(slots, count, k, inv);
    B inv_max = zero;
    for (int i = 0; i < slots; ++i) {
      const M row = B(static_cast<float>(i)) < count;
      for (int j = 0; j < slots; ++j) {
        const M used = row && (B(static_cast<float>(j)) < count);
        inv[i][j] = xsimd::select(used, inv[i][j] - c[i] * c[j], zero);
        inv_max = xsimd::max(inv_max, xsimd::abs(inv[i][j]));
      }
    }
    ok = ok && (k_max * inv_max <= B(kMaxFloatBlockCondition));
    f.Set(kBlock, xsimd::select(ok, one, zero));
    for (int i = 0; i < slots; ++i) {
      for (int j = 0; j < slots; ++j) f.Set(kInvK + 4 * i + j, xsimd::select(ok, inv[i][j], zero));
    }
  }

  static void Prepare(const WideView& view, int begin, int end) {
    for (int bundle = begin; bundle < end; ++bundle) {
      const typename L::Fields f = L::Of(view, bundle);
      B Ia[9], Ib[9];
      GatherInertia(view, view.body_a + bundle * W, Ia);
      GatherInertia(view, view.body_b + bundle * W, Ib);
      const B k_lin = f.Get(kInvMassA) + f.Get(kInvMassB);
      const int slots = view.slots[bundle];
      Rows rows;
      for (int s = 0; s < slots; ++s) {
        PreparePoint(f, s, view.friction_at_anchors, Ia, Ib, k_lin, &rows);
        // the step's largest push and totals start at zero (the bundles are not cleared)
        for (const int field : {kMaxPush, kTotalN, kTotalT1, kTotalT2}) f.Set(SlotAt(s, field), B(0.0f));
      }
      if (slots >= 2) {
        PrepareBlock(f, slots, rows, k_lin);
      } else {
        f.Set(kBlock, B(0.0f));
      }
    }
  }
};

// The kernels of one instruction set.
template <class Arch>
const WideKernels& KernelTable() {
  static const WideKernels table = {Lanes<Arch>::W, &PrepareLanes<Arch>::Prepare, &Lanes<Arch>::WarmStart,
                                    &Lanes<Arch>::Solve, &Lanes<Arch>::Accumulate};
  return table;
}

}  // namespace
}  // namespace wide
}  // namespace contactsim
