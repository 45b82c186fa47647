#pragma once
// The time and memory of the commands whose accepted options allow hours of work, estimated before any
// work (issue 33: `metrics --base-cells 4096 --depth 12`, `bench crowd --agents 100000 --steps 100000`,
// `experiment manifold-compare --agents 100000`, `simulate-study --observers 100000`, `power --n
// 1000000000`, `power --simulations 1000000000`, `render --synthetic 10000` and `bench correct
// --characters 10000` printed nothing, or an estimate only after 2 s of work). One cost model per command,
// in one place: its work units counted from the options and inputs, times the seconds per unit measured
// in Release on the project's 2-core machine (the constants in command_estimates.cpp say how, and
// docs/architecture.md "Estimates before work" gives the load), plus the memory those units hold. Each
// command prints its estimate with announce_estimate before it starts; its progress lines then give the
// time left from the real rate (framework/core/progress.hpp). The limits that refuse work outright
// (characters per crowd, character-frames) are framework/spec/estimate_work.hpp's.
#include <string>
#include <vector>

namespace crowdlab::cli {

struct CommandEstimate {
  double units = 0;       ///< work units, counted from the options and inputs
  std::string unit_name;  ///< what a unit is ("agent-steps")
  double seconds = 0;     ///< units x the measured seconds per unit
  double extra_mb = 0;    ///< memory the units hold, beyond what the process holds when it is printed
};

/// Prints `e` on stderr before the work starts, labelled as the command's progress lines are.
void announce_estimate(const std::string& label, const CommandEstimate& e);

/// `metrics`: the overlap quadrature of every colliding pair in every frame; its cost grows with the
/// cells of one pair's grid (base_cells^2 x 4^depth). Counted as if every character touched one other
/// in every frame (a dense crowd), the case the limits are for.
CommandEstimate metrics_estimate(double characters, double frames, int base_cells, int depth);

/// `bench crowd`: agent-steps of the navigation model (3 warm-up steps included).
CommandEstimate bench_crowd_estimate(double agents, double steps);

/// `experiment manifold-compare`: agent-steps of every run (scenes x models x Relevant functions x runs).
CommandEstimate manifold_compare_estimate(double runs, double agents, double steps);

/// `simulate-study`: one session per observer, each answering every trial's questions.
CommandEstimate simulate_study_estimate(double observers, double trials, double questions);

/// `power`: for each n, simulations x n simulated observers answer every stimulus of the contrast.
CommandEstimate power_estimate(const std::vector<int>& sample_sizes, double simulations, double stimuli);

/// `render`: every character drawn in every frame at width x height.
CommandEstimate render_estimate(double characters, double frames, double width, double height);

/// `bench correct`: character-frames of the corrector (warm-up included).
CommandEstimate bench_correct_estimate(double characters, double frames);

}  // namespace crowdlab::cli
