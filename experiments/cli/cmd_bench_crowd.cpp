// `crowdlab bench crowd`: milliseconds per simulation step of a navigation model on the classic
// antipodal-circle benchmark (van den Berg et al. 2011, Sec. 6): N agents evenly spaced 0.6 m apart
// on a circle of radius R = 0.6 N / (2 pi), each walking to its antipode. Radius 0.25 m, neighbour
// distance 2 m, 10 neighbours, horizons 2 s, max speed 1.5 m/s, dt 0.1 s (the crowd.* defaults).
// A throwaway 3-step run warms caches and the TBB pool; then every step of a fresh run is timed
// with steady_clock. Reports the median and mean over the timed steps.
#include <tbb/global_control.h>
#include <tbb/info.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <numeric>
#include <vector>

#include "experiments/cli/bench_group.hpp"
#include "experiments/cli/command_estimates.hpp"
#include "experiments/cli/command_table.hpp"
#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "framework/crowd/crowd_simulation.hpp"
#include "framework/crowd/make_navigation_model.hpp"

namespace crowdlab::cli::cmd_bench_crowd {
namespace {

struct Args {
  std::string model = "orca";
  int agents = 1000, steps = 100, threads = 1;
  bool until_arrived = false, json = false, overlap_free = false;
};

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

/// CPU time of the whole process (all threads), ms. On a loaded machine wall time includes waiting
/// for a core; CPU time per step (divided by the threads) shows what the code itself costs.
double process_cpu_ms() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) * 1e3 + static_cast<double>(ts.tv_nsec) * 1e-6;
}

std::vector<AgentInit> circle_agents(int n) {
  const double R = n * 0.6 / (2.0 * std::numbers::pi);
  std::vector<AgentInit> agents(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double a = 2.0 * std::numbers::pi * i / n;
    AgentInit& g = agents[static_cast<std::size_t>(i)];
    g.position = R * Vec2(std::cos(a), std::sin(a));
    g.goal = -g.position;
    g.radius_m = 0.25;
    g.preferred_speed_mps = 1.5;
    g.max_speed_mps = 1.5;
  }
  return agents;
}

bool all_arrived(const CrowdSimulation& sim, const std::vector<AgentInit>& agents) {
  for (std::size_t i = 0; i < sim.size(); ++i)
    if ((sim.position(i) - agents[i].goal).norm() > 0.05) return false;
  return true;
}

// Beyond these a benchmark runs for hours or exhausts memory before printing anything (issue 21:
// --agents 1000000000); they are ten times the largest crowds and runs the project measures.
constexpr int kMaxAgents = 100000;
constexpr int kMaxSteps = 100000;

