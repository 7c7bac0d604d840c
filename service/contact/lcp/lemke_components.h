// Lemke's method on the rows of each contact component alone: rows that
// share no dynamic body are independent, so the LCP of a step is block
// diagonal over the components (bodies joined by rows, static bodies
// joining nothing), and each block is its own LCP. Lemke's dense tableau
// costs O(n) per pivot over the whole problem and its pivots grow with n,
// so k equal components cost about k^2 less one by one: four hulls
// resting on a heightfield, one problem of up to 420 variables and 550
// pivots a step, took 73% of their time in the tableau's pivots
// (perf record; docs/methods/lcp.md, "Lemke by components").
#pragma once

#include <vector>

#include "service/contact/constraint_row.h"
#include "service/contact/lcp/lemke.h"
#include "service/contact/lcp/solve_report.h"
#include "service/physics/status.h"

namespace contactsim {

// SolveRowsLemke (lemke_rows.h) on each component of `rows`; the report
// sums the pivots and keeps the largest residual and complementarity. When
// any component ends without a solution nothing is applied and the report
// says so, as SolveRowsLemke's does.
Status SolveRowsLemkeByComponent(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                                 const LemkeOptions& options, SolveReport* report);

}  // namespace contactsim
