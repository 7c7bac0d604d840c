#include "service/contact/lcp/row_schedule.h"

#include <algorithm>

namespace contactsim {

void RowSchedule::FindRuns(const std::vector<ConstraintRow>& rows) {
  runs_.clear();
  for (int k = 0; k < static_cast<int>(rows.size()); ++k) {
    const ConstraintRow& r = rows[k];
    if (k > 0 && r.a == rows[k - 1].a && r.b == rows[k - 1].b) {
      ++runs_.back().count;
    } else {
      runs_.push_back({k, 1, 0});
    }
  }
}

int* RowSchedule::Interleave(int begin, int end, int* out) const {
  int longest = 0;
  for (int i = begin; i < end; ++i) longest = std::max(longest, sorted_[i].count);
  for (int s = 0; s < longest; ++s) {
    for (int i = begin; i < end; ++i) {
      if (s < sorted_[i].count) *out++ = sorted_[i].first + s;
    }
  }
  return out;
}

void RowSchedule::Interleave(int begin, int end, std::vector<int>* order) const {
  const size_t at = order->size();
  int rows = 0;
  for (int i = begin; i < end; ++i) rows += sorted_[i].count;
  order->resize(at + rows);
  Interleave(begin, end, order->data() + at);
}

void RowSchedule::AppendByLevel(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                                int begin, int end, std::vector<int>* order) {
  auto moves = [&](int body) { return body >= 0 && bodies[body].inv_mass > 0.0; };
  for (int i = begin; i < end; ++i) {
    for (int body : {rows[sorted_[i].first].a, rows[sorted_[i].first].b}) {
      if (moves(body)) body_level_[body] = -1;
    }
  }
  int levels = 0;
  for (int i = begin; i < end; ++i) {
    Run& run = sorted_[i];
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
  level_start_.assign(levels + 1, begin);
  for (int i = begin; i < end; ++i) ++level_start_[sorted_[i].level + 1];
  for (int l = 0; l < levels; ++l) level_start_[l + 1] += level_start_[l] - begin;
  cursor_.assign(level_start_.begin(), level_start_.end() - 1);
  level_sorted_.assign(sorted_.begin() + begin, sorted_.begin() + end);
  for (const Run& run : level_sorted_) sorted_[cursor_[run.level]++] = run;
  for (int l = 0; l < levels; ++l) Interleave(level_start_[l], level_start_[l + 1], order);
}

void RowSchedule::Order(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                        std::vector<int>* order) {
  FindRuns(rows);
  sorted_ = runs_;
  body_level_.resize(bodies.size());
  order->clear();
  AppendByLevel(rows, bodies, 0, static_cast<int>(sorted_.size()), order);
}

void RowSchedule::Colour(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                         int first_ordered, std::vector<int>* order, std::vector<int>* group_rows,
                         BlockColours* colours, ParallelRunner* runner) {
  const int world = static_cast<int>(bodies.size());
  roles_.resize(bodies.size() + 1);
  for (size_t i = 0; i < bodies.size(); ++i) {
    roles_[i] = bodies[i].inv_mass > 0.0 ? ColourRole::kColoured : ColourRole::kFixed;
  }
  roles_[world] = ColourRole::kFixed;
  const int n = static_cast<int>(rows.size());
  ends_.resize(n);
  const auto ends = [&](int begin, int end, int /*worker*/) {
    for (int k = begin; k < end; ++k) {
      ends_[k] = {rows[k].a >= 0 ? rows[k].a : world, rows[k].b >= 0 ? rows[k].b : world};
    }
  };
  if (runner != nullptr) {
    runner->For(n, kEndsGrain, ends);
  } else {
    ends(0, n, 0);
  }
  for (int k = std::max(first_ordered, 0); k < n; ++k) {
    for (int body : {ends_[k].a, ends_[k].b}) {
      if (roles_[body] == ColourRole::kColoured) roles_[body] = ColourRole::kSerial;
    }
  }
  // the rows' bodies and the bodies' roles decide the order: the same as
  // the last call's, the same order (the contact graph of a resting scene
  // seldom changes from step to step)
  if (ends_ == last_ends_ && roles_ == last_roles_) {
    *order = last_order_;
    *group_rows = last_group_rows_;
    *colours = last_colours_;
    return;
  }
  ColourAnew(rows, bodies, order, group_rows, colours, runner);
  last_ends_ = ends_;
  last_roles_ = roles_;
  last_order_ = *order;
  last_group_rows_ = *group_rows;
  last_colours_ = *colours;
}

void RowSchedule::ColourAnew(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                             std::vector<int>* order, std::vector<int>* group_rows, BlockColours* colours,
                             ParallelRunner* runner) {
  FindRuns(rows);
  coloured_.resize(runs_.size());
  for (size_t i = 0; i < runs_.size(); ++i) coloured_[i] = NormalBlock{runs_[i].first, runs_[i].count};
  const BlockColours by_run = ColourBlocks(ends_, roles_, &coloured_);
  sorted_.resize(coloured_.size());
  for (size_t i = 0; i < coloured_.size(); ++i) sorted_[i] = {coloured_[i].first, coloured_[i].count, 0};

  // groups of kRunsPerGroup within each colour, each group's rows counted
  // here and interleaved into its own place on the threads; the overflow
  // one group
  group_rows->assign(1, 0);
  group_first_run_.clear();
  colours->starts.clear();
  for (int c = 0; c < by_run.colours(); ++c) {
    colours->starts.push_back(static_cast<int>(group_rows->size()) - 1);
    for (int i = by_run.starts[c]; i < by_run.starts[c + 1]; i += kRunsPerGroup) {
      int count = 0;
      for (int r = i; r < std::min(i + kRunsPerGroup, by_run.starts[c + 1]); ++r) count += sorted_[r].count;
      group_first_run_.push_back(i);
      group_rows->push_back(group_rows->back() + count);
    }
  }
  const int groups = static_cast<int>(group_first_run_.size());
  group_first_run_.push_back(by_run.starts.back());
  order->resize(group_rows->back());
  const auto fill = [&](int begin, int end, int /*worker*/) {
    for (int g = begin; g < end; ++g) {
      // a group ends at its colour's end or kRunsPerGroup runs on
      const int last = std::min(group_first_run_[g] + kRunsPerGroup, group_first_run_[g + 1]);
      Interleave(group_first_run_[g], last, order->data() + (*group_rows)[g]);
    }
  };
  if (runner != nullptr) {
    runner->For(groups, kFillGrain, fill);
  } else {
    fill(0, groups, 0);
  }
  colours->starts.push_back(static_cast<int>(group_rows->size()) - 1);
  const int overflow = by_run.starts.back();
  if (overflow == static_cast<int>(sorted_.size())) return;
  body_level_.resize(bodies.size());
  AppendByLevel(rows, bodies, overflow, static_cast<int>(sorted_.size()), order);
  group_rows->push_back(static_cast<int>(order->size()));
}

}  // namespace contactsim
