#pragma once
// The stimulus check of a finished run as a table (Markdown): one row per clip of manifest.csv with the
// five measures (stimuli/stimulus_check.hpp) and what misses the spec's render.check thresholds.
// Printed by `crowdlab check-stimuli DIR` and placed beside the tables of `reproduce gomez2024`.
#include <string>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::cli {

struct StimulusCheckTable {
  std::string markdown;  ///< header, one row per clip (practice clips included, marked)
  int clips = 0;         ///< rows
  int failed = 0;        ///< rows with at least one threshold missed
  int unmeasured = 0;    ///< rows without any measure (a manifest from before the check)
};

/// The table of `manifest`, judged by `spec`'s render.check (loops: protocol.loop_video; pixel limits
/// scaled by each clip's height). Rows without a viewpoint or method factor judge as a non-baseline clip
/// seen from no named viewpoint.
StimulusCheckTable stimulus_check_table(const StimulusManifest& manifest, const ExperimentSpec& spec);

}  // namespace crowdlab::cli
