#include "bipednav/planning/local/moving_obstacles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include "bipednav/planning/local/plan_utils.hpp"

namespace bipednav::planning::local {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Constant-velocity Kalman prediction of one axis over dt (white-noise acceleration of std q).
void kf_predict(double& p, double& v, Eigen::Matrix2d& P, double dt, double q) {
  p += v * dt;
  Eigen::Matrix2d F;
  F << 1.0, dt, 0.0, 1.0;
  Eigen::Matrix2d Q;
  const double q2 = q * q;
  Q << 0.25 * dt * dt * dt * dt * q2, 0.5 * dt * dt * dt * q2, 0.5 * dt * dt * dt * q2, dt * dt * q2;
  P = F * P * F.transpose() + Q;
}

// Kalman update of one axis with a position measurement z of variance r2.
void kf_update(double& p, double& v, Eigen::Matrix2d& P, double z, double r2) {
  const double s = P(0, 0) + r2;
  const Eigen::Vector2d k = P.col(0) / s;
  const double innov = z - p;
  p += k(0) * innov;
  v += k(1) * innov;
  Eigen::Matrix2d I_KH = Eigen::Matrix2d::Identity();
  I_KH(0, 0) -= k(0);
  I_KH(1, 0) -= k(1);
  P = I_KH * P;
}

}  // namespace

Eigen::Vector2d TrackedObstacle::predict(double t_s) const {
  const double dt = t_s - recurrence_base_s;
  if (recurrence.size() >= 2 && dt >= 0.0) {
    const auto after = std::lower_bound(recurrence.begin(), recurrence.end(), dt,
                                        [](const PathSample& s, double t) { return s.t_s < t; });
    if (after == recurrence.end()) {  // beyond it: the velocity over its last (up to) five steps
      const PathSample &a = recurrence[recurrence.size() - std::min<std::size_t>(recurrence.size(), 6)],
                       &b = recurrence.back();
      return recurrence_base + b.position + (b.position - a.position) * ((dt - b.t_s) / (b.t_s - a.t_s));
    }
    if (after == recurrence.begin()) return recurrence_base + after->position;
    const PathSample& a = *(after - 1);
    const double f = (dt - a.t_s) / (after->t_s - a.t_s);
    return recurrence_base + a.position + f * (after->position - a.position);
  }
  return predict_constant_velocity(t_s);
}

MovingObstacleTracker::MovingObstacleTracker(MovingObstacleParams params) : params_(std::move(params)) {
  params_.validate();
}

void MovingObstacleTracker::clear() {
  tracks_.clear();
  lost_.clear();
  trails_.clear();
  last_stamp_s_ = -1e300;
}

void MovingObstacleTracker::update(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& robot,
                                   double stamp_s) {
  if (!params_.enabled || !std::isfinite(stamp_s) || !robot.allFinite()) return;
  update_blobs(cluster_blobs(points, robot, params_, {}, &blob_scratch_), stamp_s);
}

void MovingObstacleTracker::update(const std::vector<Eigen::Vector2d>& points, const std::vector<double>& heights,
                                   const Pose2& robot, double stamp_s) {
  if (!params_.enabled || !std::isfinite(stamp_s) || !robot.is_finite()) return;
  update_blobs(cluster_blobs(points, robot.position(), params_, heights, &blob_scratch_), stamp_s, robot);
}

namespace {

double position_sigma(const TrackedObstacle& t) { return std::sqrt(std::max(t.cov_x(0, 0), t.cov_y(0, 0))); }

// How much a coasting track's radius (and gate) grows: its position std beyond the one it had when
// last seen, bounded.
double coast_growth(const TrackedObstacle& t, double max_growth_m) {
  if (!t.coasting) return 0.0;
  return std::clamp(position_sigma(t) - t.seen_sigma_m, 0.0, max_growth_m);
}

// radius_floor: the distance from p to the segment from where the lost track l was last seen to where it
// is predicted at stamp_s (at most max_prediction_s past its last update).
double lost_track_distance(const TrackedObstacle& l, const Eigen::Vector2d& p, double stamp_s,
                           double max_prediction_s) {
  const double dt = std::min(stamp_s - l.stamp_s, max_prediction_s);
  return point_segment_distance(p, l.predict(l.last_seen_s), l.position + l.velocity * dt);
}

// radius_floor: adds a blob's radius to t's recent radii, forgets those older than window_s and
// returns the largest left.
double floor_radius(TrackedObstacle& t, double radius_m, double stamp_s, double window_s) {
  auto& r = t.radii;
  r.push_back({stamp_s, radius_m});
  r.erase(r.begin(), std::find_if(r.begin(), r.end(), [&](const TrackedObstacle::RadiusSample& s) {
            return s.stamp_s >= stamp_s - window_s;
          }));
  double out = 0.0;
  for (const auto& s : r) out = std::max(out, s.radius_m);
  return out;
}

}  // namespace

