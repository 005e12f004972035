#include "bipednav/tracking/tracker.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <utility>

#include "bipednav/tracking/association.hpp"
#include "bipednav/tracking/hungarian.hpp"

namespace bipednav::tracking {

double major_sigma(const Eigen::Matrix2d& C) {
  const double m = 0.5 * (C(0, 0) + C(1, 1)), d = 0.5 * (C(0, 0) - C(1, 1));
  const double largest = m + std::sqrt(d * d + C(0, 1) * C(0, 1));
  return std::sqrt(largest < 0.0 ? 0.0 : largest);  // NaN stays NaN
}

namespace {

// The unit directions 0, 22.5, .., 157.5 degrees.
const std::array<Eigen::Vector2d, 8>& spread_directions() {
  static const std::array<Eigen::Vector2d, 8> u = [] {
    std::array<Eigen::Vector2d, 8> out;
    for (std::size_t k = 0; k < out.size(); ++k) {
      const double a = static_cast<double>(k) * M_PI / 8.0;
      out[k] = {std::cos(a), std::sin(a)};
    }
    return out;
  }();
  return u;
}

}  // namespace

void Spread::add(const Eigen::Vector2d& p) {
  const auto& u = spread_directions();
  for (std::size_t k = 0; k < u.size(); ++k) {
    const double s = u[k].dot(p);
    lo_[k] = empty_ ? s : std::min(lo_[k], s);
    hi_[k] = empty_ ? s : std::max(hi_[k], s);
  }
  empty_ = false;
}

double Spread::diameter() const {
  double d = 0.0;
  for (std::size_t k = 0; k < lo_.size(); ++k) d = std::max(d, hi_[k] - lo_[k]);
  return d;
}

const char* motion_test_name(MotionTest m) {
  static constexpr std::array<const char*, 6> kNames{"proven",       "moving", "flat",
                                                     "short_window", "still",  "origin_occupied"};
  return kNames.at(static_cast<std::size_t>(m));
}

MultiObjectTracker::MultiObjectTracker(TrackerParams params, SensorVisibility visibility)
    : params_((params.validate(), std::move(params))),
      visibility_(std::move(visibility)),
      persistent_(params_.cluster_cell_m, params_.persistent_span_s, params_.persistent_gap_s,
                  params_.persistent_memory_s) {}

void MultiObjectTracker::set_static_map(const mapping::Costmap2D& occupancy, double stamp_s) {
  static_.update(occupancy, stamp_s, params_.static_gap_s);
}

void MultiObjectTracker::clear() {
  tracks_.clear();
  detections_.clear();
  static_.clear();
  persistent_.clear();
  last_stamp_s_ = -1e300;
}

void MultiObjectTracker::update(const DetectionInput& in) {
  if (!std::isfinite(in.stamp_s) || in.stamp_s <= last_stamp_s_ || !in.T_map_base.is_finite()) return;
  const std::vector<Eigen::Vector3d> points = points_in_range(in, params_);
  // The proven movers where they are predicted now: their points are no static evidence, and no
  // static map explains them.
  std::vector<MoverCircle> movers;
  for (const auto& t : tracks_) {
    if (!t.confirmed() || !t.proven) continue;
    MoverCircle& c = movers.emplace_back();
    Eigen::Matrix2d P;
    t.filter.predict_position(in.stamp_s - t.stamp_s, c.center, P);
    c.radius_m = t.radius_m + params_.mover_margin_m;
  }
  persistent_.add(points, in.stamp_s, [&](const Eigen::Vector3d& q) {
    return std::any_of(movers.begin(), movers.end(), [&](const MoverCircle& c) { return c.contains(q.head<2>()); });
  });
  const std::vector<Eigen::Vector3d> unexplained = unexplained_points(points, static_, &persistent_, movers, params_);
  cycle_points_ = &points;
  update_detections(detect_objects(unexplained, in.T_map_base.position(), params_, !in.heights_m.empty()), in.stamp_s,
                    in.T_map_base);
  cycle_points_ = nullptr;
}

void MultiObjectTracker::update_detections(const std::vector<Detection>& detections, double stamp_s,
                                           const Pose2& T_map_base) {
  if (!std::isfinite(stamp_s) || stamp_s <= last_stamp_s_ || !T_map_base.is_finite()) return;
  const double cycle_dt_s = last_stamp_s_ > -1e299 ? stamp_s - last_stamp_s_ : 0.0;
  last_stamp_s_ = stamp_s;
  detections_.clear();
  for (const auto& d : detections)
    if (d.finite()) detections_.push_back(d);
  std::vector<const TrackFilter*> filters;
  for (auto& t : tracks_) {
    t.filter.predict(stamp_s - t.stamp_s);
    t.stamp_s = stamp_s;
    filters.push_back(&t.filter);
  }
  std::vector<int> match = associate(filters, detections_, params_.gate_chi2);
  reacquire_movers(match, stamp_s);
  std::vector<char> used(detections_.size(), 0);
  std::vector<Track> kept;
  kept.reserve(tracks_.size() + detections_.size());
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    Track& t = tracks_[i];
    ++t.updates;
    t.hit_history <<= 1;
    if (match[i] >= 0) {
      used[static_cast<std::size_t>(match[i])] = 1;
      update_track(t, detections_[static_cast<std::size_t>(match[i])], stamp_s);
    } else {
      t.filter.miss();
      if (!keep_unseen(t, cycle_dt_s, T_map_base)) continue;
    }
    kept.push_back(std::move(t));
  }
  tracks_ = std::move(kept);
  for (std::size_t j = 0; j < detections_.size(); ++j)
    if (!used[j]) start_track(detections_[j], stamp_s);
}

