// The collision detector's kept manifolds (manifold reuse,
// service/collision/manifold_cache.h) in a snapshot. With reuse on, whether
// a touching pair gets its kept points or a fresh separating-axis test and
// clip changes its contacts, so a restored run continues bit for bit only
// with the same manifolds; the detector's other state (the separating-axis
// cache, the broadphase's order) changes only speed and is not saved.
#pragma once

#include <vector>

#include "service/collision/manifold_cache.h"
#include "service/physics/status.h"
#include "service/proto/snapshot.pb.h"

namespace contactsim {

void SaveManifolds(const ManifoldCache& cache, proto::Snapshot* out);

// Reads the kept manifolds of `snap` into *out, checking every field; on
// error the message names the pair and the field, and *out is unchanged.
// A snapshot without them (older, or written with reuse off) gives none:
// reuse starts cold.
Status ReadManifolds(const proto::Snapshot& snap, std::vector<CachedManifold>* out);

}  // namespace contactsim
