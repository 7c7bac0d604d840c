// Friction against spinning from the contact patch (torsional friction),
// the `patch_torsion` parameter of the methods that take it.
//
// A face resting on a face touches over an area, but the narrowphase
// reports its corners (manifold_reduction.h), and Coulomb friction at n
// corners, each carrying N / n at r_i from the centre, resists a spin about
// the normal with the moment mu sum (N / n) r_i: a square of side a,
// mu N a / sqrt(2). Under uniform pressure p = N / A over the patch P the
// friction p mu dA at every point opposes its velocity, and a spin about
// the area centroid c meets the moment
//   M = mu (N / A) integral_P |x - c| dA = mu N r_eff,
// r_eff the patch's mean distance from its centroid (Goyal, Ruina and
// Papadopoulos 1991, "Planar sliding with dry friction", the limit
// surface's pure-moment point; Xydas and Kao 1999 for soft fingers; MuJoCo's
// condim 4 takes a torsional coefficient times N instead). For a square of
// side a, r_eff = a (sqrt(2) + ln(1 + sqrt(2))) / 6 = 0.3826 a, 0.541 times
// the corners' a / sqrt(2); for a disc of radius R, 2 R / 3.
//
// `uniform` keeps the corners and their Coulomb disks and moves the point
// where each one's friction acts toward the centroid, in the contact plane,
//   p_i' = p_i - (1 - s) d_i,  s = r_eff / mean_i |d_i|,
// d_i the in-plane offset of p_i from c. Pure sliding is unchanged (each
// corner still bounds its friction by mu lambda_n,i, and the tangent forces
// act at the same height, so the tipping moment is the same); a pure spin
// meets mu sum lambda_n,i s |d_i|, mu N r_eff when the corners carry equal
// shares; between the two, the friction at each moved point opposes the
// velocity there, a four-point quadrature of the patch that dissipates and
// never drives. Adding a torsion row on top of the corners would count the
// twist twice; replacing their friction with one at the centre and a
// torsion row (xpbd's patch, xpbd_patch_friction.h, whose twist limit takes
// r_eff instead) needs a solver of its own for each method. The normal rows
// keep the corners: they carry the patch's tilt.
//
// Two points (an edge, a lying capsule) and one have no area: their
// friction stays where they are.
#pragma once

#include <string>
#include <vector>

#include "service/collision/contact.h"
#include "service/contact/param_table.h"

namespace contactsim {

enum class PatchTorsion { kOff, kUniform };

// The parameter's text to its meaning (the table has validated it).
inline PatchTorsion ParsePatchTorsion(const std::string& text) {
  return text == "uniform" ? PatchTorsion::kUniform : PatchTorsion::kOff;
}

template <class P>
ParamField<P> PatchTorsionParam(std::string P::*member) {
  return ChoiceParam("patch_torsion", member, {"off", "uniform"},
                     "friction against spin about a face contact's normal: off = at its corners' Coulomb rate, "
                     "uniform = that of uniform pressure over the patch, mu N r_eff (patch_torsion.h)");
}

// The error for a method whose friction has no patch to take it from.
Status RefusePatchTorsion(const char* method, const ParamMap& params, const char* why);

// The mean distance from the area centroid of the convex hull of `points`
// (m, in a plane with unit normal n), and the centroid; 0 when the hull
// has no area (fewer than three points, or all on a line).
double UniformPatchRadius(const Vec3* points, int count, const Vec3& n, Vec3* centroid);

// For every contact of `contacts`, the point where its friction acts
// (world): its own, or, for a patch of three or more consecutive contacts
// of one body pair with one normal, moved toward the centroid as above.
void PatchFrictionPoints(const ContactSet& contacts, std::vector<Vec3>* points);

}  // namespace contactsim