bool MovingObstacleTracker::is_moving(const TrackedObstacle& t) const {
  return t.hits >= params_.min_hits && t.velocity.norm() >= params_.min_moving_speed_mps &&
         (t.displaced || ((t.position - t.origin).norm() >= params_.min_displacement_m && !t.origin_occupied));
}

void MovingObstacleTracker::latch_displaced(TrackedObstacle& t) const {
  const double latch = params_.latch_displacement_m;
  if (latch > 0.0 && !t.displaced && !t.origin_occupied && t.hits >= params_.min_hits &&
      t.velocity.norm() >= params_.min_moving_speed_mps && (t.position - t.origin).squaredNorm() >= latch * latch)
    t.displaced = true;
}

void MovingObstacleTracker::note_occupied_origins(const std::vector<Blob>& blobs) {
  // Half the displacement a mover needs: a track nearer its origin is not moving however its
  // filter moves it this cycle.
  const double near2 = 0.25 * params_.min_displacement_m * params_.min_displacement_m;
  for (auto& t : tracks_) {
    t.origin_occupied = false;
    if (t.displaced || (t.position - t.origin).squaredNorm() < near2) continue;
    for (const Blob& b : blobs) {
      if (!b.centroid.allFinite() || (b.centroid - t.position).norm() <= t.max_radius_m) continue;  // its own
      if ((b.centroid - t.origin).norm() <= b.radius_m + params_.vacated_radius_m) {
        t.origin_occupied = true;
        break;
      }
    }
  }
}

void MovingObstacleTracker::update_blobs(const std::vector<Blob>& blobs, double stamp_s,
                                         const std::optional<Pose2>& robot) {
  if (!params_.enabled || !std::isfinite(stamp_s) || stamp_s <= last_stamp_s_) return;
  last_stamp_s_ = stamp_s;
  predict_tracks(stamp_s);
  note_occupied_origins(blobs);
  std::vector<char> track_used(tracks_.size(), 0), blob_used(blobs.size(), 0);
  associate(blobs, stamp_s, track_used, blob_used);
  keep_unseen(stamp_s, robot, track_used);
  for (std::size_t j = 0; j < blobs.size(); ++j) {
    if (blob_used[j] || !blobs[j].centroid.allFinite()) continue;
    start_track(blobs[j], stamp_s);
  }
  for (auto it = trails_.begin(); it != trails_.end();) {
    auto& h = it->second;
    h.erase(h.begin(), std::find_if(h.begin(), h.end(), [&](const TrackedObstacle::PathSample& s) {
              return s.t_s >= stamp_s - params_.recurrence_history_s;
            }));
    it = h.empty() ? trails_.erase(it) : std::next(it);
  }
}

void MovingObstacleTracker::predict_tracks(double stamp_s) {
  const double q = params_.accel_noise_mps2;
  // Predict every track to this cycle.
  for (auto& t : tracks_) {
    const double dt = stamp_s - t.stamp_s;
    kf_predict(t.position.x(), t.velocity.x(), t.cov_x, dt, q);
    kf_predict(t.position.y(), t.velocity.y(), t.cov_y, dt, q);
    t.stamp_s = stamp_s;
  }
}

