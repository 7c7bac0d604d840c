#include "service/contact/soft/soft_point_order.h"

namespace contactsim {
namespace {

// manifolds a thread copies at a time
constexpr int kOrderGrain = 256;

}  // namespace

void SoftPointOrder::Apply(ParallelRunner& runner, std::vector<SoftManifold>* manifolds,
                           std::vector<SoftPoint>* points) {
  const int n = static_cast<int>(manifolds->size());
  starts_.resize(n);
  int next = 0;
  for (int k = 0; k < n; ++k) {
    starts_[k] = next;
    next += (*manifolds)[k].count;
  }
  point_of_contact_.resize(points->size());
  scratch_.resize(points->size());
  runner.For(n, kOrderGrain, [&](int begin, int end, int) {
    for (int k = begin; k < end; ++k) {
      SoftManifold& m = (*manifolds)[k];
      for (int i = 0; i < m.count; ++i) {
        scratch_[starts_[k] + i] = (*points)[m.first + i];
        point_of_contact_[m.first + i] = starts_[k] + i;
      }
      m.first = starts_[k];
      InvertSoftManifold(scratch_, &m);
    }
  });
  points->swap(scratch_);
}

}  // namespace contactsim
