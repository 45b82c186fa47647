#include "framework/correction/correct_crowd.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "framework/core/blend_poses.hpp"
#include "framework/correction/corrector.hpp"

namespace crowdlab {
namespace {

/// Largest horizontal root distance between the last and the first frame under which a crowd loops (m).
constexpr double kLoopRootM = 0.1;

/// True when every character's root ends where it started (a stationary crowd that loops).
bool input_loops(const CrowdAnimation& crowd) {
  for (const CharacterAnimation& c : crowd.characters) {
    const Vec3 d = c.frames.back().root_position_m - c.frames.front().root_position_m;
    if (std::hypot(d.x(), d.z()) > kLoopRootM) return false;
  }
  return true;
}

}  // namespace

CrowdAnimation correct_crowd(const CrowdAnimation& crowd, const CorrectorParams& params, Progress* progress,
                             CorrectionReport* report) {
  validate_crowd(crowd, "correct_crowd");
  std::vector<BodyShape> shapes;
  shapes.reserve(crowd.characters.size());
  for (const CharacterAnimation& ch : crowd.characters) shapes.push_back(ch.shape);
  Corrector corrector(std::move(shapes), params, crowd.environment, crowd.meta.fps);

  CrowdAnimation out = crowd;
  const size_t n = crowd.characters.size();
  const int frames = crowd.frame_count();
  std::vector<Pose> targets(n);
  CorrectionReport r;
  r.frames = frames;
  double contacts = 0.0, iterations = 0.0;
  const int preroll =
      frames > 1 && params.loop_preroll_s > 0.0 && input_loops(crowd)
          ? std::min(frames - 1, static_cast<int>(std::lround(params.loop_preroll_s * crowd.meta.fps)))
          : 0;
  r.preroll_frames = preroll;
  if (frames > 0) {
    for (size_t c = 0; c < n; ++c)
      targets[c] =
          crowd.characters[c].frames[static_cast<size_t>(frames - preroll) % static_cast<size_t>(frames)];
    // Feet are free while the crowd settles (the first frame's overlaps are pushed out, feet included);
    // holds start on the first output frame.
    corrector.set_foot_holds(false);
    for (int k = 0; k < params.settle_steps; ++k) {
      corrector.step(targets);
      if (corrector.last_stats().rejected) ++r.rejected_steps;
    }
    r.settle_steps = params.settle_steps;
    corrector.set_foot_holds(true);
  }
  // The pre-roll's output of frames N - P .. N - 1, per character: the clip's end blends into it.
  std::vector<std::vector<Pose>> preroll_out(n);
  for (int f = frames - preroll; f < frames && preroll > 0; ++f) {
    for (size_t c = 0; c < n; ++c) targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
    const std::vector<Pose> corrected = corrector.step(targets);
    for (size_t c = 0; c < n; ++c) preroll_out[c].push_back(corrected[c]);
    if (corrector.last_stats().rejected) ++r.rejected_steps;
  }
  for (int f = 0; f < frames; ++f) {
    for (size_t c = 0; c < n; ++c) targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
    const std::vector<Pose> corrected = corrector.step(targets);
    for (size_t c = 0; c < n; ++c) out.characters[c].frames[static_cast<size_t>(f)] = corrected[c];
    const StepStats& st = corrector.last_stats();
    contacts += st.contacts();
    iterations += st.cg_iterations;
    if (st.rejected) ++r.rejected_steps;
    if (!st.converged) ++r.unconverged_steps;
    if (progress) progress->advance();
  }
  // Frame 0 continued from the pre-roll's last state; the clip's last P frames blend into the pre-roll's
  // (weight rising 0 -> 1, raised cosine), so the last frame is the pre-roll's and the loop closes.
  for (int k = 0; k < preroll; ++k) {
    const double w = preroll > 1 ? 0.5 - 0.5 * std::cos(std::numbers::pi * k / (preroll - 1)) : 1.0;
    const size_t f = static_cast<size_t>(frames - preroll + k);
    for (size_t c = 0; c < n; ++c)
      out.characters[c].frames[f] =
          blend_poses(out.characters[c].frames[f], preroll_out[c][static_cast<size_t>(k)], w);
  }
  r.contacts_mean = frames > 0 ? contacts / frames : 0.0;
  r.cg_iterations_mean = frames > 0 ? iterations / frames : 0.0;
  if (r.rejected_steps > 0)
    spdlog::warn(
        "correct_crowd: {} of {} steps were rejected (solver did not converge); the last stable state was "
        "kept",
        r.rejected_steps, frames);
  if (report) *report = r;
  return out;
}

}  // namespace crowdlab