void MovingObstacleTracker::associate(const std::vector<Blob>& blobs, double stamp_s, std::vector<char>& track_used,
                                      std::vector<char>& blob_used) {
  // Gated nearest-neighbour association, closest pairs first.
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    for (std::size_t j = 0; j < blobs.size(); ++j) {
      if (!blobs[j].centroid.allFinite()) continue;
      const double d = (tracks_[i].position - blobs[j].centroid).norm();
      // A coasting track's gate widens with its uncertainty (it may have slowed or turned unseen).
      if (d <= params_.gate_m + coast_growth(tracks_[i], params_.coast_max_growth_m)) pairs.emplace_back(d, i, j);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  for (const auto& [d, i, j] : pairs) {
    if (track_used[i] || blob_used[j]) continue;
    track_used[i] = blob_used[j] = 1;
    update_track(tracks_[i], blobs[j], stamp_s);
    recur(tracks_[i], stamp_s);
  }
}

void MovingObstacleTracker::update_track(TrackedObstacle& t, const Blob& blob, double stamp_s) const {
  const double r2 = params_.measurement_noise_m * params_.measurement_noise_m;
  double rj2 = r2;
  if (params_.partial_view_noise) {
    const double r = params_.measurement_noise_m + std::max(0.0, t.max_radius_m - blob.radius_m);
    rj2 = r * r;
  }
  kf_update(t.position.x(), t.velocity.x(), t.cov_x, blob.centroid.x(), rj2);
  kf_update(t.position.y(), t.velocity.y(), t.cov_y, blob.centroid.y(), rj2);
  const double speed = t.velocity.norm();
  if (speed > params_.max_speed_mps) t.velocity *= params_.max_speed_mps / speed;
  t.max_radius_m = std::max(t.max_radius_m, blob.radius_m);
  t.radius_m = blob.radius_m;
  if (params_.radius_floor)
    t.radius_m = std::max(t.radius_m, floor_radius(t, blob.radius_m, stamp_s, params_.radius_floor_window_s));
  t.top_m = std::max(t.top_m, blob.top_m);
  ++t.hits;
  latch_displaced(t);
}

void MovingObstacleTracker::recur(TrackedObstacle& t, double stamp_s) {
  t.recurrence.clear();
  t.recurrence_base_s = stamp_s;
  t.recurrence_base = t.position;
  if (params_.recurrence_history_s <= 0.0 || !is_moving(t)) return;
  trails_[t.id].push_back({stamp_s, t.position});
  const double speed = t.velocity.norm();
  // The direction of travel at sample j of trail h: over its samples within half a second either side.
  constexpr double kHalfWindow_s = 0.5, kMinCos = 0.7071;
  const double match2 = params_.recurrence_match_m * params_.recurrence_match_m;
  const std::vector<TrackedObstacle::PathSample>* from = nullptr;
  std::size_t from_j = 0;
  for (const auto& trail : trails_) {
    const std::vector<TrackedObstacle::PathSample>& h = trail.second;
    const auto heading = [&](std::size_t j) -> Eigen::Vector2d {
      std::size_t a = j, b = j;
      while (a > 0 && h[a - 1].t_s >= h[j].t_s - kHalfWindow_s) --a;
      while (b + 1 < h.size() && h[b + 1].t_s <= h[j].t_s + kHalfWindow_s) ++b;
      return h[b].position - h[a].position;
    };
    const auto passes = [&](std::size_t j) {
      if (h[j].t_s > stamp_s - params_.recurrence_min_lag_s || (h[j].position - t.position).squaredNorm() > match2)
        return false;
      const Eigen::Vector2d d = heading(j);
      return d.norm() >= params_.min_moving_speed_mps * kHalfWindow_s &&
             d.dot(t.velocity) >= kMinCos * d.norm() * speed;
    };
    // The trail's latest pass: the run of samples that match, latest first; of it the sample
    // nearest to where t is.
    std::size_t best = h.size();
    for (std::size_t j = h.size(); j-- > 0;) {
      if (!passes(j)) {
        if (best < h.size()) break;
        continue;
      }
      if (best == h.size() ||
          (h[j].position - t.position).squaredNorm() < (h[best].position - t.position).squaredNorm())
        best = j;
    }
    if (best < h.size() && (!from || h[best].t_s > (*from)[from_j].t_s)) from = &h, from_j = best;
  }
  if (!from) return;
  const auto& h = *from;
  for (std::size_t i = from_j; i < h.size() && h[i].t_s - h[from_j].t_s <= params_.max_prediction_s; ++i)
    t.recurrence.push_back({h[i].t_s - h[from_j].t_s, h[i].position - h[from_j].position});
}

void MovingObstacleTracker::keep_unseen(double stamp_s, const std::optional<Pose2>& robot,
                                        const std::vector<char>& track_used) {
  // Tracks not seen this cycle keep their prediction until they are too old; a moving one whose
  // prediction is where no sensor could see it coasts on (the sensors' silence says nothing).
  const bool can_coast = params_.coast_in_blind_zone && robot && robot->is_finite() && !visibility_.empty();
  std::vector<TrackedObstacle> kept;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    auto& t = tracks_[i];
    if (track_used[i]) {
      t.last_seen_s = stamp_s;
      t.coasting = false;
      t.seen_sigma_m = position_sigma(t);
    }
    const double unseen_s = stamp_s - t.last_seen_s;
    if (unseen_s <= params_.max_track_age_s) {
      kept.push_back(t);
      continue;
    }
    const bool was_moving = t.coasting || is_moving(t);
    const bool coasts = was_moving && can_coast && t.top_m > 0.0 && unseen_s <= params_.max_coast_s &&
                        !((t.position - robot->position()).norm() <= params_.max_range_m &&
                          visibility_.sees(*robot, t.position, t.top_m));
    if (!coasts) {
      // Dropped: with radius_floor a moving one is remembered for reacquisition.
      if (params_.radius_floor && was_moving) lost_.emplace_back(t, stamp_s);
      continue;
    }
    t.coasting = true;
    kept.push_back(t);
  }
  tracks_ = std::move(kept);
  if (params_.radius_floor) {
    std::erase_if(lost_, [&](const std::pair<TrackedObstacle, double>& l) {
      return stamp_s - l.first.last_seen_s > params_.max_coast_s;
    });
  }
}

