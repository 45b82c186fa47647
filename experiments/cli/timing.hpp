#pragma once
// Timing helpers shared by the `crowdlab bench` subcommands.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <numeric>
#include <vector>

namespace crowdlab::cli {

/// Median of a sample (copies; fine for benchmark-sized samples). 0 for an empty sample.
inline double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

inline double mean_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

/// Milliseconds taken by f().
template <class F>
double time_ms(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

/// CPU time of the calling thread (ms) taken by f(). On a shared machine wall time also counts the
/// time other processes hold the core; this does not. Meaningful for single-threaded runs (with one
/// TBB thread the work runs on the calling thread).
template <class F>
double thread_cpu_ms(F&& f) {
  timespec t0{}, t1{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
  f();
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
  return 1e3 * static_cast<double>(t1.tv_sec - t0.tv_sec) +
         1e-6 * static_cast<double>(t1.tv_nsec - t0.tv_nsec);
}

/// CPU time of the whole process, all threads (ms). For multi-threaded benchmarks on a shared machine:
/// differences of this around a step count the work done, not the time spent waiting for a core.
inline double process_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

}  // namespace crowdlab::cli
