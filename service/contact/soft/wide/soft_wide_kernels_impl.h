// The float path's kernels, written once over the lanes of xsimd's batch
// of an instruction set (soft_wide_kernels.h). Included by one source file
// per instruction set; everything here is that file's own (an unnamed
// namespace), so the AVX copy is never linked where SSE2 code runs.
//
// The rows are SoftPoint's (soft_contact.h), with the same formulas: the
// friction disk per point (SlipFrictionStep, slip_friction_step.h), then
// the normal rows as a block (SolveBlockNormals, soft_manifold.cpp)
// accepted per lane when every impulse stays >= 0, else swept point by
// point (SolveSoftNormal). Where the scalar code branches, the lanes take
// both sides and select. The prepare kernel and the table of an
// instruction set's kernels are soft_wide_prepare_impl.h's.
#pragma once

#include <xsimd/xsimd.hpp>

#include "service/contact/soft/wide/soft_wide_kernels.h"
#include "service/contact/soft/wide/soft_wide_transpose.h"

namespace contactsim {
namespace wide {
namespace {

// m: a point at most this far apart counts as touching (a soft row, not a
// speculative rigid one). The separations are exact to the motion
// (NormalTargets), so a face placed exactly touching, s_0 = 0, takes its
// corners' signs from the turn that float's round-off in the passes gives
// it (1e-7 rad/s, 1e-11 m at a corner in a sub-step): corners either side
// of 0 mixed rigid and soft rows in one block, and an aligned stack of
// 0.04 m cubes drifted 2.4 mm sideways. 1e-9 m is a hundred times that
// and a thousandth of the gap a pushing point rests at (0.9 um, soft.md).
constexpr float kTouchingGap = 1e-9f;

template <class Arch>
struct Lanes {
  using B = xsimd::batch<float, Arch>;
  using M = xsimd::batch_bool<float, Arch>;
  static constexpr int W = static_cast<int>(B::size);