void MovingObstacleTracker::start_track(const Blob& blob, double stamp_s) {
  const double r2 = params_.measurement_noise_m * params_.measurement_noise_m;
  TrackedObstacle t;
  t.id = next_id_++;
  t.position = t.origin = blob.centroid;
  t.radius_m = t.max_radius_m = blob.radius_m;
  t.top_m = blob.top_m;
  t.stamp_s = t.last_seen_s = stamp_s;
  t.hits = 1;
  const double v0 = 0.5 * params_.max_speed_mps;
  t.cov_x << r2, 0.0, 0.0, v0 * v0;
  t.cov_y = t.cov_x;
  t.seen_sigma_m = position_sigma(t);
  if (params_.radius_floor) continue_lost(t, blob, stamp_s);
  tracks_.push_back(t);
}

void MovingObstacleTracker::continue_lost(TrackedObstacle& t, const Blob& blob, double stamp_s) {
  // The nearest lost track whose last seen or predicted position is within the gate (distance
  // to the segment between them) continues.
  std::size_t best = lost_.size();
  double best_d = kInf;
  for (std::size_t k = 0; k < lost_.size(); ++k) {
    const double d = lost_track_distance(lost_[k].first, blob.centroid, stamp_s, params_.max_prediction_s);
    if (d <= params_.reacquire_gate_m && d < best_d) best = k, best_d = d;
  }
  if (best < lost_.size()) {
    const TrackedObstacle& l = lost_[best].first;
    t.id = l.id;
    t.origin = l.origin;
    t.displaced = l.displaced;
    t.hits = std::max(t.hits, l.hits);
    t.velocity = l.velocity;
    t.max_radius_m = std::max(t.max_radius_m, l.max_radius_m);
    t.top_m = std::max(t.top_m, l.top_m);
    t.radii = l.radii;
    for (auto& r : t.radii) r.stamp_s = stamp_s;  // the floor restarts its window now
    t.radius_m = std::max(t.radius_m, floor_radius(t, blob.radius_m, stamp_s, params_.radius_floor_window_s));
    lost_.erase(lost_.begin() + static_cast<std::ptrdiff_t>(best));
  } else {
    t.radii.push_back({stamp_s, t.radius_m});
  }
}

std::vector<TrackedObstacle> MovingObstacleTracker::moving(double now_s) const {
  std::vector<TrackedObstacle> out;
  for (const auto& t : tracks_) {
    if (!is_moving(t) || (!t.coasting && now_s - t.last_seen_s > params_.max_track_age_s)) continue;
    out.push_back(t);
    out.back().radius_m += coast_growth(t, params_.coast_max_growth_m);
  }
  return out;
}

}  // namespace bipednav::planning::local
