#include "service/contact/lcp/lemke_components.h"

#include <algorithm>

#include "service/contact/lcp/lemke_rows.h"
#include "service/contact/union_find.h"

namespace contactsim {
namespace {

bool Moves(const std::vector<SolverBody>& bodies, int i) { return i >= 0 && bodies[i].inv_mass > 0.0; }

// Each row's component, numbered in the order of their first rows.
int LabelComponents(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                    std::vector<int>* label) {
  UnionFind sets(static_cast<int>(bodies.size()));
  for (const ConstraintRow& r : rows) {
    if (Moves(bodies, r.a) && Moves(bodies, r.b)) sets.Join(r.a, r.b);
  }
  std::vector<int> number(bodies.size(), -1);
  int count = 0;
  label->assign(rows.size(), -1);
  for (size_t k = 0; k < rows.size(); ++k) {
    const ConstraintRow& r = rows[k];
    const int body = Moves(bodies, r.a) ? r.a : r.b;
    if (body < 0) {  // a row on no body that moves: its own component
      (*label)[k] = count++;
      continue;
    }
    int& n = number[sets.Root(body)];
    if (n < 0) n = count++;
    (*label)[k] = n;
  }
  return count;
}

}  // namespace

Status SolveRowsLemkeByComponent(std::vector<ConstraintRow>& rows, std::vector<SolverBody>& bodies,
                                 const LemkeOptions& options, SolveReport* report) {
  std::vector<int> label;
  const int count = LabelComponents(rows, bodies, &label);
  if (count <= 1) return SolveRowsLemke(rows, bodies, options, report);
  *report = SolveReport();
  report->converged = true;
  const std::vector<SolverBody> start = bodies;  // put back if a component fails
  std::vector<int> members, local(rows.size(), -1);
  std::vector<ConstraintRow> part;
  for (int c = 0; c < count; ++c) {
    members.clear();
    for (size_t k = 0; k < rows.size(); ++k) {
      if (label[k] == c) local[k] = static_cast<int>(members.size()), members.push_back(static_cast<int>(k));
    }
    part.clear();
    for (int k : members) {
      part.push_back(rows[k]);
      if (part.back().normal_row >= 0) part.back().normal_row = local[part.back().normal_row];
    }
    SolveReport one;
    const Status st = SolveRowsLemke(part, bodies, options, &one);
    report->iterations += one.iterations;
    report->residual = std::max(report->residual, one.residual);
    report->complementarity = std::max(report->complementarity, one.complementarity);
    if (!st.ok() || !one.converged) {
      bodies = start;
      report->converged = false;
      report->outcome = one.outcome;
      return st;
    }
    for (size_t i = 0; i < members.size(); ++i) rows[members[i]].lambda = part[i].lambda;
  }
  return Status::Ok();
}

}  // namespace contactsim
