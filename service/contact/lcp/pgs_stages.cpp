// PGS's warm start and sweeps colour by colour as the stages of one
// ParallelRunner::Stages call (pgs.h, "Threads"), built with the stage list
// soft and xpbd use (colour_stages.h). One thread runs the same stages in
// the same order, so the result does not depend on the thread count.
#include <algorithm>

#include "service/contact/colour_stages.h"
#include "service/contact/lcp/pgs.h"
#include "service/contact/lcp/row_complementarity.h"

namespace contactsim {

namespace {

// rows a thread measures the complementarity of at a time
constexpr int kErrorGrain = 1024;

}  // namespace

void PgsSolver::SweepColoured(const PgsOptions& options, std::vector<ConstraintRow>& rows,
                              std::vector<SolverBody>& bodies, SolveReport* report) {
  using Fn = ParallelRunner::StageFn;
  const int groups = static_cast<int>(group_rows_.size()) - 1;
  group_worst_.assign(groups, 0.0);
  // set by the serial stage after a sweep; the stages' barrier orders the
  // write before every later stage's reads
  bool done = false;
  const Fn warm_start = [&](int i, int j) {
    for (int k = group_rows_[i]; k < group_rows_[j]; ++k) {
      const Row& r = rows_[k];
      if (r.lambda != 0.0) Apply(r, vel_[r.a], vel_[r.b], r.lambda);
    }
  };
  const Fn sweep = [&](int i, int j) {
    if (done) return;
    for (int g = i; g < j; ++g) group_worst_[g] = SweepRows(group_rows_[g], group_rows_[g + 1]);
  };
  const Fn check = [&](int, int) {
    if (done) return;
    const double worst = groups > 0 ? *std::max_element(group_worst_.begin(), group_worst_.end()) : 0.0;
    ++report->iterations;
    report->residual = worst;
    report->converged = done = worst < options.tolerance && report->iterations >= options.min_iterations;
  };
  // the impulses go to the bodies through ConstraintRow::Apply, so dP and
  // dL sum; a colour's groups share no body with mass, the only ones written
  const Fn apply = [&](int i, int j) {
    for (int k = group_rows_[i]; k < group_rows_[j]; ++k) {
      ConstraintRow& row = rows[rows_[k].source];
      row.lambda = rows_[k].lambda;
      row.Apply(row.lambda, bodies);
    }
  };
  const int n = static_cast<int>(rows.size());
  chunk_error_.assign((n + kErrorGrain - 1) / kErrorGrain, 0.0);
  const Fn measure = [&](int i, int j) {
    chunk_error_[i / kErrorGrain] = ComplementarityError(rows, bodies, FrictionSet::kDisk, i, j);
  };
  ColourStages list(&stages_, options.runner->threads());
  list.AddColours(warm_start, colours_, groups);
  for (int it = 0; it < options.iterations; ++it) {
    list.AddColours(sweep, colours_, groups);
    list.AddSerial(check);
  }
  list.AddColours(apply, colours_, groups);
  if (options.measure_complementarity) list.Add(measure, 0, n, kErrorGrain);
  options.runner->Stages(stages_);
  report->complementarity = chunk_error_.empty() ? 0.0 : *std::max_element(chunk_error_.begin(), chunk_error_.end());
}

}  // namespace contactsim
