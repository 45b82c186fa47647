#pragma once
// `crowdlab run` composed: the framework's run pipeline (framework/pipeline/run_experiment.hpp) with the
// stimuli module's presentation stages (stimuli/presentation_stages.hpp: render, contact sheet) and
// every library's version in the provenance sidecars.
#include "framework/pipeline/run_experiment.hpp"

namespace crowdlab::cli {

/// run_experiment() with the renderer's stages and every library's version in the sidecars.
RunSummary run_with_stimuli(const ExperimentSpec& spec, const RunOptions& options);

}  // namespace crowdlab::cli