void MultiObjectTracker::reacquire_movers(std::vector<int>& match, double stamp_s) {
  std::vector<char> taken(detections_.size(), 0);
  for (int j : match)
    if (j >= 0) taken[static_cast<std::size_t>(j)] = 1;
  std::vector<std::size_t> lost;
  for (std::size_t i = 0; i < tracks_.size(); ++i)
    if (match[i] < 0 && tracks_[i].confirmed() && tracks_[i].mover && !tracks_[i].recent.empty()) lost.push_back(i);
  if (lost.empty()) return;
  Eigen::MatrixXd cost =
      Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(lost.size()), static_cast<Eigen::Index>(detections_.size()),
                                std::numeric_limits<double>::infinity());
  const double k = std::sqrt(params_.gate_chi2);
  for (std::size_t a = 0; a < lost.size(); ++a) {
    const Track& t = tracks_[lost[a]];
    const Eigen::Vector2d& last = t.recent.back().position;
    const double travelled = t.velocity().norm() * (stamp_s - t.last_seen_s);
    for (std::size_t j = 0; j < detections_.size(); ++j) {
      if (taken[j]) continue;
      const Detection& d = detections_[j];
      const double dist = (d.position - last).norm();
      if (dist <= travelled + k * major_sigma(d.covariance + t.position_covariance()))
        cost(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(j)) = dist;
    }
  }
  const std::vector<int> pick = solve_assignment(cost);
  for (std::size_t a = 0; a < lost.size(); ++a) {
    if (pick[a] < 0) continue;
    Track& t = tracks_[lost[a]];
    const Detection& d = detections_[static_cast<std::size_t>(pick[a])];
    t.filter = TrackFilter(d.position, d.covariance, params_);
    t.recent.clear();
    match[lost[a]] = pick[a];
  }
}

void MultiObjectTracker::update_track(Track& t, const Detection& d, double stamp_s) const {
  t.filter.update(d.position, d.covariance);
  t.spread.add(t.position());
  ++t.hits;
  t.hit_history |= 1u;
  const double dt = stamp_s - t.last_seen_s;
  const double decayed = params_.radius_memory_s > 0.0 ? t.radius_m * std::exp(-dt / params_.radius_memory_s) : 0.0;
  t.radius_m = std::max(d.radius_m, decayed);
  t.top_m = std::max(t.top_m, d.top_m);
  t.height_span_m = std::max(t.height_span_m, d.height_span_m);
  t.last_seen_s = stamp_s;
  t.unseen_in_view_s = 0.0;
  t.recent.push_back({stamp_s, d.position, d.surface});
  std::erase_if(t.recent, [&](const TimedPosition& s) { return s.t_s < stamp_s - params_.mover_window_s - 1e-9; });
  if (t.status == TrackStatus::kCoasting) t.status = TrackStatus::kConfirmed;
  if (t.status == TrackStatus::kTentative && t.updates <= params_.confirm_window &&
      std::popcount(t.hit_history) >= params_.confirm_hits) {
    t.status = TrackStatus::kConfirmed;
    t.confirmed_s = stamp_s;
  }
  if (t.confirmed()) classify_motion(t);
}

