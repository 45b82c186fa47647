#include "experiments/cli/reproduce/stimulus_check_section.hpp"

#include <fmt/format.h>

#include <map>

#include "experiments/cli/stimulus_check_table.hpp"
#include "framework/io/read_crowd_glb.hpp"
#include "stimuli/crowd_extent.hpp"
#include "stimuli/stimulus_check.hpp"

namespace crowdlab::cli {
namespace fs = std::filesystem;

int stimulus_check_section(const SpecRun& run, const std::string& title, std::string& md) {
  StimulusManifest measured = run.manifest;
  std::map<std::string, stimuli::CrowdExtent> extents;  // baseline condition id -> its framing
  for (StimulusEntry& e : measured.entries) {
    const auto viewpoint_level = e.factors.find("viewpoint");
    if (viewpoint_level == e.factors.end()) continue;
    const std::optional<ViewpointId> viewpoint = find_viewpoint(viewpoint_level->second);
    if (!viewpoint) continue;
    // The baseline of the same condition frames both methods.
    std::string baseline_id = e.id;
    if (const size_t at = baseline_id.find("method-ours"); at != std::string::npos)
      baseline_id.replace(at, 11, "method-baseline");
    if (!extents.count(baseline_id)) {
      const CrowdAnimation baseline =
          read_crowd_glb((run.run_dir / "conditions" / baseline_id / "crowd.glb").string());
      extents.emplace(baseline_id,
                      stimuli::crowd_extent(stimuli::character_tracks(baseline), baseline.meta.fps));
    }
    const CrowdAnimation crowd = read_crowd_glb((run.run_dir / "conditions" / e.id / "crowd.glb").string());
    const stimuli::Viewpoint view(*viewpoint, extents.at(baseline_id), run.spec.render.width,
                                  run.spec.render.height, run.spec.render.viewpoint_overrides);
    e.check = stimuli::measure_stimulus_geometry(crowd, view, crowd.frame_count());
    e.height = run.spec.render.height;
  }
  const StimulusCheckTable table = stimulus_check_table(measured, run.spec);
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
