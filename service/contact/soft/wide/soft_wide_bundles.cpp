#include "service/contact/soft/wide/soft_wide_bundles.h"

#include <algorithm>
#include <cstdint>

namespace contactsim {

static_assert(wide::kSlots == kMaxNormalBlock, "a lane holds a manifold's points");

// floats before the first aligned one, at most
constexpr size_t kPad = wide::kAlign / sizeof(float);

const float* WideBundles::Aligned() const {
  const auto address = reinterpret_cast<std::uintptr_t>(data_.data());
  return data_.data() + (wide::kAlign - address % wide::kAlign) % wide::kAlign / sizeof(float);
}

void WideBundles::Allocate(const std::vector<SoftManifold>& manifolds, const BlockColours& colours) {
  // bundle by bundle, the manifolds each takes (a colour's `width_` at a
  // time, then the overflow's one at a time)
  slots_.clear();
  for (int c = 0; c < colours.colours(); ++c) {
    for (int k = colours.starts[c]; k < colours.starts[c + 1]; ++k) {
      if ((k - colours.starts[c]) % width_ == 0) slots_.push_back(0);
      slots_.back() = static_cast<unsigned char>(std::max<int>(slots_.back(), manifolds[k].count));
    }
  }
  for (int k = colours.starts.back(); k < static_cast<int>(manifolds.size()); ++k) {
    slots_.push_back(static_cast<unsigned char>(manifolds[k].count));
  }
  offsets_.resize(slots_.size());
  size_t floats = 0;
  for (size_t b = 0; b < slots_.size(); ++b) {
    offsets_[b] = static_cast<int>(floats);
    floats += static_cast<size_t>(wide::BundleFields(slots_[b])) * width_;
  }
  const size_t lanes = slots_.size() * width_;
  // not cleared: PackLane writes a lane's inputs and zeroes its empty
  // slots', ClearLane a padding lane, and the prepare kernel the rest
  // (clearing the whole array cost 3.6% of a pyramid step)
  data_.resize(floats + kPad);
  body_a_.assign(lanes, dummy_);
  body_b_.assign(lanes, dummy_);
  write_a_.assign(lanes, 0);
  write_b_.assign(lanes, 0);
  points_.assign(lanes * wide::kSlots, -1);
}

// With the width known when compiling, a field's place in the lane is a
// constant offset: each store is a conversion and a move (the width read
// and multiplied a store cost 0.08M instructions a float pyramid step,
// BENCHMARKS.md, "soft: the float path").
template <int W>
void WideBundles::PackLane(const std::vector<SoftPoint>& points, const SoftManifold& m,
                           const std::vector<SoftBody>& bodies, const std::vector<Vec3>* friction_points,
                           int bundle, int lane) {
  using namespace wide;
  const int width = W > 0 ? W : width_;
  float* base = Aligned() + offsets_[bundle] + lane;
  const auto put = [base, width](int field, double x) { base[field * width] = static_cast<float>(x); };
  const auto put3 = [&](int field, const Vec3& v) {
    for (int k = 0; k < 3; ++k) put(field + k, v[k]);
  };
  const SoftPoint& p0 = points[m.first];
  const int index = bundle * width + lane;
  body_a_[index] = p0.a;
  body_b_[index] = p0.b;
  write_a_[index] = bodies[p0.a].inv_mass > 0.0 ? 1 : 0;
  write_b_[index] = bodies[p0.b].inv_mass > 0.0 ? 1 : 0;
  put3(kN, p0.n), put3(kT1, p0.t1), put3(kT2, p0.t2);
  put(kInvMassA, bodies[p0.a].inv_mass), put(kInvMassB, bodies[p0.b].inv_mass);
  put(kCount, m.count);  // the rows, effective masses and K^-1 are the prepare kernel's
  // a pair's points share its materials' friction and its spring
  // (SoftSprings); where a heavy-on-light solve would stiffen them
  // point by point, the step takes the double path (soft_wide_solver.h)
  put(kFriction, p0.friction);
  put(kBiasRate, p0.soft.bias_rate), put(kMassScale, p0.soft.mass_scale), put(kImpulseScale, p0.soft.impulse_scale);
  if (m.count < slots_[bundle]) ClearSlots(bundle, lane, m.count);
  for (int s = 0; s < m.count; ++s) {
    const SoftPoint& p = points[m.first + s];
    points_[static_cast<size_t>(index) * kSlots + s] = m.first + s;
    const auto at = [s](int field) { return SlotAt(s, field); };
    put3(at(kRa), p.ra), put3(at(kRb), p.rb);
    if (friction_points != nullptr) {
      Vec3 fa, fb;
      SoftFrictionArms(p, m.first + s, friction_points, bodies, &fa, &fb);
      put3(at(kFa), fa), put3(at(kFb), fb);
    }
    // s_0 itself rather than s_0 - n . (r_B - r_A): in float, that difference
    // of anchors' lengths loses s_0 to their round-off (NormalTargets)
    put(at(kSeparation), p.adjusted_separation + p.n.dot(p.rb - p.ra));
    put(at(kLambdaN), p.lambda_n), put(at(kLambdaT1), p.lambda_t1), put(at(kLambdaT2), p.lambda_t2);
  }
}

void WideBundles::Pack(const std::vector<SoftPoint>& points, const std::vector<SoftManifold>& manifolds,
                       const BlockColours& colours, const std::vector<SoftBody>& bodies,
                       const std::vector<Vec3>* friction_points, int width, int dummy) {
  width_ = width;
  dummy_ = dummy;
  friction_at_anchors_ = friction_points == nullptr;
  colours_.starts.assign(1, 0);
  for (int c = 0; c < colours.colours(); ++c) {
    const int size = colours.starts[c + 1] - colours.starts[c];
    colours_.starts.push_back(colours_.starts.back() + (size + width_ - 1) / width_);
  }
  Allocate(manifolds, colours);
  if (width_ == 8) {
    PackLanes<8>(points, manifolds, colours, bodies, friction_points);
  } else if (width_ == 4) {
    PackLanes<4>(points, manifolds, colours, bodies, friction_points);
  } else {
    PackLanes<0>(points, manifolds, colours, bodies, friction_points);
  }
  for (int index = 0; index < static_cast<int>(body_a_.size()); ++index) {
    if (body_a_[index] == dummy_) ClearLane(index / width_, index % width_);
  }
}

template <int W>
void WideBundles::PackLanes(const std::vector<SoftPoint>& points, const std::vector<SoftManifold>& manifolds,
                            const BlockColours& colours, const std::vector<SoftBody>& bodies,
                            const std::vector<Vec3>* friction_points) {
  const int width = W > 0 ? W : width_;
  for (int c = 0; c < colours.colours(); ++c) {
    for (int k = colours.starts[c]; k < colours.starts[c + 1]; ++k) {
      const int offset = k - colours.starts[c];
      PackLane<W>(points, manifolds[k], bodies, friction_points, colours_.starts[c] + offset / width, offset % width);
    }
  }
  const int overflow = static_cast<int>(manifolds.size()) - colours.starts.back();
  for (int k = 0; k < overflow; ++k) {
    PackLane<W>(points, manifolds[colours.starts.back() + k], bodies, friction_points, colours_.starts.back() + k, 0);
  }
}

void WideBundles::ClearSlots(int bundle, int lane, int from) {
  using namespace wide;
  float* base = Aligned() + offsets_[bundle] + lane;
  for (int s = from; s < slots_[bundle]; ++s) {
    for (const int field : {kRa, kRb}) {
      for (int k = 0; k < 3; ++k) base[(SlotAt(s, field) + k) * width_] = 0.0f;
    }
    if (!friction_at_anchors_) {
      for (const int field : {kFa, kFb}) {
        for (int k = 0; k < 3; ++k) base[(SlotAt(s, field) + k) * width_] = 0.0f;
      }
    }
    for (const int field : {kSeparation, kLambdaN, kLambdaT1, kLambdaT2}) base[SlotAt(s, field) * width_] = 0.0f;
  }
}

void WideBundles::ClearLane(int bundle, int lane) {
  // the lane's own fields up to its K^-1, which the prepare kernel writes,
  // and its slots' (clearing every field cost 0.07M instructions a float
  // pyramid step, BENCHMARKS.md, "soft: the float path")
  float* base = Aligned() + offsets_[bundle] + lane;
  for (int field = 0; field < wide::kBlock; ++field) base[field * width_] = 0.0f;
  ClearSlots(bundle, lane, 0);
}

template <class Read>
void WideBundles::ForEachPoint(const Read& read) const {
  const float* data = Aligned();
  for (size_t bundle = 0; bundle < slots_.size(); ++bundle) {
    const float* base = data + offsets_[bundle];
    const int* entry = &points_[bundle * width_ * wide::kSlots];
    for (int lane = 0; lane < width_; ++lane, entry += wide::kSlots) {
      for (int s = 0; s < slots_[bundle]; ++s) {
        if (entry[s] >= 0) read(entry[s], s, base + lane);
      }
    }
  }
}

void WideBundles::Unpack(std::vector<SoftPoint>& points) const {
  if (width_ == 8) {
    UnpackLanes<8>(points);
  } else if (width_ == 4) {
    UnpackLanes<4>(points);
  } else {
    UnpackLanes<0>(points);
  }
}

// the width known when compiling, as in PackLane
template <int W>
void WideBundles::UnpackLanes(std::vector<SoftPoint>& points) const {
  using namespace wide;
  const int width = W > 0 ? W : width_;
  ForEachPoint([&](int k, int s, const float* base) {
    const auto get = [&](int field) { return static_cast<double>(base[SlotAt(s, field) * width]); };
    SoftPoint& p = points[k];
    p.lambda_n = get(kLambdaN), p.lambda_t1 = get(kLambdaT1), p.lambda_t2 = get(kLambdaT2);
    p.max_push = get(kMaxPush);
    p.total_n = get(kTotalN), p.total_t1 = get(kTotalT1), p.total_t2 = get(kTotalT2);
  });
}

void WideBundles::UnpackFrictionRows(std::vector<SoftPoint>& points) const {
  using namespace wide;
  ForEachPoint([&](int k, int s, const float* base) {
    const auto get = [&](int field) { return static_cast<double>(base[SlotAt(s, field) * width_]); };
    const auto get3 = [&](int field) { return Vec3(get(field), get(field + 1), get(field + 2)); };
    SoftPoint& p = points[k];
    p.ra_t1 = get3(kRaT1), p.ra_t2 = get3(kRaT2), p.rb_t1 = get3(kRbT1), p.rb_t2 = get3(kRbT2);
    p.ia_t1 = get3(kIaT1), p.ia_t2 = get3(kIaT2), p.ib_t1 = get3(kIbT1), p.ib_t2 = get3(kIbT2);
    p.mass_t1 = get(kMassT1), p.mass_t2 = get(kMassT2), p.k_t12 = get(kKT12);
  });
}

wide::WideView WideBundles::View(wide::WideBody* bodies) {
  wide::WideView view;
  view.data = Aligned();
  view.body_a = body_a_.data();
  view.body_b = body_b_.data();
  view.write_a = write_a_.data();
  view.write_b = write_b_.data();
  view.slots = slots_.data();
  view.offsets = offsets_.data();
  view.bodies = bodies;
  view.width = width_;
  view.friction_at_anchors = friction_at_anchors_;
  return view;
}

}  // namespace contactsim
