// `crowdlab bench correct`: median ms per step of the collision-correction solver (seed 000 §3) on a
// stationary swaying crowd (framework/correction/swaying_crowd_fixture.hpp) at a given density.
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "experiments/cli/bench_group.hpp"
#include "experiments/cli/command_registry.hpp"
#include "framework/core/error.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"

namespace crowdlab::cli {
namespace {

/// Peak resident set size of this process (MB), from /proc/self/status VmHWM.
double peak_rss_mb() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

struct Options {
  int characters = 60;
  double density = 6.66;
  int steps = 100;
  int warmup = 10;
  int threads = 0;
  bool json = false;
  double stiffness = CorrectorParams{}.stiffness;
  double damping = CorrectorParams{}.damping;
  double contact_stiffness = CorrectorParams{}.contact_stiffness;
  double cg_tolerance = CorrectorParams{}.cg_tolerance;
};

void run(const Options& o) {
  if (o.characters < 1) throw InputError("--characters must be >= 1");
  if (o.steps < 1) throw InputError("--steps must be >= 1");
  if (o.warmup < 0) throw InputError("--warmup must be >= 0");
  if (o.threads < 0) throw InputError("--threads must be >= 0");
  const int threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));

  SwayingCrowdOptions fixture;
  fixture.characters = o.characters;
  fixture.density_per_m2 = o.density;
  fixture.frames = o.warmup + o.steps;
  const CrowdAnimation crowd = make_swaying_crowd_fixture(fixture);
  std::vector<BodyShape> shapes;
  for (const auto& ch : crowd.characters) shapes.push_back(ch.shape);
  CorrectorParams params;
  params.stiffness = o.stiffness;
  params.damping = o.damping;
  params.contact_stiffness = o.contact_stiffness;
  params.cg_tolerance = o.cg_tolerance;
  Corrector corrector(std::move(shapes), params, crowd.environment, crowd.meta.fps);

  std::vector<Pose> targets(crowd.characters.size());
  std::vector<double> ms;
  double contacts = 0.0, inter = 0.0, iterations = 0.0, pairs = 0.0;
  int rejected = 0, unconverged = 0;
  for (int f = 0; f < fixture.frames; ++f) {
    for (size_t c = 0; c < targets.size(); ++c)
      targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
    const auto t0 = std::chrono::steady_clock::now();
    corrector.step(targets);
    const auto t1 = std::chrono::steady_clock::now();
    if (f < o.warmup) continue;
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    const StepStats& st = corrector.last_stats();
    contacts += st.contacts();
    inter += st.inter_body_contacts;
    iterations += st.cg_iterations;
    pairs += st.body_pairs;
    rejected += st.rejected ? 1 : 0;
    unconverged += st.converged ? 0 : 1;
  }
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  const double median = sorted.size() % 2 ? sorted[sorted.size() / 2]
                                          : 0.5 * (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]);
  double mean = 0.0;
  for (double v : ms) mean += v;
  mean /= static_cast<double>(ms.size());
  const double n = static_cast<double>(ms.size());
  const double rss = peak_rss_mb();
  if (o.json) {
    nlohmann::json j;
    j["ms_per_step_median"] = median;
    j["ms_per_step_mean"] = mean;
    j["characters"] = o.characters;
    j["density_per_m2"] = o.density;
    j["steps"] = o.steps;
    j["contacts_mean"] = contacts / n;
    j["inter_body_contacts_mean"] = inter / n;
    j["body_pairs_mean"] = pairs / n;
    j["cg_iterations_mean"] = iterations / n;
    j["rejected_steps"] = rejected;
    j["unconverged_steps"] = unconverged;
    j["peak_rss_mb"] = rss;
    j["peak_rss_mb_per_character"] = rss / o.characters;
    j["threads"] = threads;
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("bench correct: %d characters at %.2f /m^2, %d steps (+%d warm-up), %d thread(s)\n",
                o.characters, o.density, o.steps, o.warmup, threads);
    std::printf("  ms/step   median %.3f  mean %.3f\n", median, mean);
    std::printf("  contacts  mean %.1f (inter-body %.1f), body pairs %.1f\n", contacts / n, inter / n,
                pairs / n);
    std::printf("  CG        mean %.2f iterations; %d unconverged, %d rejected steps\n", iterations / n,
                unconverged, rejected);
    std::printf("  memory    peak RSS %.1f MB (%.3f MB per character, fixture animation included)\n", rss,
                rss / o.characters);
  }
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto opts = std::make_shared<Options>();
  auto* cmd = bench_group(root)->add_subcommand(
      "correct", "Collision-correction solver: median ms per step on a stationary swaying crowd");
  cmd->add_option("--characters", opts->characters, "Number of characters")->capture_default_str();
  cmd->add_option("--density", opts->density, "Characters per square metre")->capture_default_str();
  cmd->add_option("--steps", opts->steps, "Timed steps")->capture_default_str();
  cmd->add_option("--warmup", opts->warmup, "Untimed steps first")->capture_default_str();
  cmd->add_option("--threads", opts->threads, "TBB threads (0 = all cores)")->capture_default_str();
  cmd->add_option("--stiffness", opts->stiffness, "Control spring k (Eq. 4, per unit inertia, 1/s^2)")
      ->capture_default_str();
  cmd->add_option("--damping", opts->damping, "Control damping d (Eq. 4)")->capture_default_str();
  cmd->add_option("--contact-stiffness", opts->contact_stiffness, "Collision penalty k_delta (N/m)")
      ->capture_default_str();
  cmd->add_option("--cg-tolerance", opts->cg_tolerance, "CG relative residual tolerance")
      ->capture_default_str();
  cmd->add_flag("--json", opts->json, "Print one JSON object");
  cmd->callback([opts] { run(*opts); });
});

}  // namespace
}  // namespace crowdlab::cli