  struct V3 {
    B x, y, z;
  };
  static V3 Add(const V3& a, const V3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  static V3 Sub(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  static V3 Mul(const B& s, const V3& a) { return {s * a.x, s * a.y, s * a.z}; }
  static B Dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
  static V3 Select(const M& m, const V3& a, const V3& b) {
    return {xsimd::select(m, a.x, b.x), xsimd::select(m, a.y, b.y), xsimd::select(m, a.z, b.z)};
  }

  // One bundle's fields.
  struct Fields {
    float* base;
    B Get(int f) const { return B::load_aligned(base + f * W); }
    V3 Get3(int f) const { return {Get(f), Get(f + 1), Get(f + 2)}; }
    void Set(int f, const B& x) const { x.store_aligned(base + f * W); }
  };
  static Fields Of(const WideView& view, int bundle) {
    return {view.data + view.offsets[bundle]};
  }

  // The two bodies' velocities, lane by lane.
  struct Pair {
    V3 va, wa, vb, wb;
  };
  // The motion since the step's start that a separation reads (the turns
  // as dR - I, WideBody::turn).
  struct Motion {
    V3 dpa, dpb;
    B dra[9], drb[9];
  };

  // The first `count` floats of each lane's body (WideBody's order: v, w,
  // dp, turn) as batches: whole batches of columns transposed in
  // registers where the instruction set allows (soft_wide_transpose.h),
  // the rest through a buffer.
  static void GatherFields(const WideView& view, const int* index, int count, B* out) {
    const float* rows[W];
    for (int l = 0; l < W; ++l) rows[l] = view.bodies[index[l]].Floats();
    if constexpr (TransposesInRegisters<B>()) {
      int done = 0;
      for (; done < count && done + W <= kWideBodyFloats; done += W) LoadColumns(rows, done, out + done);
      // the last few over the batch before them again (the same floats)
      if (done < count) LoadColumns(rows, count - W, out + count - W);
      return;
    }
    const int done = 0;
    alignas(kAlign) float buf[kWideBodyFloats][W];
    for (int l = 0; l < W; ++l) {
      for (int k = done; k < count; ++k) buf[k][l] = rows[l][k];
    }
    for (int k = done; k < count; ++k) out[k] = B::load_aligned(buf[k]);
  }
  static void GatherSide(const WideView& view, const int* index, V3* v, V3* w, V3* dp, B* dr) {
    B f[kWideBodyFloats];
    GatherFields(view, index, dp == nullptr ? 6 : kWideBodyFloats, f);
    *v = {f[0], f[1], f[2]};
    *w = {f[3], f[4], f[5]};
    if (dp == nullptr) return;
    *dp = {f[6], f[7], f[8]};
    for (int k = 0; k < 9; ++k) dr[k] = f[9 + k];
  }
  static void Gather(const WideView& view, int bundle, Pair* p, Motion* m) {
    const int* a = view.body_a + bundle * W;
    const int* b = view.body_b + bundle * W;
    GatherSide(view, a, &p->va, &p->wa, m != nullptr ? &m->dpa : nullptr, m != nullptr ? m->dra : nullptr);
    GatherSide(view, b, &p->vb, &p->wb, m != nullptr ? &m->dpb : nullptr, m != nullptr ? m->drb : nullptr);
  }
  // Only dynamic bodies are written: a static or kinematic one may sit in
  // several lanes and bundles at once (block_colours.h).
  static void ScatterSide(const WideView& view, const int* index, const unsigned char* write, const V3& v,
                          const V3& w) {
    if constexpr (TransposesInRegisters<B>()) {
      float* rows[W];
      for (int l = 0; l < W; ++l) rows[l] = view.bodies[index[l]].Floats();
      const B c[6] = {v.x, v.y, v.z, w.x, w.y, w.z};
      StoreRows6(c, rows, write);
      return;
    }
    alignas(kAlign) float buf[6][W];
    v.x.store_aligned(buf[0]), v.y.store_aligned(buf[1]), v.z.store_aligned(buf[2]);
    w.x.store_aligned(buf[3]), w.y.store_aligned(buf[4]), w.z.store_aligned(buf[5]);
    for (int l = 0; l < W; ++l) {
      if (write[l] == 0) continue;
      WideBody& body = view.bodies[index[l]];
      for (int k = 0; k < 3; ++k) {
        body.v[k] = buf[k][l];
        body.w[k] = buf[3 + k][l];
      }
    }
  }
  static void Scatter(const WideView& view, int bundle, const Pair& p) {
    ScatterSide(view, view.body_a + bundle * W, view.write_a + bundle * W, p.va, p.wa);
    ScatterSide(view, view.body_b + bundle * W, view.write_b + bundle * W, p.vb, p.wb);
  }

  // -j d on A at its response ia, +j d on B (PushImpulse): a body without
  // inverse mass has zero responses and is left as it was.
  static void Push(const B& j, const V3& d, const V3& ia, const V3& ib, const B& ima, const B& imb, Pair& p) {
    p.va = Sub(p.va, Mul(ima * j, d));
    p.wa = Sub(p.wa, Mul(j, ia));
    p.vb = Add(p.vb, Mul(imb * j, d));
    p.wb = Add(p.wb, Mul(j, ib));
  }

  static void WarmStart(const WideView& view, int begin, int end) {
    for (int bundle = begin; bundle < end; ++bundle) {
      const Fields f = Of(view, bundle);
      Pair p;
      Gather(view, bundle, &p, nullptr);
      const V3 n = f.Get3(kN), t1 = f.Get3(kT1), t2 = f.Get3(kT2);
      const B ima = f.Get(kInvMassA), imb = f.Get(kInvMassB);
      for (int s = 0; s < view.slots[bundle]; ++s) {
        const auto at = [s](int field) { return SlotAt(s, field); };
        Push(f.Get(at(kLambdaN)), n, f.Get3(at(kIaN)), f.Get3(at(kIbN)), ima, imb, p);
        Push(f.Get(at(kLambdaT1)), t1, f.Get3(at(kIaT1)), f.Get3(at(kIbT1)), ima, imb, p);
        Push(f.Get(at(kLambdaT2)), t2, f.Get3(at(kIaT2)), f.Get3(at(kIbT2)), ima, imb, p);
      }
      Scatter(view, bundle, p);
    }
  }

  static void Accumulate(const WideView& view, int begin, int end) {
    for (int bundle = begin; bundle < end; ++bundle) {
      const Fields f = Of(view, bundle);
      for (int s = 0; s < view.slots[bundle]; ++s) {
        f.Set(SlotAt(s, kTotalN), f.Get(SlotAt(s, kTotalN)) + f.Get(SlotAt(s, kLambdaN)));
        f.Set(SlotAt(s, kTotalT1), f.Get(SlotAt(s, kTotalT1)) + f.Get(SlotAt(s, kLambdaT1)));
        f.Set(SlotAt(s, kTotalT2), f.Get(SlotAt(s, kTotalT2)) + f.Get(SlotAt(s, kLambdaT2)));
      }
    }
  }

  // SlipFrictionStep over the lanes: the per-axis update, along the slip
  // where it leaves the disk, then onto the disk.
  static void SlipStep(const B& limit, const B& u1, const B& u2, const B& m1, const B& m2, const B& k12, B* l1,
                       B* l2) {
    const B zero(0.0f), one(1.0f);
    B n1 = *l1 - m1 * u1;
    B n2 = *l2 - m2 * u2;
    B squared = n1 * n1 + n2 * n2;
    const M over = squared > limit * limit;
    if (xsimd::any(over)) {
      const B uu = u1 * u1 + u2 * u2;
      const M has1 = m1 > zero, has2 = m2 > zero;
      const B uku = xsimd::select(has1, u1 * u1 / xsimd::select(has1, m1, one), zero) +
                    B(2.0f) * k12 * u1 * u2 + xsimd::select(has2, u2 * u2 / xsimd::select(has2, m2, one), zero);
      const M slide = over && (uu > zero) && (uku > zero);
      const B step = uu / xsimd::select(slide, uku, one);
      n1 = xsimd::select(slide, *l1 - step * u1, n1);
      n2 = xsimd::select(slide, *l2 - step * u2, n2);
      squared = xsimd::select(slide, n1 * n1 + n2 * n2, squared);
      const M clip = over && (squared > limit * limit);
      const M positive = squared > zero;
      const B scale = xsimd::select(positive, limit / xsimd::sqrt(xsimd::select(positive, squared, one)), zero);
      n1 = xsimd::select(clip, n1 * scale, n1);
      n2 = xsimd::select(clip, n2 * scale, n2);
    }
    *l1 = n1;
    *l2 = n2;
  }

  static void SolveFriction(const Fields& f, int s, const V3& t1, const V3& t2, const B& ima, const B& imb, Pair& p) {
    const auto at = [s](int field) { return SlotAt(s, field); };
    const V3 dv = Sub(p.vb, p.va);
    const B u1 = Dot(t1, dv) + Dot(f.Get3(at(kRbT1)), p.wb) - Dot(f.Get3(at(kRaT1)), p.wa);
    const B u2 = Dot(t2, dv) + Dot(f.Get3(at(kRbT2)), p.wb) - Dot(f.Get3(at(kRaT2)), p.wa);
    const B l1_old = f.Get(at(kLambdaT1)), l2_old = f.Get(at(kLambdaT2));
    B l1 = l1_old, l2 = l2_old;
    SlipStep(f.Get(kFriction) * f.Get(at(kLambdaN)), u1, u2, f.Get(at(kMassT1)), f.Get(at(kMassT2)),
             f.Get(at(kKT12)), &l1, &l2);
    f.Set(at(kLambdaT1), l1);
    f.Set(at(kLambdaT2), l2);
    const B d1 = l1 - l1_old, d2 = l2 - l2_old;
    const V3 J = Add(Mul(d1, t1), Mul(d2, t2));
    p.va = Sub(p.va, Mul(ima, J));
    p.wa = Sub(p.wa, Add(Mul(d1, f.Get3(at(kIaT1))), Mul(d2, f.Get3(at(kIaT2)))));
    p.vb = Add(p.vb, Mul(imb, J));
    p.wb = Add(p.wb, Add(Mul(d1, f.Get3(at(kIbT1))), Mul(d2, f.Get3(at(kIbT2)))));
  }

  // What each point's normal row aims at (SoftNormalTarget) at its
  // separation now, SoftSeparation's s written as
  //   s = s_0 + n . (dp_B - dp_A) + ((dR_B - I)^T n) . r_B - ((dR_A - I)^T n) . r_A,
  // (n . dR r = (dR^T n) . r, so each body's turn meets n once a lane):
  // every term is as small as the motion, so s keeps float's digits of
  // itself. The double path's s_0 - n . (r_B - r_A) + n . (dR_B r_B - dR_A r_A)
  // cancels the anchors' lengths, which in float left s wrong by their
  // round-off, up to 1e-8 m at 0.1 m, afresh each step as the anchors moved:
  // the springs (k ~ 4e4 N/m) chased it, and a hull resting on a face
  // rocked at up to 1.2e-6 m/s.
  struct Targets {
    B bias[kSlots], mass_scale[kSlots], impulse_scale[kSlots];
  };
  static V3 TurnedBack(const B* dr, const V3& n) {  // (dR - I)^T n, dR - I column-major
    return {dr[0] * n.x + dr[1] * n.y + dr[2] * n.z, dr[3] * n.x + dr[4] * n.y + dr[5] * n.z,
            dr[6] * n.x + dr[7] * n.y + dr[8] * n.z};
  }
  static void NormalTargets(const WideView& view, int bundle, const Fields& f, const WidePass& pass, const V3& n,
                            const Motion& m, const B* lambda, Targets* t) {
    const B shift = Dot(n, Sub(m.dpb, m.dpa));
    const V3 na = TurnedBack(m.dra, n), nb = TurnedBack(m.drb, n);
    const B zero(0.0f), one(1.0f), inv_h(pass.inv_h), floor(-pass.max_push_velocity);
    const B bias_rate = f.Get(kBiasRate), mass_scale = f.Get(kMassScale), impulse_scale = f.Get(kImpulseScale);
    for (int s = 0; s < view.slots[bundle]; ++s) {
      const auto at = [s](int field) { return SlotAt(s, field); };
      const B sep = shift + Dot(nb, f.Get3(at(kRb))) - Dot(na, f.Get3(at(kRa))) + f.Get(at(kSeparation));
      // speculative: may close the gap, not pass it
      const M apart = sep > B(kTouchingGap);
      if (pass.use_bias) {
        t->bias[s] = xsimd::select(apart, sep * inv_h, xsimd::max(bias_rate * sep, floor));
        t->mass_scale[s] = xsimd::select(apart, one, mass_scale);
        t->impulse_scale[s] = xsimd::select(apart, zero, impulse_scale);
      } else {
        // a point that pushes keeps its gap (SoftPass::hold_pushing_gaps)
        const M speculative = pass.hold_pushing_gaps ? apart && !(lambda[s] > zero) : apart;
        t->bias[s] = xsimd::select(speculative, sep * inv_h, zero);
        t->mass_scale[s] = one;
        t->impulse_scale[s] = zero;
      }
    }
  }

  // The block solve (SolveBlockNormals): the lanes where every total stays
  // >= 0 come back true, with their bodies, impulses and pushes in `p`, `lambda`, `push`.
  static M BlockNormals(int slots, const Fields& f, const Targets& t, const V3& n, const B& ima, const B& imb,
                        Pair& p, B* lambda, B* push) {
    const B zero(0.0f);
    M ok = f.Get(kBlock) > zero;
    if (!xsimd::any(ok)) return ok;
    const B ndv = Dot(n, Sub(p.vb, p.va));
    B target[kSlots], total[kSlots];
    for (int s = 0; s < slots; ++s) {
      target[s] = ndv + Dot(f.Get3(SlotAt(s, kRbN)), p.wb) - Dot(f.Get3(SlotAt(s, kRaN)), p.wa) + t.bias[s];
    }
    for (int i = 0; i < slots; ++i) {
      B step = f.Get(kInvK + 4 * i) * target[0];
      for (int j = 1; j < slots; ++j) step = step + f.Get(kInvK + 4 * i + j) * target[j];
      total[i] = lambda[i] - t.mass_scale[i] * step - t.impulse_scale[i] * lambda[i];
      ok = ok && (total[i] >= zero);
    }
    if (!xsimd::any(ok)) return ok;
    B sum = zero;
    V3 wa = {zero, zero, zero}, wb = wa;
    for (int s = 0; s < slots; ++s) {
      const B applied = total[s] - lambda[s];
      lambda[s] = total[s];
      push[s] = xsimd::max(push[s], applied);
      sum = sum + applied;
      wa = Add(wa, Mul(applied, f.Get3(SlotAt(s, kIaN))));
      wb = Add(wb, Mul(applied, f.Get3(SlotAt(s, kIbN))));
    }
    p.va = Sub(p.va, Mul(ima * sum, n));
    p.wa = Sub(p.wa, wa);
    p.vb = Add(p.vb, Mul(imb * sum, n));
    p.wb = Add(p.wb, wb);
    return ok;
  }

  // The points one by one (SolveSoftNormal).
  static void SweepNormals(int slots, const Fields& f, const Targets& t, const V3& n, const B& ima, const B& imb,
                           Pair& p, B* lambda, B* push) {
    const B zero(0.0f);
    for (int s = 0; s < slots; ++s) {
      const V3 ran = f.Get3(SlotAt(s, kRaN)), rbn = f.Get3(SlotAt(s, kRbN));
      const B vn = Dot(n, Sub(p.vb, p.va)) + Dot(rbn, p.wb) - Dot(ran, p.wa);
      const B increment = -f.Get(SlotAt(s, kMassN)) * t.mass_scale[s] * (vn + t.bias[s]) -
                          t.impulse_scale[s] * lambda[s];
      const B total = xsimd::max(lambda[s] + increment, zero);
      const B applied = total - lambda[s];
      lambda[s] = total;
      push[s] = xsimd::max(push[s], applied);
      Push(applied, n, f.Get3(SlotAt(s, kIaN)), f.Get3(SlotAt(s, kIbN)), ima, imb, p);
    }
  }

  static void SolveNormals(const WideView& view, int bundle, const Fields& f, const WidePass& pass, const V3& n,
                           const B& ima, const B& imb, const Motion& m, Pair& p) {
    const int slots = view.slots[bundle];
    B lambda[kSlots], push[kSlots];
    for (int s = 0; s < slots; ++s) {
      lambda[s] = f.Get(SlotAt(s, kLambdaN));
      push[s] = f.Get(SlotAt(s, kMaxPush));
    }
    Targets t;
    NormalTargets(view, bundle, f, pass, n, m, lambda, &t);
    Pair block = p;
    B block_lambda[kSlots], block_push[kSlots];
    for (int s = 0; s < slots; ++s) block_lambda[s] = lambda[s], block_push[s] = push[s];
    const M ok = BlockNormals(slots, f, t, n, ima, imb, block, block_lambda, block_push);
    if (!xsimd::all(ok)) SweepNormals(slots, f, t, n, ima, imb, p, lambda, push);
    p.va = Select(ok, block.va, p.va);
    p.wa = Select(ok, block.wa, p.wa);
    p.vb = Select(ok, block.vb, p.vb);
    p.wb = Select(ok, block.wb, p.wb);
    for (int s = 0; s < slots; ++s) {
      f.Set(SlotAt(s, kLambdaN), xsimd::select(ok, block_lambda[s], lambda[s]));
      f.Set(SlotAt(s, kMaxPush), xsimd::select(ok, block_push[s], push[s]));
    }
  }

  static void Solve(const WideView& view, const WidePass& pass, int begin, int end) {
    for (int bundle = begin; bundle < end; ++bundle) {
      const Fields f = Of(view, bundle);
      Pair p;
      Motion m;
      Gather(view, bundle, &p, &m);
      const V3 n = f.Get3(kN), t1 = f.Get3(kT1), t2 = f.Get3(kT2);
      const B ima = f.Get(kInvMassA), imb = f.Get(kInvMassB);
      for (int s = 0; s < view.slots[bundle]; ++s) SolveFriction(f, s, t1, t2, ima, imb, p);
      SolveNormals(view, bundle, f, pass, n, ima, imb, m, p);
      Scatter(view, bundle, p);
    }
  }
};

}  // namespace
}  // namespace wide
}  // namespace contactsim
