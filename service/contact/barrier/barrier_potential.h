// The scalar functions of Incremental Potential Contact (Li, Ferguson,
// Schneider, Langlois, Zorin, Panozzo, Jiang and Kaufman 2020, SIGGRAPH):
//  * the log barrier on a distance d with activation distance d_hat (eq. 6),
//      b(d) = -(d - d_hat)^2 ln(d / d_hat) for 0 < d < d_hat, 0 beyond,
//    C2 at d_hat and infinite at contact, so a minimiser never touches;
//  * the smoothed friction of lagged contacts (sec. 5): the tangential
//    displacement y over the step enters as f0(y) with f0' = f1,
//      f1(y) = -y^2 / eps^2 + 2 y / eps for y < eps, 1 beyond,
//    with eps = eps_v h: static friction up to slip speed eps_v, Coulomb's
//    mu lambda beyond.
#pragma once

namespace contactsim {

double Barrier(double d, double d_hat);
double BarrierFirstDerivative(double d, double d_hat);
double BarrierSecondDerivative(double d, double d_hat);

double FrictionF0(double y, double eps);
double FrictionF1(double y, double eps);
// f1(y) / y, finite (2 / eps) as y -> 0
double FrictionF1OverY(double y, double eps);

}  // namespace contactsim
