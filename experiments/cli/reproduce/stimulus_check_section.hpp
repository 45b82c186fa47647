#pragma once
// `reproduce gomez2024`'s stimulus-check table (issue 28): the stimulus check of every condition of a
// spec run beside the reproduction's other tables. The reproduction runs without video, so only the
// geometric measures are taken here (crowd in frame, character height, loop seam; stimuli/
// stimulus_check.hpp), from each condition's crowd file and a camera framed from its baseline's root
// motion (shared by both methods, as in `run`); the overlap columns need the rendered clips
// (`crowdlab run` + `crowdlab check-stimuli`).
#include <string>

#include "experiments/cli/reproduce/reproduce_common.hpp"

namespace crowdlab::cli {

/// Appends "## Stimulus check: <title>" and the table (stimulus_check_table.hpp) to `md`; returns the
/// number of clips outside the spec's render.check.
int stimulus_check_section(const SpecRun& run, const std::string& title, std::string& md);

}  // namespace crowdlab::cli
