#include "bipednav/tracking/persistent_cells.hpp"

#include <cmath>
#include <iterator>

namespace bipednav::tracking {

PersistentCells::PersistentCells(double cell_m, double min_span_s, double max_gap_s, double memory_s)
    : cell_m_(cell_m), min_span_s_(min_span_s), max_gap_s_(max_gap_s), memory_s_(memory_s) {}

bool PersistentCells::key_of(const Eigen::Vector2d& p, std::uint64_t& key) const {
  const double fx = std::floor(p.x() / cell_m_), fy = std::floor(p.y() / cell_m_);
  if (!(std::abs(fx) < 1e9 && std::abs(fy) < 1e9)) return false;
  key = (static_cast<std::uint64_t>(static_cast<std::uint32_t>(static_cast<std::int32_t>(fx))) << 32) |
        static_cast<std::uint64_t>(static_cast<std::uint32_t>(static_cast<std::int32_t>(fy)));
  return true;
}

void PersistentCells::hit(const Eigen::Vector3d& p, double stamp_s) {
  std::uint64_t key = 0;
  if (!key_of(p.head<2>(), key)) return;
  const auto [it, fresh] = cells_.try_emplace(key, Run{stamp_s, stamp_s, false});
  Run& r = it->second;
  if (!fresh && stamp_s - r.last_s > max_gap_s_ && !r.earned) r.start_s = stamp_s;  // the run broke off
  r.last_s = stamp_s;
  if (stamp_s - r.start_s >= min_span_s_) r.earned = true;
}

void PersistentCells::forget_old(double stamp_s) {
  // Once a second: runs that broke off and earned cells unhit for memory_s go.
  if (stamp_s - last_forget_s_ < 1.0) return;
  last_forget_s_ = stamp_s;
  for (auto it = cells_.begin(); it != cells_.end();) {
    const Run& r = it->second;
    const double unhit = stamp_s - r.last_s;
    if (r.earned ? unhit > memory_s_ : unhit > max_gap_s_)
      it = cells_.erase(it);
    else
      ++it;
  }
}

bool PersistentCells::persistent(const Eigen::Vector2d& p) const {
  std::uint64_t key = 0;
  if (!key_of(p, key)) return false;
  const auto it = cells_.find(key);
  return it != cells_.end() && it->second.earned && stamp_s_ - it->second.last_s <= memory_s_;
}

void PersistentCells::clear() {
  cells_.clear();
  stamp_s_ = last_forget_s_ = -1e300;
}

}  // namespace bipednav::tracking
