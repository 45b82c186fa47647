#include "experiments/cli/reproduce/reproduce_gomez2024.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <algorithm>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>

#include "crowdlab_embedded_paper_specs.hpp"
#include "experiments/cli/bench_correct_run.hpp"
#include "experiments/cli/figures/damping_figure.hpp"
#include "experiments/cli/figures/overlap_vs_density.hpp"
#include "experiments/cli/reproduce/correction_quality_section.hpp"
#include "experiments/cli/reproduce/reproduction_checks.hpp"
#include "experiments/cli/reproduce/stimulus_check_section.hpp"
#include "framework/core/error.hpp"
#include "framework/correction/damping_experiment.hpp"
#include "framework/pipeline/provenance.hpp"

namespace crowdlab::cli {
namespace {
namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
using nlohmann::json;

struct Size {
  double duration_s, fps;
  int observers, timing_steps, timing_warmup;
  double min_reduction;  ///< Fig. 3 tolerance: ours / baseline <= 1 - min_reduction at every density
};

Size size_of(const ReproduceOptions& o) {
  // The corrector starts on the uncorrected first frame and separates the bodies over ~0.3-0.5 s, a third
  // of a 1 s clip: the quick size accepts a 70 % reduction, the full (20 s) size the 95 %.
  Size s = o.quick ? Size{1.0, 30.0, 8, 10, 2, 0.70} : Size{20.0, 30.0, 30, 100, 10, 0.95};
  if (o.duration_s > 0) s.duration_s = o.duration_s;
  if (o.fps > 0) s.fps = o.fps;
  if (o.observers > 0) s.observers = o.observers;
  return s;
}

/// Fig. 3 rows from a run's per-condition metrics (viewpoints share one crowd: first one wins).
void add_overlap_rows(const SpecRun& run, const std::string& scenario, std::vector<OverlapRow>& rows) {
  std::map<std::pair<double, std::string>, bool> seen;
  for (const StimulusEntry& e : run.manifest.entries) {
    if (e.practice) continue;
    const double density = std::stod(e.factors.at("density"));
    const std::string method = e.factors.at("method");
    if (seen[{density, method}]) continue;
    seen[{density, method}] = true;
    const json m = entry_metrics(run, e);
    rows.push_back({scenario, m.at("characters").get<int>(), density, method, e.mean_overlap_l});
  }
  std::stable_sort(rows.begin(), rows.end(), [](const OverlapRow& a, const OverlapRow& b) {
    return a.scenario != b.scenario ? a.scenario > b.scenario  // stationary first
           : a.density != b.density ? a.density < b.density
                                    : a.method < b.method;
  });
}

void check_overlap(const std::vector<OverlapRow>& rows, double min_reduction, ReproductionChecks& checks,
                   std::string& md) {
  md +=
      "## Figure 3: mean per-character overlap volume vs density\n\n"
      "![stationary](fig3/overlap_vs_density_stationary.png) "
      "![corridor](fig3/overlap_vs_density_corridor.png)\n\n"
      "| scenario | density (/m²) | characters | baseline (L) | ours (L) | reduction |\n"
      "|---|---|---|---|---|---|\n";
  for (const std::string scenario : {"stationary", "corridor"}) {
    double lowest = kNaN, highest = kNaN, lowest_density = 1e9, highest_density = -1;
    for (const OverlapRow& r : rows) {
      if (r.scenario != scenario || r.method != "baseline") continue;
      const double ours = overlap_of(rows, scenario, r.density, "ours");
      const double reduction = r.mean_overlap_l > 0 ? 1.0 - ours / r.mean_overlap_l : kNaN;
      md += fmt::format("| {} | {} | {} | {} | {} | {:.1f} % |\n", scenario, r.density, r.characters,
                        repro_number(r.mean_overlap_l), repro_number(ours), 100 * reduction);
      checks.within(fmt::format("fig3.{}.reduction@{}", scenario, r.density),
                    fmt::format("{} at {}/m²: overlap reduction of ours vs baseline", scenario, r.density),
                    reduction, min_reduction, 1.0,
                    min_reduction >= 0.95
                        ? "§4.2: ours keeps a 'relatively low' overlap; issue target >= 95 %"
                        : "§4.2 'relatively low'; >= 70 % on 1 s clips (start-up transient)");
      if (r.density < lowest_density) lowest_density = r.density, lowest = r.mean_overlap_l;
      if (r.density > highest_density) highest_density = r.density, highest = r.mean_overlap_l;
    }
    checks.within(fmt::format("fig3.{}.baseline_growth", scenario),
                  fmt::format("{}: baseline overlap at {}/m² over that at {}/m²", scenario, highest_density,
                              lowest_density),
                  highest / lowest, 1.0, kInf,
                  "§4.2: baseline overlap 'increases dramatically' with density");
  }
  md +=
      "\nThe paper gives Figure 3 as a plot only (no numbers in the text): the baseline grows steeply with "
      "density while ours stays 'relatively low'.\n\n";
}

void damping_section(const fs::path& dir, ReproductionChecks& checks, std::string& md) {
  const std::vector<DampingRun> runs =
      run_damping_experiment({0.0, 0.006, 0.06, 0.6}, CorrectorParams{}, 8.0);
  write_damping_figure(runs, dir / "fig4");
  md +=
      "## Figure 4: damping sweep (shove at t = 3.5 s)\n\n![damping](fig4/damping.png)\n\n"
      "| d | RMS deviation after 3.5 s (mm) | max deviation (mm) | overshoot past the target (mm) | "
      "mean deviation, last second (mm) |\n|---|---|---|---|---|\n";
  std::map<double, const DampingRun*> by_d;
  for (const DampingRun& r : runs) {
    by_d[r.damping] = &r;
    md += fmt::format("| {} | {:.2f} | {:.2f} | {:.2f} | {:.2f} |\n", r.damping, 1000 * r.rms_deviation_m,
                      1000 * r.max_deviation_m, 1000 * r.overshoot_m, 1000 * r.final_deviation_m);
  }
  md +=
      "\nPaper (Fig. 4 caption): d = 0.006 closely matches the target; no damping is unstable; a high d "
      "drifts from the target.\n\n";
  // The caption's two failure modes, each measured by what it is: an undamped character rings past its
  // target after the shove (overshoot), an over-damped one is still away from it at the end (final
  // deviation). RMS over the whole recovery mixes the shove itself in and does not separate them. The
  // factor 3 is our tolerance: the paper shows the curves only (measured ~15x for both,
  // docs/reproductions.md).
  const DampingRun& nominal = *by_d.at(0.006);
  constexpr double kFactor = 3.0;
  checks.within("fig4.push_moves", "largest deviation with d = 0.006 (m): the shove moved the character",
                nominal.max_deviation_m, 0.005, kInf, "Fig. 4: a collision at t = 3.5 s");
  checks.within("fig4.d0_vs_d0.006", "overshoot past the target, ratio d = 0 / d = 0.006",
                by_d.at(0.0)->overshoot_m / std::max(nominal.overshoot_m, 1e-4), kFactor, kInf,
                "Fig. 4: no damping is unstable (rings)");
  checks.within("fig4.d0.6_vs_d0.006", "deviation in the last second, ratio d = 0.6 / d = 0.006",
                by_d.at(0.6)->final_deviation_m / std::max(nominal.final_deviation_m, 1e-4), kFactor, kInf,
                "Fig. 4: high damping drifts from the target");
}

void timing_section(const Size& size, const fs::path& dir, std::string& md) {
  struct Case {
    int characters;
    double density, paper_ms;
    const char* target;  ///< this project's target, if any (not checked: wall clock depends on the load)
  };
  std::string csv =
      "characters,density_per_m2,ms_per_step_median,ms_per_step_mean,contacts_mean,"
      "cg_iterations_mean,threads,paper_ms_per_step\n";
  md +=
      "## Timing: corrector ms per step\n\n"
      "| characters | density (/m²) | this machine, median (mean) ms | contacts | CG iterations | threads | "
      "paper (8-core Ryzen 7 2700) | target |\n|---|---|---|---|---|---|---|---|\n";
  for (const Case c :
       {Case{20, 2.22, 5.0, "-"}, Case{60, 6.66, 20.0, "<= 2 ms on a quiet 2-core machine (issue 18)"}}) {
    CorrectBenchOptions b;
    b.characters = c.characters;
    b.density = c.density;
    b.steps = size.timing_steps;
    b.warmup = size.timing_warmup;
    const CorrectBenchResult r = run_correct_bench(b);
    csv += fmt::format("{},{},{:.4f},{:.4f},{:.2f},{:.2f},{},{}\n", c.characters, c.density, r.ms_median,
                       r.ms_mean, r.contacts_mean, r.cg_iterations_mean, r.threads, c.paper_ms);
    md += fmt::format("| {} | {} | {:.2f} ({:.2f}) | {:.1f} | {:.1f} | {} | up to {} ms | {} |\n",
                      c.characters, c.density, r.ms_median, r.ms_mean, r.contacts_mean, r.cg_iterations_mean,
                      r.threads, c.paper_ms, c.target);
  }
  write_file_atomic(dir / "timing.csv", csv);
  md += fmt::format(
      "\n{} timed steps after {} warm-up steps on the swaying-crowd fixture (`crowdlab bench "
      "correct`); wall-clock times depend on the machine and its load and are not checked.\n\n",
      size.timing_steps, size.timing_warmup);
}

/// The method main effect of one composite in the report's stats/<measure>.json.
void check_study(const fs::path& report_dir, ReproductionChecks& checks, std::string& md) {
  md += "| composite | F(method) | p | mean baseline | mean ours |\n|---|---|---|---|---|\n";
  for (const std::string measure : {"Q_CR", "Q_CA", "Q_OR"}) {
    std::ifstream in(report_dir / "stats" / (measure + ".json"));
    if (!in) throw RuntimeError("the study report has no stats for " + measure);
    const json stats = json::parse(in);
    double p = kNaN, f = kNaN, mean_base = kNaN, mean_ours = kNaN;
    for (const json& e : stats.at("anova").at("effects"))
      if (e.at("effect") == "method") {
        f = e.at("F").is_number() ? e.at("F").get<double>() : kNaN;
        const bool gg = e.at("mauchly_p").is_number() && e.at("mauchly_p").get<double>() < 0.05;
        const json& pv = gg ? e.at("p_gg") : e.at("p");
        p = pv.is_number() ? pv.get<double>() : kNaN;
      }
    for (const json& ph : stats.at("posthoc"))
      if (ph.at("effect") == "method")
        for (const json& pair : ph.at("comparisons")) {
          const bool base_first = pair.at("a") == "baseline";
          mean_base = (base_first ? pair.at("mean_a") : pair.at("mean_b")).get<double>();
          mean_ours = (base_first ? pair.at("mean_b") : pair.at("mean_a")).get<double>();
        }
    md += fmt::format("| {} | {} | {} | {} | {} |\n", measure, repro_number(f), repro_number(p),
                      repro_number(mean_base), repro_number(mean_ours));
    checks.within("study." + measure + ".method_p", measure + ": p of the method main effect", p, 0.0, 0.05,
                  "§4.4.4: significant main effect of method on every composite");
    checks.within("study." + measure + ".ours_minus_baseline", measure + ": mean ours - mean baseline",
                  mean_ours - mean_base, 0.0, kInf, "§4.4.4: Ours rated higher (H1)");
  }
}

}  // namespace

void reproduce_gomez2024(const ReproduceOptions& o) {
  const Size size = size_of(o);
  const fs::path dir = fs::absolute(o.out);
  fs::create_directories(dir);
  ReproductionChecks checks;
  std::string md = fmt::format(
      "# Reproduction of Gómez et al. 2024 (seed 000)\n\nGenerated by `crowdlab reproduce gomez2024{}`: "
      "clips of {} s at {} fps (no video), {} simulated observers.\n\n",
      o.quick ? " --quick" : "", size.duration_s, size.fps, size.observers);

  auto resize = [&](YAML::Node& root) {
    root["duration_s"] = size.duration_s;
    root["fps"] = size.fps;
  };
  // The mesh-level measures (rendered vertices inside another character, proxy coverage) are checked on
  // the paper's 20 s clips only (correction_quality_section), and they are about three quarters of the
  // metrics stage on these MPFB2 crowds: shorter runs leave them out (issue 31: the --quick test's time).
  const bool full_length = size.duration_s >= 20.0;
  const SpecRun stationary =
      run_spec_variant(kSpecGomez2024Stationary, dir, "stationary", o.force, resize, full_length, true);
  const SpecRun corridor =
      run_spec_variant(kSpecGomez2024Nonstationary, dir, "corridor", o.force, resize, full_length, true);
  std::vector<OverlapRow> rows;
  add_overlap_rows(stationary, "stationary", rows);
  add_overlap_rows(corridor, "corridor", rows);
  write_overlap_vs_density(rows, dir / "fig3");
  check_overlap(rows, size.min_reduction, checks, md);
  std::string quality_csv;
  correction_quality_section(stationary, "stationary", rows, full_length, true, checks, md, quality_csv);
  correction_quality_section(corridor, "corridor", rows, full_length, false, checks, md, quality_csv);
  write_file_atomic(dir / "correction_quality.csv", quality_csv);
  md +=
      "\nMeasures as defined in docs/correction.md (framework/metrics/foot_contact_quality.hpp); the "
      "baseline "
      "rows measure the input against itself (its own stance-foot drift, depth and ground contact). The "
      "depth "
      "and overlap targets are checked on the paper's 20 s clips only: a short clip is mostly the "
      "corrector's "
      "start-up transient.\n\n";

  stimulus_check_section(stationary, "stationary (§4.4 stage 1)", md);
  stimulus_check_section(corridor, "corridor (§4.4 stage 2)", md);

  damping_section(dir, checks, md);
  if (!o.skip_timing) timing_section(size, dir, md);

  md += fmt::format(
      "## Study analysis on simulated observers (stationary stage, §4.4)\n\n"
      "{} simulated observers answered the 40 stationary conditions (6 Likert items) from each "
      "clip's measured overlap (study_ui/simulated_observer.hpp); full report: "
      "[study_report/report.md](study_report/report.md).\n\n",
      size.observers);
  const std::string report =
      simulate_study_and_report(stationary, study::ObserverModel{}, size.observers, stationary.spec.seed,
                                dir / "study", dir / "study_report");
  check_study(dir / "study_report", checks, md);
  md +=
      "\nThe paper (30 participants) found main effects of method on all three composites, ours higher; the "
      "simulated observers' method effect is part of their model, so this checks that the pipeline (trial "
      "lists, logging, composites, RM-ANOVA) recovers it, not the human result.\n\n";

  checks.finish(dir, "reproduce gomez2024", md);
}

}  // namespace crowdlab::cli
