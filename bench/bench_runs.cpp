#include "bench/bench_runs.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "bipednav/common/progress.hpp"
#include "bipednav/navigation/robot_loading.hpp"
#include "bipednav/runner/footstep_runner.hpp"

namespace bipednav::bench {

void run_in_parallel(std::size_t n, int jobs, const std::string& label, const std::function<void(std::size_t)>& work) {
  ProgressBar bar(label, n, true);
  std::mutex bar_mutex;
  std::atomic<std::size_t> next{0}, done{0};
  auto worker = [&] {
    for (std::size_t i = next++; i < n; i = next++) {
      work(i);
      const std::lock_guard lock(bar_mutex);
      bar.update(++done);
    }
  };
  std::vector<std::thread> threads;
  for (int j = 1; j < jobs; ++j) threads.emplace_back(worker);
  worker();
  for (auto& t : threads) t.join();
  bar.finish();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

std::map<std::string, RobotProfile> robot_profiles(const std::vector<std::string>& robots,
                                                   const runner::RunOptions& base) {
  std::map<std::string, RobotProfile> profiles;
  for (const auto& robot : robots) {
    const RobotProfile profile = navigation::load_robot(robot);
    // Reads the parameters each run will read, so a bad file fails before the first run.
    if (runner::is_footstep_robot(profile))
      runner::footstep_navigator_params(profile, base.params_file);
    else
      runner::navigator_params(profile, base);
    profiles[robot] = profile;
  }
  return profiles;
}

}  // namespace bipednav::bench
