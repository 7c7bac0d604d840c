#include "service/collision/sweep_and_prune.h"

#include <algorithm>
#include <functional>

#include "service/collision/broadphase_check.h"
#include "service/collision/parallel_sort.h"
#include "service/collision/region_probe.h"

namespace contactsim {
namespace {

// boxes a thread sweeps at a time (a box meets a few to a few dozen others)
constexpr int kSweepGrain = 128;
// boxes a thread gathers, and bodies whose partners it sorts, at a time
// (tens of nanoseconds each)
constexpr int kGatherGrain = 512;

// Boxes wider than this (m) are unbounded on that axis: planes get +-1e15
// (aabb.cpp). They would swamp the spread of the others, so they do not vote
// for the sweep axis.
constexpr double kUnboundedExtent = 1e12;
// Switch axis only when another one spreads the centres this many times more
// (variance ratio); the hysteresis keeps a scene near the tie from re-sorting
// every step.
constexpr double kAxisSwitchRatio = 2.0;

bool Before(double min_a, int index_a, double min_b, int index_b) {
  return min_a < min_b || (min_a == min_b && index_a < index_b);
}

// The sums CentreVariance needs over some boxes.
struct CentreSums {
  Vec3 sum = Vec3::Zero(), sum_sq = Vec3::Zero(), count = Vec3::Zero();
};

// Variance of the box centres along each axis, bounded boxes only. The
// sums are taken over runs of kGatherGrain boxes (on the threads when
// `split` spreads them) and added in run order, so the axis does not depend
// on the thread count (nor could the pairs: they are sorted by body).
Vec3 CentreVariance(const std::vector<Aabb>& boxes,
                    const std::function<void(int, int, const ParallelRunner::RangeFn&)>& split) {
  const int n = static_cast<int>(boxes.size());
  std::vector<CentreSums> runs((n + kGatherGrain - 1) / kGatherGrain);
  split(n, kGatherGrain, [&](int lo, int hi, int /*worker*/) {
    for (int r = lo; r < hi; r += kGatherGrain) {
      CentreSums& s = runs[r / kGatherGrain];
      for (int i = r; i < std::min(r + kGatherGrain, hi); ++i) {
        for (int k = 0; k < 3; ++k) {
          if (boxes[i].max[k] - boxes[i].min[k] > kUnboundedExtent) continue;
          const double c = 0.5 * (boxes[i].min[k] + boxes[i].max[k]);
          s.sum[k] += c;
          s.sum_sq[k] += c * c;
          s.count[k] += 1.0;
        }
      }
    }
  });
  Vec3 sum = Vec3::Zero(), sum_sq = Vec3::Zero(), count = Vec3::Zero();
  for (const CentreSums& s : runs) {
    sum += s.sum;
    sum_sq += s.sum_sq;
    count += s.count;
  }
  Vec3 variance = Vec3::Zero();
  for (int k = 0; k < 3; ++k) {
    if (count[k] > 0) variance[k] = sum_sq[k] / count[k] - (sum[k] / count[k]) * (sum[k] / count[k]);
  }
  return variance;
}

}  // namespace

int SweepAndPrune::ChooseAxis(const std::vector<Aabb>& boxes) const {
  const Vec3 variance = CentreVariance(
      boxes, [this](int n, int grain, const ParallelRunner::RangeFn& body) { Split(n, grain, body); });
  int best = 0;
  for (int k = 1; k < 3; ++k) {
    if (variance[k] > variance[best]) best = k;
  }
  if (!entries_.empty() && variance[best] <= kAxisSwitchRatio * variance[axis_]) return axis_;
  return best;
}

void SweepAndPrune::Rebuild(const std::vector<Aabb>& boxes) {
  const int n = static_cast<int>(boxes.size());
  entries_.resize(n);
  for (int i = 0; i < n; ++i) entries_[i] = {boxes[i].min[axis_], i};
  std::sort(entries_.begin(), entries_.end(),
            [](const Entry& a, const Entry& b) { return Before(a.min, a.index, b.min, b.index); });
}

// Insertion sort of the last step's order under the new bounds, each entry
// moving left past the entries that now start after it: by runs of
// kGatherGrain entries on the threads, then merged (parallel_sort.h). The
// order (min, index) is total, so the result is one insertion sort's bit
// for bit, and the inversions counted are its shifts.
void SweepAndPrune::Repair(const std::vector<Aabb>& boxes) {
  Split(static_cast<int>(entries_.size()), kGatherGrain, [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) entries_[k].min = boxes[entries_[k].index].min[axis_];
  });
  ParallelSort(
      &entries_, &entry_scratch_, runner_, kGatherGrain,
      [](const Entry& a, const Entry& b) { return Before(a.min, a.index, b.min, b.index); }, &last_swaps_);
}

