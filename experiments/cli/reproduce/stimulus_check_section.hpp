#pragma once
// `reproduce gomez2024`'s stimulus-check table (issue 28): the stimulus check of every condition of a
// spec run beside the reproduction's other tables. The reproduction runs without video, with `run
// --check-only`'s stage for its geometric measures (crowd in frame, character height, loop seam;
// stimuli/stimulus_check.hpp: the cameras `run` frames its clips with; run_spec_variant's
// stimulus_check); the overlap columns need drawn frames (`crowdlab run` + `crowdlab check-stimuli`, or
// `run --check-only`).
#include <string>

#include "experiments/cli/reproduce/reproduce_common.hpp"

namespace crowdlab::cli {

/// Appends "## Stimulus check: <title>" and the table (stimulus_check_table.hpp) to `md`; returns the
/// number of clips outside the spec's render.check.
int stimulus_check_section(const SpecRun& run, const std::string& title, std::string& md);

}  // namespace crowdlab::cli
