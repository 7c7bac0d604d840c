#include "service/contact/barrier/barrier_state.h"

#include <cstdint>

#include "service/physics/byte_stream.h"

namespace contactsim {
namespace {

template <typename M>
void PutMatrix(ByteWriter& out, const M& m) {
  for (Eigen::Index i = 0; i < m.size(); ++i) out.Put(m.data()[i]);
}

template <typename M>
bool GetMatrix(ByteReader& in, M* m) {
  for (Eigen::Index i = 0; i < m->size(); ++i) {
    if (!in.Get(&m->data()[i])) return false;
  }
  return true;
}

}  // namespace

bool AffineBodyState::Matches(const RigidBody& body) const {
  return body.x == x && body.q.coeffs() == rotation.coeffs() && body.P == P && body.L == L;
}

void AffineBodyState::Stamp(const RigidBody& body) {
  x = body.x;
  rotation = body.q;
  P = body.P;
  L = body.L;
}

std::string BarrierState::Save() const {
  ByteWriter out;
  out.Put(static_cast<uint64_t>(bodies.size()));
  for (const auto& [id, s] : bodies) {
    out.Put(id);
    PutMatrix(out, s.q);
    PutMatrix(out, s.qdot);
    PutMatrix(out, s.x);
    PutMatrix(out, s.rotation.coeffs());
    PutMatrix(out, s.P);
    PutMatrix(out, s.L);
  }
  out.Put(static_cast<uint64_t>(friction.size()));
  for (const LaggedFriction& f : friction) {
    out.Put(f.a);
    out.Put(f.b);
    PutMatrix(out, f.Xa);
    PutMatrix(out, f.Xb);
    PutMatrix(out, f.T);
    out.Put(f.mu_lambda);
  }
  out.Put(static_cast<uint64_t>(placed.size()));
  for (const PlacedPair& p : placed) {
    out.Put(p.a);
    out.Put(p.b);
    out.Put(static_cast<int32_t>(p.kind));
    out.Put(static_cast<int32_t>(p.ia));
    out.Put(static_cast<int32_t>(p.ib));
    out.Put(static_cast<uint8_t>(p.swapped));
    out.Put(p.zero);
  }
  return out.bytes();
}

bool BarrierState::Restore(const std::string& bytes) {
  if (bytes.empty()) {
    Clear();
    return true;
  }
  ByteReader in(bytes);
  BarrierState loaded;
  uint64_t n = 0;
  bool ok = in.Get(&n);
  for (uint64_t i = 0; ok && i < n; ++i) {
    BodyId id = 0;
    AffineBodyState s;
    ok = in.Get(&id) && GetMatrix(in, &s.q) && GetMatrix(in, &s.qdot) && GetMatrix(in, &s.x) &&
         GetMatrix(in, &s.rotation.coeffs()) && GetMatrix(in, &s.P) && GetMatrix(in, &s.L);
    loaded.bodies[id] = s;
  }
  ok = ok && in.Get(&n);
  for (uint64_t i = 0; ok && i < n; ++i) {
    LaggedFriction f;
    ok = in.Get(&f.a) && in.Get(&f.b) && GetMatrix(in, &f.Xa) && GetMatrix(in, &f.Xb) && GetMatrix(in, &f.T) &&
         in.Get(&f.mu_lambda);
    loaded.friction.push_back(f);
  }
  // (older bytes end here)
  n = 0;
  ok = ok && (in.done() || in.Get(&n));
  for (uint64_t i = 0; ok && i < n; ++i) {
    PlacedPair p;
    int32_t kind = 0, ia = 0, ib = 0;
    uint8_t swapped = 0;
    ok = in.Get(&p.a) && in.Get(&p.b) && in.Get(&kind) && in.Get(&ia) && in.Get(&ib) && in.Get(&swapped) &&
         in.Get(&p.zero);
    p.kind = kind, p.ia = ia, p.ib = ib, p.swapped = swapped != 0;
    loaded.placed.push_back(p);
  }
  if (!ok || !in.done()) return false;
  *this = std::move(loaded);
  return true;
}

}  // namespace contactsim
