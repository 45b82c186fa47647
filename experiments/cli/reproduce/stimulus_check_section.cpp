#include "experiments/cli/reproduce/stimulus_check_section.hpp"

#include <fmt/format.h>

#include "experiments/cli/stimulus_check_table.hpp"

namespace crowdlab::cli {

int stimulus_check_section(const SpecRun& run, const std::string& title, std::string& md) {
  const StimulusCheckTable table = stimulus_check_table(run.manifest, run.spec);
  md += fmt::format(
      "## Stimulus check: {}\n\nThe clips' geometry at {}x{} (docs/stimuli.md, \"Stimulus check\"; the "
      "overlap "
      "columns need the rendered clips: `crowdlab run` then `crowdlab check-stimuli`). Loops judged: "
      "{}.\n\n{}\n"
      "{} clip(s), {} outside render.check.\n\n",
      title, run.spec.render.width, run.spec.render.height,
      run.spec.protocol.loop_video ? "yes" : "no (clips play once)", table.markdown, table.clips,
      table.failed);
  return table.failed;
}

}  // namespace crowdlab::cli
