#pragma once

#include <vector>

#include "bipednav/tracking/detection.hpp"
#include "bipednav/tracking/track_filter.hpp"

namespace bipednav::tracking {

// Global nearest neighbour association of detections to tracks (their filters, predicted to the
// detections' time). A pair is allowed when the detection lies inside the track's Mahalanobis
// gate, d^2 = nu^T S^-1 nu <= gate_chi2 (S the innovation covariance of the track's prediction and
// the detection's covariance); the allowed pairs are assigned by the Hungarian method
// (solve_assignment: the most pairs, then the least cost) on the cost d^2 + ln det S, the
// negative log-likelihood of the pair up to a constant (Blackman's generalized distance, 1986).
// Returns, per track, the index of its detection or -1. Non-finite detections are never assigned.
std::vector<int> associate(const std::vector<const TrackFilter*>& tracks, const std::vector<Detection>& detections,
                           double gate_chi2);

}  // namespace bipednav::tracking
