#include "service/contact/min_norm_solve.h"

#include <Eigen/QR>
#include <algorithm>

namespace contactsim {
namespace {

constexpr double kRegularisation = 1e-8;  // relative to S's unit diagonal
constexpr double kResidual = 1e-10;       // accepted |S y - b| / |b|
constexpr int kRefinements = 2;           // always taken
constexpr int kMaxRefinements = 40;       // taken while each one still halves the residual

}  // namespace

MinNormCache::Factor& MinNormCache::AnalysedFor(const Eigen::SparseMatrix<double>& R) {
  const int* outer = R.outerIndexPtr();
  const int* inner = R.innerIndexPtr();
  const size_t n_outer = static_cast<size_t>(R.outerSize()) + 1;
  const size_t n_inner = static_cast<size_t>(R.nonZeros());
  ++uses_;
  for (Entry& e : entries_) {
    if (e.outer.size() == n_outer && e.inner.size() == n_inner && std::equal(e.outer.begin(), e.outer.end(), outer) &&
        std::equal(e.inner.begin(), e.inner.end(), inner)) {
      e.last_use = uses_;
      return *e.factor;
    }
  }
  Entry* slot = nullptr;
  if (entries_.size() < kEntries) {
    slot = &entries_.emplace_back();
  } else {  // the least recently used
    slot = &*std::min_element(entries_.begin(), entries_.end(),
                              [](const Entry& x, const Entry& y) { return x.last_use < y.last_use; });
  }
  slot->outer.assign(outer, outer + n_outer);
  slot->inner.assign(inner, inner + n_inner);
  slot->factor = std::make_unique<Factor>();
  slot->factor->analyzePattern(R);
  slot->last_use = uses_;
  return *slot->factor;
}

Eigen::VectorXd MinNormSolve(const Eigen::SparseMatrix<double>& S, const Eigen::VectorXd& b,
                             MinNormReport* report, MinNormCache* cache) {
  Eigen::SparseMatrix<double> R = S;
  for (int i = 0; i < R.rows(); ++i) R.coeffRef(i, i) += kRegularisation;
  R.makeCompressed();
  MinNormCache::Factor own;
  MinNormCache::Factor& llt = cache != nullptr ? cache->AnalysedFor(R) : own;
  if (cache == nullptr) llt.analyzePattern(R);
  llt.factorize(R);
  if (llt.info() == Eigen::Success) {
    Eigen::VectorXd y = llt.solve(b);
    for (int step = 0; step < kRefinements; ++step) y += llt.solve(b - S * y);
    const double accepted = kResidual * b.norm();
    Eigen::VectorXd residual = b - S * y;
    double norm = residual.norm();
    // Each refinement shrinks the part of the error along an eigenvector of
    // S with eigenvalue sigma by eps / (sigma + eps): a consistent system
    // whose smallest non-zero sigma is near eps (an arm's joint rows with
    // the contacts on its links, sigma ~ 1e-7) needs a few more than two,
    // still far cheaper than the dense decomposition. A part of b outside
    // S's range does not shrink, and stops the refinements.
    for (int step = kRefinements; step < kMaxRefinements && norm > accepted; ++step) {
      const Eigen::VectorXd next = y + llt.solve(residual);
      Eigen::VectorXd next_residual = b - S * next;
      const double next_norm = next_residual.norm();
      if (!(next_norm < 0.5 * norm)) break;
      y = next;
      residual.swap(next_residual);
      norm = next_norm;
    }
    if (norm <= accepted) return y;
  }
  if (report) report->fallback = true;
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(Eigen::MatrixXd(S)).solve(b);
}

}  // namespace contactsim
