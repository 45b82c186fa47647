#pragma once
// `reproduce gomez2024`'s correction-quality table (issue 18): for every density of a scenario, the
// baseline and the corrected crowd of the run measured against the baseline, as the run's metrics stage
// wrote them into each condition's metrics.json (framework/metrics/correction_quality.hpp: overlap
// reduction, p99 inter-body depth, stance-foot drift, foot pops, joint deviation, feet below the ground,
// planted feet above the input's; issue 27: free-limb deviation, joint flips, environment penetration and,
// for bodies with a rendered mesh, mesh-level overlap and proxy coverage), with a check per target: drift
// p99 <= 10 mm, 0 pops, mean deviation <= 10 deg, free-limb deviation p99 <= 2 deg and max <= 5 deg and, on
// the paper's 20 s clips only, depth p99 <= 10 mm, overlap reduction >= 98 % and issue 27's other targets
// (0 flips, environment p99 <= 5 mm, planted-foot float p99 and feet below ground <= 10 mm, ours' share
// of rendered vertices inside another character <= 5 % of the baseline's, >= 99 % of rendered vertices
// within 5 mm of their capsules; absent meshes fail the last two). A short clip is mostly
// the corrector's start-up transient (it starts on the uncorrected first frame): on the 1 s clips of
// --quick the p99 depth was 18.6 / 28.2 mm at two densities, 3.8-9.9 mm at the others.
#include <string>
#include <vector>

#include "experiments/cli/figures/overlap_vs_density.hpp"
#include "experiments/cli/reproduce/reproduce_common.hpp"
#include "experiments/cli/reproduce/reproduction_checks.hpp"

namespace crowdlab::cli {

/// Appends the scenario's rows to `md` (the table header when `first`) and to `csv`, and the checks to
/// `checks`. The overlap reductions come from `rows` (Figure 3's data); `full_length`: the clips are the
/// paper's 20 s (the depth and overlap targets are checked only then).
void correction_quality_section(const SpecRun& run, const std::string& scenario,
                                const std::vector<OverlapRow>& rows, bool full_length, bool first,
                                ReproductionChecks& checks, std::string& md, std::string& csv);

}  // namespace crowdlab::cli
