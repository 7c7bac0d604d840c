// Last step's contact impulses, kept per contact feature so that the next
// solve starts from them (warm starting, Catto 2005). Key: (id of A, id of
// B, feature id), in a vector sorted by key and searched by bisection
// (deterministic, and no allocation once its capacity is reached); contact
// pairs come in a canonical body order (docs/conventions.md), so A and B do
// not swap between steps. Three rows per contact: normal, t1, t2.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

#include "service/collision/contact.h"
#include "service/contact/constraint_row.h"

namespace contactsim {

class WarmStartCache {
 public:
  // Sets the lambda of the three rows of each contact from the cache (0 when absent).
  void Load(const ContactSet& contacts, std::vector<ConstraintRow>* rows) const;
  // Replaces the cache by the rows' impulses.
  void Store(const ContactSet& contacts, const std::vector<ConstraintRow>& rows);
  void Clear() { impulses_.clear(); }
  // The impulses bit for bit, for snapshots (ContactMethod::SaveState).
  std::string Save() const;
  // Replaces the impulses by saved ones; false (and nothing changed) when
  // the bytes are malformed.
  bool Restore(const std::string& bytes);
  size_t size() const { return impulses_.size(); }

 private:
  using Key = std::tuple<BodyId, BodyId, uint32_t>;
  struct Entry {
    Key key;
    std::array<double, 3> lambda;
    size_t order;  // contact index: of two contacts with one key (a hash collision) the first wins
    bool operator<(const Entry& o) const { return std::tie(key, order) < std::tie(o.key, o.order); }
  };
  std::vector<Entry> impulses_;
};

}  // namespace contactsim
