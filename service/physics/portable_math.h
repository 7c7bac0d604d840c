// Elementary functions that give the same bits on every x86-64 machine and
// under every compiler (docs/snapshots.md, "Determinism across builds").
//
// The C library's sin, cos, exp, log, pow, atan2 and asin are not: glibc
// picks at load time, by CPU, between code paths built with and without
// fused multiply-add (its IFUNC variants), which round differently in the
// last bit for some arguments, so a run would depend on the machine that
// replays it. These use only IEEE 754 operations that are exactly rounded
// (+, -, *, /, sqrt) and exact ones (nearbyint, frexp, ldexp), in a fixed
// order, with the build's contraction off (CMakeLists.txt): the result is
// a function of the argument alone.
//
// Method (Cody and Waite 1980, "Software Manual for the Elementary
// Functions"; Muller 2016, "Elementary Functions", ch. 11): an additive or
// multiplicative argument reduction with constants split in a high part
// whose products are exact and a low part, then a Taylor polynomial in the
// reduced argument, long enough that its truncation is below half an ulp,
// evaluated by Horner's rule. Accuracy, measured against glibc in
// tests/physics/portable_math_test.cpp: within 2 ulp for sin and cos on
// |x| < 1e5 (the reduction by pi/2 is exact below 2^20 pi/2, about 1.6e6;
// beyond it the results stay deterministic but lose accuracy), exp, log and
// atan2, 3 ulp for asin; pow is exp(y log x), within about |y log x| + 2 ulp.
#pragma once

namespace contactsim {
namespace portable {

double Sin(double x);
double Cos(double x);
double Exp(double x);
double Log(double x);  // NaN for x < 0, -inf for 0
// x^y for x >= 0 (NaN for x < 0): exp(y log x); 0^y is 0 for y > 0 and 1 for y = 0.
double Pow(double x, double y);
double Atan2(double y, double x);  // IEEE 754 special cases (signed zeros, infinities)
double Asin(double x);             // NaN outside [-1, 1]

}  // namespace portable
}  // namespace contactsim
