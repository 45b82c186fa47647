#include "experiments/cli/reproduce/correction_quality_section.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "framework/core/error.hpp"

namespace crowdlab::cli {
namespace {
using nlohmann::json;

/// A number of the quality object, or NaN (an empty csv cell, a failed check) when it is absent: the
/// mesh-level measures exist only for bodies with a rendered mesh, the added ground penetration only in
/// metrics written since issue 27's session 16.
double number_or_nan(const json& q, const char* key) {
  return q.contains(key) ? q.at(key).get<double>() : std::numeric_limits<double>::quiet_NaN();
}

/// One table row from a condition's metrics.json "correction_quality" object (the metrics stage of
/// `crowdlab run` measures every crowd against its baseline: framework/pipeline/crowd_group.hpp).
std::string row(const std::string& scenario, double density, const char* method, double reduction,
                const json& q) {
  return fmt::format(
      "| {} | {} | {} | {:.1f} % | {:.1f} | {:.1f} | {} | {:.2f} | {:.1f} / {:.1f} | {:.1f} | {:.2f} / "
      "{:.2f} | {} | "
      "{:.1f} | {} | {} |\n",
      scenario, density, method, 100 * reduction, 1000 * q.at("depth_p99_m").get<double>(),
      1000 * q.at("stance_foot_drift_p99_m").get<double>(), q.at("foot_pops").get<int>(),
      q.at("rotation_dev_mean_deg").get<double>(), 1000 * q.at("foot_ground_penetration_max_m").get<double>(),
      1000 * number_or_nan(q, "foot_ground_penetration_added_max_m"),
      1000 * q.at("foot_float_p99_m").get<double>(), q.at("free_limb_dev_p99_deg").get<double>(),
      q.at("free_limb_dev_max_deg").get<double>(), q.at("joint_flips").get<long>(),
      1000 * q.at("env_penetration_p99_m").get<double>(),
      q.contains("mesh_overlap_fraction")
          ? fmt::format("{:.4f} %", 100 * q.at("mesh_overlap_fraction").get<double>())
          : "-",
      q.contains("proxy_coverage") ? fmt::format("{:.2f} %", 100 * q.at("proxy_coverage").get<double>())
                                   : "-");
}

std::string cell(double v) {
  return std::isnan(v) ? std::string() : fmt::format("{}", v);
}

/// The "correction_quality" object of an entry's metrics, or a RuntimeError naming the condition.
json quality_of(const SpecRun& run, const StimulusEntry& e) {
  const json m = entry_metrics(run, e);
  if (!m.contains("correction_quality"))
    throw RuntimeError("metrics of condition " + e.id +
                       " lack correction_quality (written by an older crowdlab: "
                       "rerun with --force)");
  return m.at("correction_quality");
}

}  // namespace

void correction_quality_section(const SpecRun& run, const std::string& scenario,
                                const std::vector<OverlapRow>& rows, bool full_length, bool first,
                                ReproductionChecks& checks, std::string& md, std::string& csv) {
  if (first) {
    md +=
        "## Correction quality (issue 18): baseline and ours against the baseline\n\n"
        "| scenario | density (/m²) | method | overlap reduction | p99 depth (mm) | stance-foot drift p99 "
        "(mm) | foot pops | mean joint deviation (deg) | feet below ground, max: below y = 0 / added by the "
        "correction (mm) | planted feet above "
        "the input's, p99 (mm) | free-limb deviation p99 / max (deg) | joint flips | environment "
        "penetration p99 (mm) | rendered vertices inside another character | rendered vertices within 5 mm "
        "of their capsules |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    csv =
        "scenario,density,method,overlap_reduction,depth_p99_m,depth_max_m,stance_foot_drift_p99_m,"
        "stance_foot_drift_max_m,foot_pops,rotation_dev_mean_deg,foot_ground_penetration_max_m,"
        "foot_ground_penetration_added_max_m,foot_float_p99_m,free_limb_dev_p99_deg,free_limb_dev_max_deg,"
        "joint_flips,env_penetration_p99_m,"
        "env_penetration_max_m,mesh_overlap_fraction,mesh_overlap_depth_p99_m,proxy_coverage,"
        "proxy_outside_p99_m\n";
  }
  // density -> method -> quality (viewpoints share one crowd: the first entry of each wins)
  std::map<double, std::map<std::string, json>> by_density;
  for (const StimulusEntry& e : run.manifest.entries)
    if (!e.practice) {
      auto& slot = by_density[std::stod(e.factors.at("density"))];
      const std::string& method = e.factors.at("method");
      if (!slot.count(method)) slot[method] = quality_of(run, e);
    }
  for (const auto& [density, methods] : by_density) {
    const json& qb = methods.at("baseline");
    const json& qo = methods.at("ours");
    const double base_l = overlap_of(rows, scenario, density, "baseline");
    const double reduction = base_l > 0 ? 1.0 - overlap_of(rows, scenario, density, "ours") / base_l : 0.0;
    md += row(scenario, density, "baseline", 0.0, qb) + row(scenario, density, "ours", reduction, qo);
    for (const auto& [method, q, red] : {std::tuple{"baseline", qb, 0.0}, std::tuple{"ours", qo, reduction}})
      csv += fmt::format(
          "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", scenario, density, method,
          red, q.at("depth_p99_m").get<double>(), q.at("depth_max_m").get<double>(),
          q.at("stance_foot_drift_p99_m").get<double>(), q.at("stance_foot_drift_max_m").get<double>(),
          q.at("foot_pops").get<int>(), q.at("rotation_dev_mean_deg").get<double>(),
          q.at("foot_ground_penetration_max_m").get<double>(),
          cell(number_or_nan(q, "foot_ground_penetration_added_max_m")),
          q.at("foot_float_p99_m").get<double>(), q.at("free_limb_dev_p99_deg").get<double>(),
          q.at("free_limb_dev_max_deg").get<double>(), q.at("joint_flips").get<long>(),
          q.at("env_penetration_p99_m").get<double>(), q.at("env_penetration_max_m").get<double>(),
          cell(number_or_nan(q, "mesh_overlap_fraction")), cell(number_or_nan(q, "mesh_overlap_depth_p99_m")),
          cell(number_or_nan(q, "proxy_coverage")), cell(number_or_nan(q, "proxy_outside_p99_m")));
    const std::string at = fmt::format("{}@{}", scenario, density);
    const std::string ref = "issue 18 target for ours";
    checks.within("quality." + at + ".stance_drift_p99_m", at + ": stance-foot drift p99 of ours (m)",
                  qo.at("stance_foot_drift_p99_m").get<double>(), 0.0, 0.010, ref + ": <= 10 mm");
    checks.within("quality." + at + ".foot_pops", at + ": foot pops of ours (frames)",
                  qo.at("foot_pops").get<int>(), 0.0, 0.0, ref + ": 0");
    checks.within("quality." + at + ".rotation_dev_mean_deg", at + ": mean joint deviation of ours (deg)",
                  qo.at("rotation_dev_mean_deg").get<double>(), 0.0, 10.0, ref + ": <= 10 deg");
    const std::string ref27 = "issue 27 target for ours";
    checks.within("quality." + at + ".free_limb_dev_p99_deg", at + ": free-limb deviation p99 of ours (deg)",
                  qo.at("free_limb_dev_p99_deg").get<double>(), 0.0, 2.0, ref27 + ": <= 2 deg");
    checks.within("quality." + at + ".free_limb_dev_max_deg", at + ": free-limb deviation max of ours (deg)",
                  qo.at("free_limb_dev_max_deg").get<double>(), 0.0, 5.0, ref27 + ": <= 5 deg");
    if (!full_length)
      continue;  // depth, overlap and the rest of issue 27's: 20 s clips only (see the header)
    checks.within("quality." + at + ".joint_flips", at + ": joint flips of ours (joint-frames)",
                  static_cast<double>(qo.at("joint_flips").get<long>()), 0.0, 0.0, ref27 + ": 0");
    checks.within("quality." + at + ".env_penetration_p99_m",
                  at + ": environment penetration p99 of ours (m)",
                  qo.at("env_penetration_p99_m").get<double>(), 0.0, 0.005, ref27 + ": <= 5 mm");
    checks.within("quality." + at + ".foot_float_p99_m", at + ": planted feet above the input's, p99 (m)",
                  qo.at("foot_float_p99_m").get<double>(), 0.0, 0.010, ref27 + ": <= 10 mm");
    checks.within("quality." + at + ".foot_ground_penetration_max_m", at + ": feet below the ground, max (m)",
                  qo.at("foot_ground_penetration_max_m").get<double>(), 0.0, 0.010, ref27 + ": <= 10 mm");
    checks.within("quality." + at + ".foot_ground_penetration_added_max_m",
                  at + ": feet below min(0, the input's foot), added by ours, max (m)",
                  number_or_nan(qo, "foot_ground_penetration_added_max_m"), 0.0, 0.010,
                  ref27 + ": <= 10 mm (what the input's own feet leave)");
    const double mesh_ours = number_or_nan(qo, "mesh_overlap_fraction");
    const double mesh_base = number_or_nan(qb, "mesh_overlap_fraction");
    checks.within("quality." + at + ".mesh_overlap_ratio",
                  at + ": rendered vertices inside another character, ours / baseline",
                  mesh_base > 0 ? mesh_ours / mesh_base : (mesh_ours == 0 ? 0.0 : mesh_ours), 0.0, 0.05,
                  ref27 + ": <= 5 % of the baseline's");
    checks.within("quality." + at + ".proxy_coverage",
                  at + ": rendered vertices within 5 mm of their capsules",
                  number_or_nan(qo, "proxy_coverage"), 0.99, 1.0, ref27 + ": >= 99 %");
    checks.within("quality." + at + ".depth_p99_m", at + ": p99 inter-body depth of ours (m)",
                  qo.at("depth_p99_m").get<double>(), 0.0, 0.010, ref + ": <= 10 mm");
    checks.within("quality." + at + ".overlap_reduction", at + ": overlap reduction of ours", reduction, 0.98,
                  1.0, ref + ": >= 98 % (20 s clips)");
  }
}

}  // namespace crowdlab::cli
