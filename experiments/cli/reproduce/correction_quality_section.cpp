#include "experiments/cli/reproduce/correction_quality_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <tuple>

#include "framework/core/error.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "framework/metrics/correction_quality.hpp"

namespace crowdlab::cli {
namespace {
namespace fs = std::filesystem;

/// The crowd key of a condition id ("density-2.22_viewpoint-V1_method-ours_rep-1" ->
/// "density-2.22_rep-1"): the id without its presentation factors (pipeline/crowd_key.hpp).
std::string key_of(const std::string& id) {
  std::string key;
  size_t start = 0;
  while (start <= id.size()) {
    const size_t end = std::min(id.find('_', start), id.size());
    const std::string part = id.substr(start, end - start);
    if (part.rfind("viewpoint-", 0) != 0 && part.rfind("method-", 0) != 0)
      key += (key.empty() ? "" : "_") + part;
    start = end + 1;
  }
  return key;
}

std::string row(const std::string& scenario, double density, const char* method, double reduction,
                const CorrectionQuality& q) {
  return fmt::format("| {} | {} | {} | {:.1f} % | {:.1f} | {:.1f} | {} | {:.2f} | {:.1f} |\n", scenario,
                     density, method, 100 * reduction, 1000 * q.depth_p99_m, 1000 * q.feet.stance_drift_p99_m,
                     q.feet.foot_pops, q.rotation_dev_mean_deg, 1000 * q.feet.ground_penetration_max_m);
}

}  // namespace

void correction_quality_section(const SpecRun& run, const std::string& scenario,
                                const std::vector<OverlapRow>& rows, bool full_length, bool first,
                                ReproductionChecks& checks, std::string& md, std::string& csv) {
  if (first) {
    md +=
        "## Correction quality (issue 18): baseline and ours against the baseline\n\n"
        "| scenario | density (/m²) | method | overlap reduction | p99 depth (mm) | stance-foot drift p99 "
        "(mm) | "
        "foot pops | mean joint deviation (deg) | feet below ground, max (mm) "
        "|\n|---|---|---|---|---|---|---|---|---|\n";
    csv =
        "scenario,density,method,overlap_reduction,depth_p99_m,depth_max_m,stance_foot_drift_p99_m,"
        "stance_foot_drift_max_m,foot_pops,rotation_dev_mean_deg,foot_ground_penetration_max_m,"
        "foot_float_p99_m\n";
  }
  std::map<double, std::string> keys;  // density -> crowd key (viewpoints and methods share a crowd)
  for (const StimulusEntry& e : run.manifest.entries)
    if (!e.practice) keys.emplace(std::stod(e.factors.at("density")), key_of(e.id));
  for (const auto& [density, key] : keys) {
    const fs::path dir = run.run_dir / "crowds" / key;
    const CrowdAnimation baseline = read_crowd_glb((dir / "baseline.glb").string());
    const CrowdAnimation ours = read_crowd_glb((dir / "ours.glb").string());
    const CorrectionQuality qb = measure_correction_quality(baseline, baseline);
    const CorrectionQuality qo = measure_correction_quality(baseline, ours);
    const double base_l = overlap_of(rows, scenario, density, "baseline");
    const double reduction = base_l > 0 ? 1.0 - overlap_of(rows, scenario, density, "ours") / base_l : 0.0;
    md += row(scenario, density, "baseline", 0.0, qb) + row(scenario, density, "ours", reduction, qo);
    for (const auto& [method, q, red] : {std::tuple{"baseline", qb, 0.0}, std::tuple{"ours", qo, reduction}})
      csv +=
          fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", scenario, density, method, red, q.depth_p99_m,
                      q.depth_max_m, q.feet.stance_drift_p99_m, q.feet.stance_drift_max_m, q.feet.foot_pops,
                      q.rotation_dev_mean_deg, q.feet.ground_penetration_max_m, q.feet.float_p99_m);
    const std::string at = fmt::format("{}@{}", scenario, density);
    const std::string ref = "issue 18 target for ours";
    checks.within("quality." + at + ".stance_drift_p99_m", at + ": stance-foot drift p99 of ours (m)",
                  qo.feet.stance_drift_p99_m, 0.0, 0.010, ref + ": <= 10 mm");
    checks.within("quality." + at + ".foot_pops", at + ": foot pops of ours (frames)", qo.feet.foot_pops, 0.0,
                  0.0, ref + ": 0");
    checks.within("quality." + at + ".rotation_dev_mean_deg", at + ": mean joint deviation of ours (deg)",
                  qo.rotation_dev_mean_deg, 0.0, 10.0, ref + ": <= 10 deg");
    if (!full_length) continue;  // depth and overlap: 20 s clips only (see the header)
    checks.within("quality." + at + ".depth_p99_m", at + ": p99 inter-body depth of ours (m)", qo.depth_p99_m,
                  0.0, 0.010, ref + ": <= 10 mm");
    checks.within("quality." + at + ".overlap_reduction", at + ": overlap reduction of ours", reduction, 0.98,
                  1.0, ref + ": >= 98 % (20 s clips)");
  }
}

}  // namespace crowdlab::cli
