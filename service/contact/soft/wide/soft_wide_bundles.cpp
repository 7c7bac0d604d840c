#include "service/contact/soft/wide/soft_wide_bundles.h"

#include <algorithm>
#include <cstdint>

namespace contactsim {
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
constexpr double kMaxFloatBlockCondition = 1e3;

bool FloatBlock(const std::vector<SoftPoint>& points, const SoftManifold& m) {
  if (!m.block) return false;
  double k_max = 0.0;
  for (int i = 0; i < m.count; ++i) {
    const double mass = points[m.first + i].mass_n;
    if (!(mass > 0.0)) return false;
    k_max = std::max(k_max, 1.0 / mass);
  }
  const double inv_max = m.inv_k.topLeftCorner(m.count, m.count).cwiseAbs().maxCoeff();
  return k_max * inv_max <= kMaxFloatBlockCondition;
}

}  // namespace

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
  data_.assign(floats + kPad, 0.0f);
  body_a_.assign(lanes, dummy_);
  body_b_.assign(lanes, dummy_);
  write_a_.assign(lanes, 0);
  write_b_.assign(lanes, 0);
  points_.assign(lanes * wide::kSlots, -1);
}

void WideBundles::PackLane(const std::vector<SoftPoint>& points, const SoftManifold& m,
                           const std::vector<SoftBody>& bodies, int bundle, int lane) {
  using namespace wide;
  float* base = Aligned() + offsets_[bundle] + lane;
  const auto put = [&](int field, double x) { base[field * width_] = static_cast<float>(x); };
  const auto put3 = [&](int field, const Vec3& v) {
    for (int k = 0; k < 3; ++k) put(field + k, v[k]);
  };
  const SoftPoint& p0 = points[m.first];
  const int index = bundle * width_ + lane;
  body_a_[index] = p0.a;
  body_b_[index] = p0.b;
  write_a_[index] = bodies[p0.a].inv_mass > 0.0 ? 1 : 0;
  write_b_[index] = bodies[p0.b].inv_mass > 0.0 ? 1 : 0;
  put3(kN, p0.n), put3(kT1, p0.t1), put3(kT2, p0.t2);
  put(kInvMassA, bodies[p0.a].inv_mass), put(kInvMassB, bodies[p0.b].inv_mass);
  const bool block = FloatBlock(points, m);
  put(kBlock, block ? 1.0 : 0.0);
  // K^-1's rows and columns past the block's points stay zero
  for (int i = 0; block && i < m.count; ++i) {
    for (int j = 0; j < m.count; ++j) put(kInvK + 4 * i + j, m.inv_k(i, j));
  }
  for (int s = 0; s < m.count; ++s) {
    const SoftPoint& p = points[m.first + s];
    points_[static_cast<size_t>(index) * kSlots + s] = m.first + s;
    const auto at = [s](int field) { return SlotAt(s, field); };
    put3(at(kRa), p.ra), put3(at(kRb), p.rb);
    put3(at(kRaN), p.ra_n), put3(at(kRbN), p.rb_n), put3(at(kIaN), p.ia_n), put3(at(kIbN), p.ib_n);
    put3(at(kRaT1), p.ra_t1), put3(at(kRaT2), p.ra_t2), put3(at(kRbT1), p.rb_t1), put3(at(kRbT2), p.rb_t2);
    put3(at(kIaT1), p.ia_t1), put3(at(kIaT2), p.ia_t2), put3(at(kIbT1), p.ib_t1), put3(at(kIbT2), p.ib_t2);
    put(at(kAdjustedSeparation), p.adjusted_separation);
    put(at(kMassN), p.mass_n), put(at(kMassT1), p.mass_t1), put(at(kMassT2), p.mass_t2), put(at(kKT12), p.k_t12);
    put(at(kFriction), p.friction);
    put(at(kBiasRate), p.soft.bias_rate), put(at(kMassScale), p.soft.mass_scale);
    put(at(kImpulseScale), p.soft.impulse_scale);
    put(at(kLambdaN), p.lambda_n), put(at(kLambdaT1), p.lambda_t1), put(at(kLambdaT2), p.lambda_t2);
  }
}

void WideBundles::Pack(const std::vector<SoftPoint>& points, const std::vector<SoftManifold>& manifolds,
                       const BlockColours& colours, const std::vector<SoftBody>& bodies, int width, int dummy) {
  width_ = width;
  dummy_ = dummy;
  const int overflow = static_cast<int>(manifolds.size()) - colours.starts.back();
  colours_.starts.assign(1, 0);
  for (int c = 0; c < colours.colours(); ++c) {
    const int size = colours.starts[c + 1] - colours.starts[c];
    colours_.starts.push_back(colours_.starts.back() + (size + width_ - 1) / width_);
  }
  Allocate(manifolds, colours);
  for (int c = 0; c < colours.colours(); ++c) {
    for (int k = colours.starts[c]; k < colours.starts[c + 1]; ++k) {
      const int offset = k - colours.starts[c];
      PackLane(points, manifolds[k], bodies, colours_.starts[c] + offset / width_, offset % width_);
    }
  }
  for (int k = 0; k < overflow; ++k) {
    PackLane(points, manifolds[colours.starts.back() + k], bodies, colours_.starts.back() + k, 0);
  }
}

void WideBundles::Unpack(std::vector<SoftPoint>& points) const {
  using namespace wide;
  for (size_t entry = 0; entry < points_.size(); ++entry) {
    const int k = points_[entry];
    if (k < 0) continue;
    const size_t index = entry / kSlots;
    const int s = static_cast<int>(entry % kSlots);
    const size_t bundle = index / width_, lane = index % width_;
    const float* base = Aligned() + offsets_[bundle] + lane;
    const auto get = [&](int field) { return static_cast<double>(base[SlotAt(s, field) * width_]); };
    SoftPoint& p = points[k];
    p.lambda_n = get(kLambdaN), p.lambda_t1 = get(kLambdaT1), p.lambda_t2 = get(kLambdaT2);
    p.max_push = get(kMaxPush);
    p.total_n = get(kTotalN), p.total_t1 = get(kTotalT1), p.total_t2 = get(kTotalT2);
  }
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
  return view;
}

}  // namespace contactsim
