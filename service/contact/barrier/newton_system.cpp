#include "service/contact/barrier/newton_system.h"

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>

#include "service/contact/union_find.h"

namespace contactsim {

void NewtonSystem::Reset(int slots) {
  gradient_.assign(slots, Vec12::Zero());
  diagonal_.assign(slots, Mat12::Zero());
  coupled_.clear();
  coupling_.clear();
  index_.clear();
  incident_.assign(slots, {});
}

Mat12& NewtonSystem::Coupling(int r, int c, bool* transposed) {
  *transposed = r > c;
  if (r > c) std::swap(r, c);
  const long long key = static_cast<long long>(r) * slots() + c;
  const auto [it, added] = index_.try_emplace(key, static_cast<int>(coupled_.size()));
  if (added) {
    coupled_.emplace_back(r, c);
    coupling_.push_back(Mat12::Zero());
    incident_[r].push_back(it->second);
    incident_[c].push_back(it->second);
  }
  return coupling_[it->second];
}

bool NewtonSystem::Solve(std::vector<Vec12>* dq) {
  const int n = slots();
  dq->assign(n, Vec12::Zero());
  UnionFind sets(n);
  for (const auto& [r, c] : coupled_) sets.Join(r, c);
  // components in the order of their smallest slot, slots ascending
  std::vector<std::vector<int>> components;
  std::vector<int> component_of(n, -1);
  for (int s = 0; s < n; ++s) {
    const int root = sets.Root(s);
    if (component_of[root] < 0) {
      component_of[root] = static_cast<int>(components.size());
      components.emplace_back();
    }
    components[component_of[root]].push_back(s);
  }
  for (const std::vector<int>& component : components) {
    if (!SolveComponent(component, dq)) return false;
  }
  return true;
}

bool NewtonSystem::SolveComponent(const std::vector<int>& slots, std::vector<Vec12>* dq) {
  if (slots.size() == 1) {
    const int s = slots[0];
    const Eigen::LDLT<Mat12> ldlt(diagonal_[s]);
    if (ldlt.info() != Eigen::Success) return false;
    (*dq)[s] = ldlt.solve(-gradient_[s]);
    return true;
  }
  // local numbering, and the lower triangle of the component's blocks
  std::unordered_map<int, int> local;
  for (size_t k = 0; k < slots.size(); ++k) local[slots[k]] = static_cast<int>(k);
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd rhs(12 * slots.size());
  for (size_t k = 0; k < slots.size(); ++k) {
    const int s = slots[k];
    rhs.segment<12>(12 * k) = -gradient_[s];
    const Mat12& d = diagonal_[s];
    for (int c = 0; c < 12; ++c) {
      for (int r = c; r < 12; ++r) {
        if (d(r, c) != 0.0) triplets.emplace_back(12 * k + r, 12 * k + c, d(r, c));
      }
    }
    // each coupling once, from its larger slot (its row blocks are below the diagonal)
    for (int place : incident_[s]) {
      const auto [r, c] = coupled_[place];
      if (c != s) continue;
      const int lr = local[c], lc = local[r];   // block (c, r) = coupling^T
      const Mat12& m = coupling_[place];
      for (int i = 0; i < 12; ++i) {
        for (int j = 0; j < 12; ++j) {
          if (m(j, i) != 0.0) triplets.emplace_back(12 * lr + i, 12 * lc + j, m(j, i));
        }
      }
    }
  }
  const int dim = 12 * static_cast<int>(slots.size());
  Eigen::SparseMatrix<double> H(dim, dim);
  H.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower> ldlt(H);
  if (ldlt.info() != Eigen::Success) return false;
  const Eigen::VectorXd x = ldlt.solve(rhs);
  for (size_t k = 0; k < slots.size(); ++k) (*dq)[slots[k]] = x.segment<12>(12 * k);
  return true;
}

}  // namespace contactsim
