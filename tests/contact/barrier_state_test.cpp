// Tests of the barrier method's carried state (barrier_state.h): the bytes a
// snapshot holds give the same state back, placed pairs included, and bytes
// that are cut short or carry trailing data are refused with the state
// kept.
#include "service/contact/barrier/barrier_state.h"

#include <gtest/gtest.h>

#include <string>

namespace contactsim {
namespace {

BarrierState SomeState() {
  BarrierState s;
  AffineBodyState b;
  b.q(0) = 0.5;
  b.qdot(3) = -1.25;
  b.x = Vec3(1, 2, 3);
  s.bodies[7] = b;
  LaggedFriction f;
  f.a = 7;
  f.b = 1;
  f.mu_lambda = 4.5;
  s.friction.push_back(f);
  s.placed.push_back({7, 1, 4, 2, 0, false, -2e-5});
  s.placed.push_back({7, 9, 1, 3, 11, true, 1.5e-6});
  return s;
}

// Verifies that Save and Restore give back every placed pair bit for bit.
TEST(BarrierState, PlacedPairsSurviveASaveAndRestore) {
  const BarrierState s = SomeState();
  BarrierState r;
  ASSERT_TRUE(r.Restore(s.Save()));
  ASSERT_EQ(r.placed.size(), 2u);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(r.placed[i].a, s.placed[i].a);
    EXPECT_EQ(r.placed[i].b, s.placed[i].b);
    EXPECT_EQ(r.placed[i].kind, s.placed[i].kind);
    EXPECT_EQ(r.placed[i].ia, s.placed[i].ia);
    EXPECT_EQ(r.placed[i].ib, s.placed[i].ib);
    EXPECT_EQ(r.placed[i].swapped, s.placed[i].swapped);
    EXPECT_EQ(r.placed[i].zero, s.placed[i].zero);
  }
  EXPECT_EQ(r.bodies.at(7).q, s.bodies.at(7).q);
  EXPECT_EQ(r.friction.at(0).mu_lambda, 4.5);
  EXPECT_EQ(r.Save(), s.Save());
}

// Verifies that bytes saved before placed pairs existed (ending after the
// friction) restore with none, and that cut or padded bytes are refused
// with the state kept.
TEST(BarrierState, OlderBytesHoldNoPlacedPairsAndBadBytesAreRefused) {
  BarrierState older = SomeState();
  older.placed.clear();
  std::string bytes = older.Save();
  bytes.resize(bytes.size() - sizeof(uint64_t));  // no placed-pair count
  BarrierState r;
  ASSERT_TRUE(r.Restore(bytes));
  EXPECT_TRUE(r.placed.empty());
  EXPECT_EQ(r.friction.size(), 1u);

  const std::string full = SomeState().Save();
  BarrierState kept = SomeState();
  EXPECT_FALSE(kept.Restore(full.substr(0, full.size() - 3)));
  EXPECT_FALSE(kept.Restore(full + "x"));
  EXPECT_EQ(kept.Save(), full);
}

}  // namespace
}  // namespace contactsim
