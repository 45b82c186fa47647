#include "experiments/cli/pipeline/render_stages.hpp"

#include "experiments/cli/pipeline/library_versions.hpp"
#include "stimuli/presentation_stages.hpp"

namespace crowdlab::cli {

RunSummary run_with_stimuli(const ExperimentSpec& spec, const RunOptions& options) {
  RunOptions with_versions = options;
  with_versions.libraries = library_versions();
  return run_experiment(spec, with_versions, stimuli::presentation_stages(spec));
}

}  // namespace crowdlab::cli
