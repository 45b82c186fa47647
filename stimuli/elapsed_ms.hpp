#pragma once
// Milliseconds elapsed on the steady clock since a time point: the renderer's and the clip writer's
// per-stage timings. One definition for both files (they are compiled in one unity batch, issue 31).

#include <chrono>

namespace crowdlab::stimuli {

/// t: a steady_clock time point taken earlier. Returns the milliseconds since then (>= 0).
inline double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace crowdlab::stimuli
