#include "experiments/cli/bench_correct_run.hpp"

#include <tbb/global_control.h>
#include <tbb/info.h>

#include <fstream>
#include <string>
#include <vector>

#include "experiments/cli/command_estimates.hpp"
#include "experiments/cli/timing.hpp"
#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "framework/pipeline/metrics_json.hpp"
#include "framework/spec/estimate_work.hpp"

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

}  // namespace

CorrectBenchResult run_correct_bench(const CorrectBenchOptions& o) {
  if (o.characters < 1) throw InputError("--characters must be >= 1");
  if (o.steps < 1) throw InputError("--steps must be >= 1");
  if (o.warmup < 0) throw InputError("--warmup must be >= 0");
  if (o.threads < 0) throw InputError("--threads must be >= 0");
  // The fixture keeps every pose of every frame: refused by the one crowd estimate before it is built
  // (issue 32: --characters 1000000; issue 33: --steps 1000000 with 100 characters, a raw bad_alloc).
  if (const auto problem =
          crowd_limit_problem("the benchmark crowd (--characters " + std::to_string(o.characters) + ")",
                              o.characters, static_cast<double>(o.warmup) + o.steps, "lower --characters",
                              "lower --steps (+ --warmup " + std::to_string(o.warmup) + ") or --characters"))
    throw InputError(*problem);
  CorrectBenchResult r;
  r.options = o;
  r.threads = o.threads > 0 ? o.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(r.threads));

  SwayingCrowdOptions fixture;
  fixture.characters = o.characters;
  fixture.density_per_m2 = o.density;
  fixture.frames = o.warmup + o.steps;
  announce_estimate("bench correct",
                    bench_correct_estimate(o.characters, fixture.frames));  // before the fixture
  const CrowdAnimation crowd = make_swaying_crowd_fixture(fixture);
  std::vector<BodyShape> shapes;
  for (const auto& ch : crowd.characters) shapes.push_back(ch.shape);
  Corrector corrector(std::move(shapes), o.params, crowd.environment, crowd.meta.fps);

  std::vector<Pose> targets(crowd.characters.size());
  std::vector<double> ms, cpu_ms;
  CrowdAnimation corrected = o.quality ? crowd : CrowdAnimation{};  // filled outside the timed region
  // Estimate and time left for the big runs --characters allows (outside the timed region, issue 33).
  Progress progress("bench correct", static_cast<std::size_t>(fixture.frames));
  for (int f = 0; f < fixture.frames; ++f, progress.advance()) {
    for (size_t c = 0; c < targets.size(); ++c)
      targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
    const double cpu0 = process_cpu_ms();
    std::vector<Pose> out;
    const double step_ms = time_ms([&] { out = corrector.step(targets); });
    const double cpu1 = process_cpu_ms();
    if (o.quality)
      for (size_t c = 0; c < targets.size(); ++c)
        corrected.characters[c].frames[static_cast<size_t>(f)] = out[c];
    if (f < o.warmup) continue;
    ms.push_back(step_ms);
    cpu_ms.push_back(cpu1 - cpu0);
    const StepStats& st = corrector.last_stats();
    r.contacts_mean += st.contacts();
    r.inter_body_contacts_mean += st.inter_body_contacts;
    r.cg_iterations_mean += st.cg_iterations;
    r.body_pairs_mean += st.body_pairs;
    r.pulling_contacts_mean += st.pulling_contacts;
    r.active_set_passes_mean += st.active_set_passes;
    r.deep_contacts_mean += st.deep_contacts;
    r.depenetration_passes_mean += st.depenetration_passes;
    r.rejected_steps += st.rejected ? 1 : 0;
    r.unconverged_steps += st.converged ? 0 : 1;
  }
  const double n = static_cast<double>(ms.size());
  r.ms_median = median_of(ms);
  r.ms_mean = mean_of(ms);
  r.cpu_ms_median = median_of(cpu_ms);
  r.pulling_contacts_mean /= n;
  r.active_set_passes_mean /= n;
  r.deep_contacts_mean /= n;
  r.depenetration_passes_mean /= n;
  r.contacts_mean /= n;
  r.inter_body_contacts_mean /= n;
  r.cg_iterations_mean /= n;
  r.body_pairs_mean /= n;
  r.peak_rss_mb = peak_rss_mb();
  if (o.quality) {
    r.quality = measure_correction_quality(crowd, corrected, o.warmup);
    MetricsOptions mo;
    mo.pair_volumes = false;
    CrowdAnimation in_part = crowd, out_part = corrected;
    for (CrowdAnimation* a : {&in_part, &out_part})
      for (auto& ch : a->characters) ch.frames.erase(ch.frames.begin(), ch.frames.begin() + o.warmup);
    r.overlap_baseline_l = measure_crowd(in_part, mo).mean_character_overlap_l;
    r.overlap_corrected_l = measure_crowd(out_part, mo).mean_character_overlap_l;
  }
  return r;
}

nlohmann::json correct_bench_json(const CorrectBenchResult& r) {
  nlohmann::json j;
  j["ms_per_step_median"] = r.ms_median;
  j["ms_per_step_mean"] = r.ms_mean;
  j["characters"] = r.options.characters;
  j["density_per_m2"] = r.options.density;
  j["steps"] = r.options.steps;
  j["contacts_mean"] = r.contacts_mean;
  j["inter_body_contacts_mean"] = r.inter_body_contacts_mean;
  j["body_pairs_mean"] = r.body_pairs_mean;
  j["cg_iterations_mean"] = r.cg_iterations_mean;
  j["rejected_steps"] = r.rejected_steps;
  j["unconverged_steps"] = r.unconverged_steps;
  j["peak_rss_mb"] = r.peak_rss_mb;
  j["peak_rss_mb_per_character"] = r.peak_rss_mb / r.options.characters;
  j["threads"] = r.threads;
  j["cpu_ms_per_step_median"] = r.cpu_ms_median;
  j["pulling_contacts_mean"] = r.pulling_contacts_mean;
  j["deep_contacts_mean"] = r.deep_contacts_mean;
  j["depenetration_passes_mean"] = r.depenetration_passes_mean;
  j["active_set_passes_mean"] = r.active_set_passes_mean;
  if (r.options.quality) {
    const CorrectionQuality& q = r.quality;
    j["overlap_baseline_l"] = r.overlap_baseline_l;
    j["overlap_corrected_l"] = r.overlap_corrected_l;
    j["overlap_reduction"] =
        r.overlap_baseline_l > 0 ? 1.0 - r.overlap_corrected_l / r.overlap_baseline_l : 0.0;
    j.update(correction_quality_json(q));
  }
  return j;
}

}  // namespace crowdlab::cli
