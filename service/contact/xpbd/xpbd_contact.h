// Contact constraints of extended position based dynamics (Mueller et al.
// 2020, "Detailed rigid body simulation with extended position based
// dynamics", sec. 3.5-3.6).
//
// A contact is found in every sub-step at the predicted poses (xpbd_method.h)
// and remembered by its two surface points in the bodies' frames and its
// world normal n (from A to B, held over the sub-step). In the position
// solve its depth is re-evaluated at the current poses,
//   d = (p_a - p_b) . n,  p_i = x_i + R_i r_i,
// and only penetrating contacts (d > 0) are solved:
//   * non-penetration: the positional constraints move B by d along n
//     (positional_correction.h), lambda_n >= 0;
//   * static friction: the tangential part of the points' relative motion
//     over the sub-step, dp_t of dp = (p_a - p_a,prev) - (p_b - p_b,prev), is
//     undone by positional constraints along two tangents if the resulting
//     sum |lambda_t| stays below mu sum lambda_n (eq. 27), else it slides;
// and after velocities are derived from the poses, the velocity pass
// (sec. 3.6) gives each contact that pushed (lambda_n > 0) in the sub-step
//   * restitution: v_n -> max(-e v~_n, 0) with v~_n the normal velocity
//     before the position solve and e = 0 when |v~_n| is below the threshold
//     (the paper's 2 |g| h, so a resting contact does not jitter);
//   * dynamic friction: the impulse that stops v_t, at most mu lambda_n / h
//     (eq. 30 with f_n = lambda_n / h^2).
// v_n = n . (v_b - v_a) at the contact, negative when approaching.
//
// Where the paper updates contact by contact, the points of one body pair
// (a face's four corners) are solved together, by the minimum-norm solution
// of their coupled equations (PairCoupling), and friction's cone is the
// pair's. One corner at a time lifts and tilts the box, so that the first
// corner slips by half its depth and leaves the cone: measured on a resting
// 0.2 m box with 20 sub-steps, a steady drift of 0.14 mm/s and a spin of
// 7e-4 rad/s, and a five-box stack moving 2 cm in 10 s (now 7 um).
#pragma once

#include <vector>

#include "service/collision/contact.h"
#include "service/physics/world.h"

namespace contactsim {

struct XpbdContact {
  int a = -1, b = -1;         // body indices
  Vec3 ra_body, rb_body;      // m, each body's surface point in its own frame
  Vec3 n;                     // unit, world, from A to B
  double friction = 0.0;      // mu (static and dynamic)
  double restitution = 0.0;   // e
  // per sub-step
  double lambda_n = 0.0;      // kg m, accumulated normal multiplier
  Vec3 lambda_t = Vec3::Zero(); // kg m, accumulated static friction multiplier (world)
  double vn_before = 0.0;     // m/s, v_n before the position solve
  Vec3 impulse = Vec3::Zero();  // N s on B (world): lambda / h plus the velocity pass, this sub-step
};

// Poses at the start of a sub-step, for the static friction's displacement.
struct XpbdPose {
  Vec3 x;
  Quat q;
};

// Remembers a detected contact by its surface points in the body frames.
XpbdContact MakeXpbdContact(const Contact& c, const World& world);

// Current depth (m, > 0 penetrating) and the world surface points.
double XpbdContactDepth(const XpbdContact& c, const World& world, Vec3* pa = nullptr, Vec3* pb = nullptr);

// Resets the multipliers and records v~_n (call after the prediction).
void BeginXpbdSubstep(const World& world, std::vector<XpbdContact>* contacts);

// One position iteration over the contacts (non-penetration, then static
// friction); start holds the sub-step's starting poses, h is its length.
void SolveXpbdContactPositions(World& world, const std::vector<XpbdPose>& start, double h, double alpha_tilde,
                               std::vector<XpbdContact>* contacts);

// The velocity pass: dynamic friction and restitution; restitution applies
// when the approach speed exceeds `restitution_threshold` (m/s).
void SolveXpbdContactVelocities(World& world, double h, double restitution_threshold,
                                std::vector<XpbdContact>* contacts);

}  // namespace contactsim
