// The minimum-norm solution of S y = b for a sparse symmetric positive
// semidefinite S with unit diagonal: the Jacobi-scaled Delassus matrix of
// a direct solve (subspace_solve.h), singular wherever coplanar contact
// points share a face (four normal rows, rank three) or statically
// indeterminate supports share a body.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <memory>
#include <vector>

namespace contactsim {

struct MinNormReport {
  bool fallback = false;  // the dense decomposition answered (b outside S's range)
};

// The symbolic analysis of the sparse Cholesky factor (its fill-reducing
// AMD ordering and elimination tree) of the sparsity patterns solved most
// recently. The ordering costs three times the numeric factorisation of an
// arm's rows with the contacts on its links, and a component's pattern
// repeats from pass to pass and step to step while its active set holds;
// the analysis depends on the pattern alone, so reusing it changes no bit of
// the factor.
class MinNormCache {
 public:
  using Factor = Eigen::SimplicialLLT<Eigen::SparseMatrix<double>>;
  // A factor analysed for R's pattern (R compressed), from the cache or new.
  Factor& AnalysedFor(const Eigen::SparseMatrix<double>& R);

 private:
  struct Entry {
    std::vector<int> outer, inner;  // the pattern
    std::unique_ptr<Factor> factor;
    uint64_t last_use = 0;
  };
  static constexpr size_t kEntries = 32;  // a world's jointed components, about
  std::vector<Entry> entries_;
  uint64_t uses_ = 0;
};

// First the sparse Cholesky factor of S + eps I (Tikhonov regularisation:
// its solution tends to the minimum-norm one as eps -> 0 and leaves S's
// null space alone when b lies in S's range), with two steps of iterative
// refinement against S itself, which remove the eps / sigma bias along the
// directions S acts on (Golub and Van Loan, "Matrix Computations", 3.5.3).
// A stack's matrix is banded, so this costs about as much as a few sweeps.
// While the residual still halves with each refinement, more are taken (a
// nearly singular but consistent system converges slowly, at eps / sigma a
// step). When the residual shows that b has a part outside S's range (targets no
// impulses can meet, such as coplanar points asked for speeds no rigid
// motion gives), a dense complete orthogonal decomposition gives the
// least-squares minimum-norm answer instead. `cache` (optional) keeps the
// factor's symbolic analysis from one call to the next.
Eigen::VectorXd MinNormSolve(const Eigen::SparseMatrix<double>& S, const Eigen::VectorXd& b,
                             MinNormReport* report = nullptr, MinNormCache* cache = nullptr);

}  // namespace contactsim