void run(const Args& a) {
  if (a.agents < 2 || a.agents > kMaxAgents)
    throw InputError(SourceLocation{"", 0, 0, "--agents"},
                     "must be 2 to " + std::to_string(kMaxAgents) + ", got " + std::to_string(a.agents));
  if (a.steps < 1 || a.steps > kMaxSteps)
    throw InputError(SourceLocation{"", 0, 0, "--steps"},
                     "must be 1 to " + std::to_string(kMaxSteps) + ", got " + std::to_string(a.steps));
  if (a.threads < 1) throw InputError("bench crowd: --threads must be >= 1");
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(a.threads));
  CrowdSpec spec;                                 // the benchmark's parameters are crowd.* defaults
  spec.model = *parse_kind<CrowdModel>(a.model);  // check::is_member allows only the enum's spellings
  if (a.overlap_free && a.model != "orca")
    throw InputError("bench crowd: --overlap-free applies to --model orca only");
  spec.overlap_free = a.overlap_free;  // crowd.overlap_free
  const std::shared_ptr<const NavigationModel> model = make_navigation_model(spec);
  announce_estimate("bench crowd", bench_crowd_estimate(a.agents, a.steps));  // before the warm-up
  const std::vector<AgentInit> agents = circle_agents(a.agents);
  {
    CrowdSimulation warm(model, agents, {}, spec.dt_s);
    for (int s = 0; s < 3; ++s) warm.step();
  }
  CrowdSimulation sim(model, agents, {}, spec.dt_s);
  std::vector<double> ms, cpu_ms;
  ms.reserve(static_cast<std::size_t>(a.steps));
  cpu_ms.reserve(static_cast<std::size_t>(a.steps));
  // Estimate and time left for the big runs --agents and --steps allow (outside the timed region, issue 33).
  Progress progress("bench crowd", static_cast<std::size_t>(a.steps));
  for (int s = 0; s < a.steps; ++s, progress.advance()) {
    const double c0 = process_cpu_ms();
    const auto t0 = std::chrono::steady_clock::now();
    sim.step();
    const auto t1 = std::chrono::steady_clock::now();
    cpu_ms.push_back(process_cpu_ms() - c0);
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    if (a.until_arrived && s % 10 == 9 && all_arrived(sim, agents)) break;
  }
  const double med = median(ms),
               mean = std::accumulate(ms.begin(), ms.end(), 0.0) / static_cast<double>(ms.size());
  const bool arrived = all_arrived(sim, agents);
  const double cpu_med = median(cpu_ms);
  const double cpu_mean =
      std::accumulate(cpu_ms.begin(), cpu_ms.end(), 0.0) / static_cast<double>(cpu_ms.size());
  if (a.json) {
    nlohmann::json j = {{"benchmark", "crowd"},
                        {"model", a.model},
                        {"agents", a.agents},
                        {"threads", a.threads},
                        {"steps", ms.size()},
                        {"ms_per_step_median", med},
                        {"ms_per_step_mean", mean},
                        {"substeps", sim.substeps()},
                        {"overlap_free", a.overlap_free},
                        {"overlap_projections", sim.overlap_resolutions()},
                        {"all_arrived", arrived},
                        {"cpu_ms_per_step_median", cpu_med},
                        {"cpu_ms_per_step_mean", cpu_mean}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf(
        "bench crowd: model %s%s, %d agents on a circle, %d thread(s), %zu steps (dt %.2f s, %d "
        "substep(s))\n",
        a.model.c_str(), a.overlap_free ? " (overlap-free)" : "", a.agents, a.threads, ms.size(), spec.dt_s,
        sim.substeps());
    std::printf(
        "  ms per step: median %.4f, mean %.4f (process CPU ms: median %.4f, mean %.4f); all at their "
        "antipodes: %s\n",
        med, mean, cpu_med, cpu_mean, arrived ? "yes" : "no");
  }
}

}  // namespace

void add_bench_crowd_command(Command& root) {
  auto args = std::make_shared<Args>();
  Command* cmd = bench_group(root)->add_subcommand(
      "crowd",
      "Milliseconds per step of a 2D navigation model: N agents on a circle (0.6 m apart) swapping to "
      "their antipodes");
  cmd->add_option("--model", args->model, "Navigation model")
      ->check(check::is_member(kind_names<CrowdModel>()))
      ->capture_default_str();
  cmd->add_option("--agents", args->agents, "Number of agents N (circle radius N*0.6/2pi m), at most 100000")
      ->capture_default_str();
  cmd->add_option("--steps", args->steps,
                  "Timed steps of 0.1 s (the cap with --until-arrived), at most 100000")
      ->capture_default_str();
  cmd->add_option("--threads", args->threads, "TBB worker threads")->capture_default_str();
  cmd->add_flag("--until-arrived", args->until_arrived, "Stop once every agent has reached its antipode");
  cmd->add_flag("--overlap-free", args->overlap_free,
                "ORCA's overlap-free mode: step guards in infeasible programs plus the overlap projection "
                "(default: plain ORCA as in the paper and RVO2)");
  cmd->add_flag("--json", args->json, "Print one JSON object");
  cmd->callback([args] { run(*args); });
}

}  // namespace crowdlab::cli::cmd_bench_crowd