void MultiObjectTracker::classify_motion(Track& t) const {
  t.mover = t.proven;
  t.motion_test = t.proven ? MotionTest::kProven : motion_evidence(t);
  if (t.motion_test != MotionTest::kMoving) return;
  t.mover = true;
  t.proven = t.spread.diameter() >= params_.mover_proof_m;
}

MotionTest MultiObjectTracker::motion_evidence(const Track& t) const {
  // A flat patch (the top of a box lower than the sensors, swept by a LiDAR ring) is no mover.
  if (t.height_span_m >= 0.0 && t.height_span_m < params_.mover_min_height_span_m) return MotionTest::kFlat;
  const WindowVelocity w = regression_velocity(t.recent);
  if (w.samples < 3 || w.span_s < (t.born_in_free ? params_.free_birth_min_span_s : params_.mover_min_span_s))
    return MotionTest::kShortWindow;
  if (!w.moving(params_.mover_speed_mps, params_.mover_significance)) return MotionTest::kStill;
  return vacated(t) ? MotionTest::kMoving : MotionTest::kOriginOccupied;
}

bool MultiObjectTracker::vacated(const Track& t) const {
  if (cycle_points_ == nullptr || t.recent.empty()) return true;
  const Eigen::Vector2d& was = t.recent.front().surface;
  const double r2 = params_.mover_vacated_radius_m * params_.mover_vacated_radius_m;
  int left = 0;
  for (const auto& p : *cycle_points_)
    if ((p.head<2>() - was).squaredNorm() <= r2 && ++left >= params_.min_cluster_points) return false;
  return true;
}

bool MultiObjectTracker::in_view(const Track& t, const Pose2& robot) const {
  const Eigen::Vector2d p = t.position();
  if ((p - robot.position()).norm() > params_.max_range_m) return false;
  return visibility_.empty() || visibility_.sees(robot, p, t.top_m);
}

bool MultiObjectTracker::keep_unseen(Track& t, double dt_s, const Pose2& robot) const {
  if (t.status == TrackStatus::kTentative) {
    // Deleted once confirm_hits can no longer be reached within confirm_window updates.
    const int left = params_.confirm_window - t.updates;
    return left > 0 && std::popcount(t.hit_history) + left >= params_.confirm_hits;
  }
  t.status = TrackStatus::kCoasting;
  if (in_view(t, robot)) t.unseen_in_view_s += dt_s;
  const double std_m = major_sigma(t.position_covariance());
  const double max_unseen_s = t.mover ? params_.max_unseen_out_of_view_s : params_.max_unseen_in_view_s;
  return t.unseen_in_view_s <= params_.max_unseen_in_view_s && t.stamp_s - t.last_seen_s <= max_unseen_s &&
         std_m <= params_.max_position_std_m;
}

void MultiObjectTracker::start_track(const Detection& d, double stamp_s) {
  Track t{.id = next_id_++, .filter = TrackFilter(d.position, d.covariance, params_)};
  t.radius_m = d.radius_m;
  t.top_m = d.top_m;
  t.height_span_m = d.height_span_m;
  t.spread.add(t.filter.state().head<2>());
  t.recent.push_back({stamp_s, d.position, d.surface});
  t.born_s = t.last_seen_s = t.stamp_s = stamp_s;
  t.born_in_free = static_.was_free(d.position, params_.free_birth_free_s, params_.free_birth_recent_s);
  t.updates = t.hits = 1;
  t.hit_history = 1u;
  if (params_.confirm_hits <= 1) {
    t.status = TrackStatus::kConfirmed;
    t.confirmed_s = stamp_s;
  }
  tracks_.push_back(std::move(t));
}

std::vector<TrackPrediction> MultiObjectTracker::predictions() const {
  std::vector<TrackPrediction> out;
  const int steps = static_cast<int>(std::floor(params_.horizon_s / params_.prediction_step_s + 1e-9));
  for (const auto& t : tracks_) {
    if (!t.confirmed() || !t.mover) continue;
    TrackPrediction& p = out.emplace_back();
    p.id = t.id;
    p.radius_m = t.radius_m;
    p.velocity = t.velocity();
    p.states.resize(static_cast<std::size_t>(steps) + 1);
    for (int k = 0; k <= steps; ++k) {
      PredictedState& s = p.states[static_cast<std::size_t>(k)];
      const double dt = k * params_.prediction_step_s;
      s.t_s = t.stamp_s + dt;
      t.filter.predict_position(dt, s.position, s.covariance);
    }
  }
  return out;
}

}  // namespace bipednav::tracking
