#include "service/contact/lcp/warm_start_cache.h"

#include <algorithm>

namespace contactsim {

void WarmStartCache::Load(const ContactSet& contacts, std::vector<ConstraintRow>* rows) const {
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    const Entry probe{Key{c.id_a, c.id_b, c.feature_id}, {}, 0};
    const auto it = std::lower_bound(impulses_.begin(), impulses_.end(), probe);
    const bool found = it != impulses_.end() && it->key == probe.key;
    for (int j = 0; j < 3; ++j) (*rows)[3 * k + j].lambda = found ? it->lambda[j] : 0.0;
  }
}

void WarmStartCache::Store(const ContactSet& contacts, const std::vector<ConstraintRow>& rows) {
  impulses_.clear();
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    if (rows[3 * k].lambda <= 0.0) continue;
    impulses_.push_back({Key{c.id_a, c.id_b, c.feature_id},
                         {rows[3 * k].lambda, rows[3 * k + 1].lambda, rows[3 * k + 2].lambda}, k});
  }
  std::sort(impulses_.begin(), impulses_.end());
}

}  // namespace contactsim
