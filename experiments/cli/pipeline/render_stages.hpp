#pragma once
// `crowdlab run` composed: the framework's run pipeline (framework/pipeline/run_experiment.hpp) with the
// stimuli module's presentation stages (stimuli/presentation_stages.hpp: render, contact sheet) and
// every library's version in the provenance sidecars.
#include "framework/pipeline/run_experiment.hpp"

namespace crowdlab::cli {

/// run_experiment() with the renderer's stages and every library's version in the sidecars. Every clip
/// gets the stimulus check (stimuli/stimulus_check.hpp) in its sidecar and manifest row; a clip outside
/// the spec's render.check is logged as a warning, and with `strict` the run then throws RuntimeError
/// (after writing everything, manifest included).
/// With `check_only` (`run --check-only`) every clip's stimulus check is measured as in a rendered run,
/// into DIR/conditions/<id>/stimulus_check.json and the manifest, and no clip or contact sheet is made
/// (stimuli::check_only_stages).
RunSummary run_with_stimuli(const ExperimentSpec& spec, const RunOptions& options, bool strict = false,
                            bool check_only = false);

}  // namespace crowdlab::cli
