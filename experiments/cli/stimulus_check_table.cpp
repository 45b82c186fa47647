#include "experiments/cli/stimulus_check_table.hpp"

#include <fmt/format.h>

#include "stimuli/stimulus_check.hpp"

namespace crowdlab::cli {
namespace {

std::string factor(const StimulusEntry& e, const std::string& name) {
  const auto it = e.factors.find(name);
  return it == e.factors.end() ? "-" : it->second;
}

/// A measure with `digits` decimals (scaled by `scale`), or "-" when unknown.
std::string cell(double v, int digits, double scale = 1.0) {
  return v >= 0.0 ? fmt::format("{:.{}f}", v * scale, digits) : "-";
}

}  // namespace

StimulusCheckTable stimulus_check_table(const StimulusManifest& manifest, const ExperimentSpec& spec) {
  StimulusCheckTable t;
  t.markdown =
      "| clip | viewpoint | method | density | crowd in frame (min) | character height (px, median) | "
      "frames with overlap | overlap pixels (mean %) | loop seam (x median step) | check |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n";
  for (const StimulusEntry& e : manifest.entries) {
    const StimulusCheck& c = e.check;
    const stimuli::ClipRole role{find_viewpoint(factor(e, "viewpoint")), factor(e, "method") == "baseline",
                                 spec.protocol.loop_video, e.height > 0 ? e.height : spec.render.height};
    const bool measured = c.crowd_in_frame_min >= 0 || c.character_height_px >= 0 ||
                          c.overlap_frame_share >= 0 || c.seam_step_ratio >= 0;
    std::string verdict = "ok";
    if (!measured) {
      verdict = "not measured";
      ++t.unmeasured;
    } else {
      const std::vector<std::string> failures = stimuli::stimulus_check_failures(c, spec.render.check, role);
      if (!failures.empty()) {
        ++t.failed;
        verdict.clear();
        for (const std::string& f : failures) verdict += (verdict.empty() ? "" : "; ") + f;
      }
    }
    t.markdown += fmt::format(
        "| {}{} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n", e.id, e.practice ? " (practice)" : "",
        factor(e, "viewpoint"), factor(e, "method"), factor(e, "density"), cell(c.crowd_in_frame_min, 3),
        cell(c.character_height_px, 0), cell(c.overlap_frame_share, 2),
        cell(c.overlap_pixel_fraction, 3, 100.0),
        role.loops ? cell(c.seam_step_ratio, 2) : cell(c.seam_step_ratio, 2) + " (not looped)", verdict);
    ++t.clips;
  }
  return t;
}

}  // namespace crowdlab::cli
