#include "experiments/cli/command_estimates.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/progress.hpp"

namespace crowdlab::cli {
namespace {

// Seconds per work unit and bytes per unit, measured in Release on the project's 2-core machine (the
// commands and the load are in docs/architecture.md, "Estimates before work"). They are for the order
// of magnitude the user must know before starting (minutes, hours or years; megabytes or gigabytes):
// the progress lines correct them from the real rate once the work runs.

/// `metrics`: one colliding pair's overlap volume at the default quadrature (12 x 2^1 cells across,
/// 576 cells), with its depth and collision tests, per character and frame. A 56-character crowd at
/// 3.5 / m^2, 120 frames: 3.3 s at the default, 8.3 s at --depth 2, 96 s at --base-cells 48 --depth 2
/// (estimated 2, 7 and 108 s).
constexpr double kMetricsSecondsPerPairAtDefault = 2.5e-4;
constexpr double kMetricsDefaultCells = 12.0 * 12.0 * 4.0;
/// Per character and frame: the per-character overlap and depth series the report keeps.
constexpr double kMetricsBytesPerCharacterFrame = 16;

/// `bench crowd`: the default model (ORCA) on the circle crossing (0.17-0.96 us per agent-step measured
/// with 2,000-100,000 agents; the crowd is densest at the centre, so the upper end is taken).
constexpr double kCrowdSecondsPerAgentStep = 1e-6;
constexpr double kCrowdBytesPerAgent = 250;  // 100,000 agents: 110 MB resident against 85 MB for 2,000

/// `experiment manifold-compare`: one agent-step, averaged over its scenes, models and Relevant functions,
/// and each run's set-up (the model, spawning); 400 agents, 10 and 40 steps: 20.3 and 55.7 s.
constexpr double kManifoldSecondsPerAgentStep = 1.2e-4;
constexpr double kManifoldSecondsPerRun = 0.35;
constexpr double kManifoldBytesPerAgent = 1000;

/// `simulate-study`: one simulated trial (answers drawn, written to the observer's CSV and merged): 300
/// observers x 4 trials in 1.7 s.
constexpr double kSimulatedSecondsPerTrial = 1.4e-3;
/// One row of the merged responses.csv per question answered (its text is held until it is written).
constexpr double kResponseRowBytes = 160;

/// `power`: one simulated observer answering one stimulus (--n 1000 --simulations 200 on 4 stimuli, 8e5
/// answers: 4.3 s).
constexpr double kPowerSecondsPerAnswer = 5e-6;

/// `render` (llvmpipe, the headless default here): setting up one character's meshes, drawing one
/// character in one frame, and drawing and encoding one pixel of a frame. Synthetic crowds of 20 and 100
/// characters, 10 frames at 320 x 192 and 1280 x 720: setup 15 and 62 s, 172 and 463 ms per frame at 320 x
/// 192, 516 ms per frame at 1280 x 720.
constexpr double kRenderSecondsPerCharacter = 0.5;
constexpr double kRenderSecondsPerCharacterFrame = 3.6e-3;
constexpr double kRenderSecondsPerPixel = 4e-7;
/// The per-character meshes and buffers (230 MB resident for 20 characters, 398 MB for 100).
constexpr double kRenderBytesPerCharacter = 2e6;
constexpr double kPoseBytes = 24 * 4 * 8 + 64;  // 24 joint quaternions, root position, vector header

/// `bench correct`: one character through one corrector step (the default swaying crowd, 2 threads: 88 ms
/// per step for 100 characters, 554 ms for 400), and the corrector's state per character (peak 85 MB
/// resident for 100 characters, 111 MB for 400).
constexpr double kCorrectSecondsPerCharacterFrame = 1e-3;
constexpr double kCorrectBytesPerCharacter = 9e4;

constexpr double kMB = 1e6;

}  // namespace

void announce_estimate(const std::string& label, const CommandEstimate& e) {
  Progress::announce_estimate(label, e.units, e.unit_name, e.seconds, e.extra_mb);
}

CommandEstimate metrics_estimate(double characters, double frames, int base_cells, int depth) {
  const double cells = static_cast<double>(base_cells) * base_cells * std::pow(4.0, depth);
  const double pair_frames = characters * frames;
  return {pair_frames,
          "colliding pair-frames of " + std::to_string(base_cells) + " x 2^" + std::to_string(depth) +
              " cells across (one pair per character and frame)",
          pair_frames * kMetricsSecondsPerPairAtDefault * cells / kMetricsDefaultCells,
          pair_frames * kMetricsBytesPerCharacterFrame / kMB};
}

CommandEstimate bench_crowd_estimate(double agents, double steps) {
  const double agent_steps = agents * (steps + 3);
  return {agent_steps, "agent-steps", agent_steps * kCrowdSecondsPerAgentStep,
          (agents * kCrowdBytesPerAgent + steps * 2 * sizeof(double)) / kMB};
}

CommandEstimate manifold_compare_estimate(double runs, double agents, double steps) {
  const double agent_steps = runs * agents * steps;
  return {agent_steps, "agent-steps",
          runs * kManifoldSecondsPerRun + agent_steps * kManifoldSecondsPerAgentStep,
          agents * kManifoldBytesPerAgent / kMB};
}

CommandEstimate simulate_study_estimate(double observers, double trials, double questions) {
  const double observer_trials = observers * trials;
  return {observer_trials, "observer-trials", observer_trials * kSimulatedSecondsPerTrial,
          observer_trials * std::max(1.0, questions) * kResponseRowBytes / kMB};
}

CommandEstimate power_estimate(const std::vector<int>& sample_sizes, double simulations, double stimuli) {
  double observers = 0, largest_n = 0;
  for (int n : sample_sizes) {
    observers += simulations * n;
    largest_n = std::max(largest_n, static_cast<double>(n));
  }
  const double answers = observers * stimuli;
  return {answers, "observer-stimulus answers", answers * kPowerSecondsPerAnswer,
          largest_n * sizeof(double) / kMB};  // one difference per observer of a simulated study
}

CommandEstimate render_estimate(double characters, double frames, double width, double height) {
  const double character_frames = characters * frames;
  return {character_frames, "character-frames",
          characters * kRenderSecondsPerCharacter + character_frames * kRenderSecondsPerCharacterFrame +
              frames * width * height * kRenderSecondsPerPixel,
          (characters * kRenderBytesPerCharacter + character_frames * kPoseBytes) / kMB};
}

CommandEstimate bench_correct_estimate(double characters, double frames) {
  const double character_frames = characters * frames;
  return {character_frames, "character-frames", character_frames * kCorrectSecondsPerCharacterFrame,
          // the corrector's state, the fixture's poses and the corrected copy
          (characters * kCorrectBytesPerCharacter + 2 * character_frames * kPoseBytes) / kMB};
}

}  // namespace crowdlab::cli
