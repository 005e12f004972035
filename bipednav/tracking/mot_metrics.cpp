#include "bipednav/tracking/mot_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bipednav/tracking/hungarian.hpp"

namespace bipednav::tracking {

double MotSummary::mota() const {
  if (truths == 0) return 1.0;
  return 1.0 - static_cast<double>(misses + false_positives + id_switches) / static_cast<double>(truths);
}

MotSummary pool(const std::vector<MotSummary>& parts) {
  MotSummary s;
  double position_se = 0.0, velocity_se = 0.0, steady_se = 0.0, pickup_sum = 0.0;
  for (const auto& p : parts) {
    s.truths += p.truths, s.matches += p.matches, s.misses += p.misses, s.matches_turning += p.matches_turning;
    s.false_positives += p.false_positives, s.id_switches += p.id_switches;
    s.appearances += p.appearances, s.appearances_picked_up += p.appearances_picked_up;
    const auto m = static_cast<double>(p.matches);
    position_se += p.position_rmse_m * p.position_rmse_m * m;
    velocity_se += p.velocity_rmse_mps * p.velocity_rmse_mps * m;
    steady_se +=
        p.velocity_rmse_steady_mps * p.velocity_rmse_steady_mps * static_cast<double>(p.matches - p.matches_turning);
    pickup_sum += p.mean_pickup_s * static_cast<double>(p.appearances_picked_up);
    s.max_pickup_s = std::max(s.max_pickup_s, p.max_pickup_s);
  }
  if (s.matches > 0) {
    s.position_rmse_m = std::sqrt(position_se / static_cast<double>(s.matches));
    s.velocity_rmse_mps = std::sqrt(velocity_se / static_cast<double>(s.matches));
  }
  if (s.matches > s.matches_turning)
    s.velocity_rmse_steady_mps = std::sqrt(steady_se / static_cast<double>(s.matches - s.matches_turning));
  if (s.appearances_picked_up > 0) s.mean_pickup_s = pickup_sum / static_cast<double>(s.appearances_picked_up);
  return s;
}

ClearMot::ClearMot(double match_distance_m, double appearance_gap_s)
    : match_distance_m_(match_distance_m), appearance_gap_s_(appearance_gap_s) {}

std::vector<int> ClearMot::match(const std::vector<MotObject>& objects, const std::vector<MotObject>& hypotheses,
                                 const std::vector<char>& used) const {
  Eigen::MatrixXd cost =
      Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(objects.size()), static_cast<Eigen::Index>(hypotheses.size()),
                                std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    for (std::size_t j = 0; j < hypotheses.size(); ++j) {
      const double d = (objects[i].position - hypotheses[j].position).norm();
      if (!used[j] && d <= match_distance_m_) cost(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = d;
    }
  }
  return solve_assignment(cost);
}

void ClearMot::count_pickup(int truth_id, double t_s, bool matched) {
  auto it = appearance_.find(truth_id);
  if (it == appearance_.end() || t_s - it->second.last_counted_s >= appearance_gap_s_) {
    it = appearance_.insert_or_assign(truth_id, Appearance{t_s, t_s, false}).first;
    ++sum_.appearances;
  }
  Appearance& a = it->second;
  a.last_counted_s = t_s;
  if (!matched || a.picked_up) return;
  a.picked_up = true;
  ++sum_.appearances_picked_up;
  pickup_sum_s_ += t_s - a.start_s;
  sum_.max_pickup_s = std::max(sum_.max_pickup_s, t_s - a.start_s);
}

void ClearMot::add_frame(double t_s, const std::vector<MotObject>& truths, const std::vector<MotObject>& ignored,
                         const std::vector<MotObject>& hypotheses, const std::vector<char>& in_region) {
  std::vector<char> used(hypotheses.size(), 0);
  std::vector<int> hyp_of(truths.size(), -1);
  // Correspondences kept from earlier frames.
  for (std::size_t i = 0; i < truths.size(); ++i) {
    const auto last = last_match_.find(truths[i].id);
    if (last == last_match_.end()) continue;
    for (std::size_t j = 0; j < hypotheses.size(); ++j) {
      if (used[j] || hypotheses[j].id != last->second) continue;
      if ((hypotheses[j].position - truths[i].position).norm() <= match_distance_m_)
        hyp_of[i] = static_cast<int>(j), used[j] = 1;
      break;
    }
  }
  std::vector<MotObject> open;
  std::vector<std::size_t> open_index;
  for (std::size_t i = 0; i < truths.size(); ++i)
    if (hyp_of[i] < 0) open.push_back(truths[i]), open_index.push_back(i);
  const std::vector<int> fresh = match(open, hypotheses, used);
  for (std::size_t k = 0; k < open.size(); ++k) {
    if (fresh[k] < 0) continue;
    hyp_of[open_index[k]] = fresh[k];
    used[static_cast<std::size_t>(fresh[k])] = 1;
  }
  for (std::size_t i = 0; i < truths.size(); ++i) {
    ++sum_.truths;
    count_pickup(truths[i].id, t_s, hyp_of[i] >= 0);
    if (hyp_of[i] < 0) {
      ++sum_.misses;
      continue;
    }
    const MotObject& h = hypotheses[static_cast<std::size_t>(hyp_of[i])];
    ++sum_.matches;
    position_se_ += (h.position - truths[i].position).squaredNorm();
    const double v2 = (h.velocity - truths[i].velocity).squaredNorm();
    velocity_se_ += v2;
    if (truths[i].turning)
      ++sum_.matches_turning;
    else
      steady_se_ += v2;
    const auto last = last_match_.find(truths[i].id);
    if (last != last_match_.end() && last->second != h.id) ++sum_.id_switches;
    last_match_[truths[i].id] = h.id;
    last_truth_[h.id] = truths[i].id;
  }
  // Hypotheses left on an object that does not count are neither matches nor false positives.
  const std::vector<int> on_ignored = match(ignored, hypotheses, used);
  for (const int j : on_ignored)
    if (j >= 0) used[static_cast<std::size_t>(j)] = 1;
  for (std::size_t j = 0; j < hypotheses.size(); ++j) {
    const auto last = last_truth_.find(hypotheses[j].id);
    if (used[j] || last == last_truth_.end()) continue;
    const bool out_of_view =
        std::any_of(ignored.begin(), ignored.end(), [&](const MotObject& o) { return o.id == last->second; });
    if (out_of_view) used[j] = 1;
  }
  for (std::size_t j = 0; j < hypotheses.size(); ++j)
    if (!used[j] && (in_region.empty() || in_region[j])) ++sum_.false_positives;
}

MotSummary ClearMot::summary() const {
  MotSummary s = sum_;
  if (s.matches > 0) {
    s.position_rmse_m = std::sqrt(position_se_ / static_cast<double>(s.matches));
    s.velocity_rmse_mps = std::sqrt(velocity_se_ / static_cast<double>(s.matches));
  }
  if (s.matches > s.matches_turning)
    s.velocity_rmse_steady_mps = std::sqrt(steady_se_ / static_cast<double>(s.matches - s.matches_turning));
  if (s.appearances_picked_up > 0) s.mean_pickup_s = pickup_sum_s_ / static_cast<double>(s.appearances_picked_up);
  return s;
}

}  // namespace bipednav::tracking
