#include "service/contact/lcp/row_schedule.h"

#include <algorithm>

namespace contactsim {

void RowSchedule::Order(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                        std::vector<int>* order) {
  runs_.clear();
  for (int k = 0; k < static_cast<int>(rows.size()); ++k) {
    const ConstraintRow& r = rows[k];
    if (k > 0 && r.a == rows[k - 1].a && r.b == rows[k - 1].b) {
      ++runs_.back().count;
    } else {
      runs_.push_back({k, 1, 0});
    }
  }

  body_level_.assign(bodies.size(), -1);
  auto moves = [&](int body) { return body >= 0 && bodies[body].inv_mass > 0.0; };
  int levels = 0;
  for (Run& run : runs_) {
    const int a = rows[run.first].a, b = rows[run.first].b;
    int level = 0;
    if (moves(a)) level = std::max(level, body_level_[a] + 1);
    if (moves(b)) level = std::max(level, body_level_[b] + 1);
    if (moves(a)) body_level_[a] = level;
    if (moves(b)) body_level_[b] = level;
    run.level = level;
    levels = std::max(levels, level + 1);
  }

  // counting sort of the runs by level, stable
  level_start_.assign(levels + 1, 0);
  for (const Run& run : runs_) ++level_start_[run.level + 1];
  for (int l = 0; l < levels; ++l) level_start_[l + 1] += level_start_[l];
  cursor_.assign(level_start_.begin(), level_start_.end() - 1);
  by_level_.resize(runs_.size());
  for (int i = 0; i < static_cast<int>(runs_.size()); ++i) by_level_[cursor_[runs_[i].level]++] = i;

  order->clear();
  for (int l = 0; l < levels; ++l) {
    const int begin = level_start_[l], end = level_start_[l + 1];
    int longest = 0;
    for (int i = begin; i < end; ++i) longest = std::max(longest, runs_[by_level_[i]].count);
    for (int s = 0; s < longest; ++s) {
      for (int i = begin; i < end; ++i) {
        const Run& run = runs_[by_level_[i]];
        if (s < run.count) order->push_back(run.first + s);
      }
    }
  }
}

}  // namespace contactsim
