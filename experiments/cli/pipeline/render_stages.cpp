#include "experiments/cli/pipeline/render_stages.hpp"

#include <string>
#include <vector>

#include "experiments/cli/pipeline/library_versions.hpp"
#include "framework/core/error.hpp"
#include "stimuli/presentation_stages.hpp"

namespace crowdlab::cli {

RunSummary run_with_stimuli(const ExperimentSpec& spec, const RunOptions& options, bool strict,
                            bool check_only) {
  RunOptions with_versions = options;
  with_versions.libraries = library_versions();
  std::vector<std::string> failed;
  const RunSummary summary = run_experiment(
      spec, with_versions,
      check_only ? stimuli::check_only_stages(spec, &failed) : stimuli::presentation_stages(spec, &failed));
  if (strict && !failed.empty()) {
    std::string list;
    for (const std::string& f : failed) list += "\n  " + f;
    throw RuntimeError(
        "run --strict: " + std::to_string(failed.size()) +
        " stimulus check(s) outside render.check (the run's outputs and manifest are written):" + list);
  }
  return summary;
}

}  // namespace crowdlab::cli