void SweepAndPrune::Gather(const std::vector<Aabb>& boxes, const std::vector<bool>& movable) {
  const int n = static_cast<int>(entries_.size());
  const int u = (axis_ + 1) % 3, v = (axis_ + 2) % 3;
  max_.resize(n);
  sweep_.resize(n);
  movable_.resize(n);
  Split(n, kGatherGrain, [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) {
      const Aabb& box = boxes[entries_[k].index];
      max_[k] = box.max[axis_];
      sweep_[k] = {box.min[axis_], box.min[u], box.max[u], box.min[v], box.max[v]};
      movable_[k] = movable[entries_[k].index] ? 1 : 0;
    }
  });
}

void SweepAndPrune::Split(int n, int grain, const ParallelRunner::RangeFn& body) const {
  if (runner_ != nullptr) {
    runner_->For(n, grain, body);
  } else {
    body(0, n, 0);
  }
}

void SweepAndPrune::FindPairs(const std::vector<Aabb>& boxes, const std::vector<bool>& movable,
                              std::vector<BodyPair>* pairs) {
  CheckBroadphaseInput(boxes, movable);
  pairs->clear();
  const int n = static_cast<int>(boxes.size());
  if (static_cast<int>(entries_.size()) != n) entries_.clear();
  const int axis = ChooseAxis(boxes);
  last_rebuilt_ = entries_.empty() || axis != axis_;
  if (last_rebuilt_) {
    axis_ = axis;
    last_swaps_ = 0;
    Rebuild(boxes);
  } else {
    Repair(boxes);
  }

  Gather(boxes, movable);

  // sweep: a box overlaps on the axis exactly the boxes that start in
  // [min, max]; each box's run is independent, so boxes are shared out in
  // chunks and each thread collects its own pairs (their order is undone by
  // the sort below)
  const int threads = runner_ != nullptr ? runner_->threads() : 1;
  worker_pairs_.resize(threads);
  for (std::vector<BodyPair>& w : worker_pairs_) w.clear();
  const auto sweep = [&](int begin, int end, int worker) { Sweep(begin, end, &worker_pairs_[worker]); };
  if (threads > 1) {
    runner_->For(n, kSweepGrain, sweep);
  } else {
    const ParallelRegionProbe probe(n > kSweepGrain);  // on the threads when there are more
    sweep(0, n, 0);
  }
  for (const std::vector<BodyPair>& w : worker_pairs_) pairs->insert(pairs->end(), w.begin(), w.end());
  SortPairsByBody(n, pairs);
}

void SweepAndPrune::Sweep(int begin, int end, std::vector<BodyPair>* pairs) const {
  const int n = static_cast<int>(entries_.size());
  for (int a = begin; a < end; ++a) {
    const double max_a = max_[a];
    const SweepBounds ca = sweep_[a];
    const uint8_t movable_a = movable_[a];
    for (int b = a + 1; b < n && sweep_[b].min <= max_a; ++b) {
      const SweepBounds& cb = sweep_[b];
      // the other two axes, the same closed-interval test as Aabb::Overlaps
      // (touching boxes pair as in the naive phase); bitwise &, not &&: each
      // comparison alone is a coin flip the branch predictor loses, while
      // their conjunction is almost always false
      const bool overlap = (cb.min_u <= ca.max_u) & (ca.min_u <= cb.max_u) & (cb.min_v <= ca.max_v) &
                           (ca.min_v <= cb.max_v) & ((movable_a | movable_[b]) != 0);
      if (!overlap) continue;
      const int i = entries_[a].index, j = entries_[b].index;
      pairs->emplace_back(std::min(i, j), std::max(i, j));
    }
  }
}

void SweepAndPrune::SortPairsByBody(int n, std::vector<BodyPair>* pairs) {
  // body order, not sweep order, so that both broadphases agree bit for bit:
  // a counting sort on the first body (O(n + pairs); std::sort took 5% of a
  // sphere_pile step), then each body's few partners in order
  first_counts_.assign(n + 1, 0);
  for (const BodyPair& p : *pairs) ++first_counts_[p.first + 1];
  for (int i = 0; i < n; ++i) first_counts_[i + 1] += first_counts_[i];
  sorted_.resize(pairs->size());
  for (const BodyPair& p : *pairs) sorted_[first_counts_[p.first]++] = p;
  // first_counts_[i] now ends body i's run, which starts at the end of i - 1's
  Split(n, kGatherGrain, [&](int first, int last, int /*worker*/) {
    for (int i = first; i < last; ++i) {
      std::sort(sorted_.begin() + (i == 0 ? 0 : first_counts_[i - 1]), sorted_.begin() + first_counts_[i]);
    }
  });
  pairs->swap(sorted_);
}

}  // namespace contactsim
