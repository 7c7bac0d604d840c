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

void RowSchedule::Interleave(int begin, int end, std::vector<int>* order) const {
  int longest = 0;
  for (int i = begin; i < end; ++i) longest = std::max(longest, sorted_[i].count);
  for (int s = 0; s < longest; ++s) {
    for (int i = begin; i < end; ++i) {
      if (s < sorted_[i].count) order->push_back(sorted_[i].first + s);
    }
  }
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
                         BlockColours* colours) {
  const int world = static_cast<int>(bodies.size());
  roles_.resize(bodies.size() + 1);
  for (size_t i = 0; i < bodies.size(); ++i) {
    roles_[i] = bodies[i].inv_mass > 0.0 ? ColourRole::kColoured : ColourRole::kFixed;
  }
  roles_[world] = ColourRole::kFixed;
  ends_.resize(rows.size());
  for (size_t k = 0; k < rows.size(); ++k) {
    ends_[k] = {rows[k].a >= 0 ? rows[k].a : world, rows[k].b >= 0 ? rows[k].b : world};
    if (static_cast<int>(k) < first_ordered) continue;
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
  ColourAnew(rows, bodies, order, group_rows, colours);
  last_ends_ = ends_;
  last_roles_ = roles_;
  last_order_ = *order;
  last_group_rows_ = *group_rows;
  last_colours_ = *colours;
}

void RowSchedule::ColourAnew(const std::vector<ConstraintRow>& rows, const std::vector<SolverBody>& bodies,
                             std::vector<int>* order, std::vector<int>* group_rows, BlockColours* colours) {
  FindRuns(rows);
  coloured_.resize(runs_.size());
  for (size_t i = 0; i < runs_.size(); ++i) coloured_[i] = NormalBlock{runs_[i].first, runs_[i].count};
  const BlockColours by_run = ColourBlocks(ends_, roles_, &coloured_);
  sorted_.resize(coloured_.size());
  for (size_t i = 0; i < coloured_.size(); ++i) sorted_[i] = {coloured_[i].first, coloured_[i].count, 0};

  // groups of kRunsPerGroup within each colour; the overflow one group
  order->clear();
  group_rows->assign(1, 0);
  colours->starts.clear();
  for (int c = 0; c < by_run.colours(); ++c) {
    colours->starts.push_back(static_cast<int>(group_rows->size()) - 1);
    for (int i = by_run.starts[c]; i < by_run.starts[c + 1]; i += kRunsPerGroup) {
      Interleave(i, std::min(i + kRunsPerGroup, by_run.starts[c + 1]), order);
      group_rows->push_back(static_cast<int>(order->size()));
    }
  }
  colours->starts.push_back(static_cast<int>(group_rows->size()) - 1);
  const int overflow = by_run.starts.back();
  if (overflow == static_cast<int>(sorted_.size())) return;
  body_level_.resize(bodies.size());
  AppendByLevel(rows, bodies, overflow, static_cast<int>(sorted_.size()), order);
  group_rows->push_back(static_cast<int>(order->size()));
}

}  // namespace contactsim
