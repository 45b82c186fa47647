#include "framework/correction/correct_crowd.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include "framework/core/crowd_penetration_depth.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/correction/blend_keeping_planted_feet.hpp"
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

/// Deepest inter-body penetration (m) over frames [first, last) of a crowd.
double deepest(const CrowdAnimation& crowd, int first, int last) {
  double depth = 0.0;
  std::vector<WorldCapsules> bodies(crowd.characters.size());
  for (int f = first; f < last; ++f) {
    for (size_t c = 0; c < bodies.size(); ++c)
      bodies[c] =
          world_capsules(crowd.characters[c].shape, crowd.characters[c].frames[static_cast<size_t>(f)]);
    depth = std::max(depth, deepest_crowd_penetration(bodies));
  }
  return depth;
}

/// Penetration a loop closure may add beyond the unclosed clip's deepest (m): below what shows.
constexpr double kClosureDepthSlackM = 0.001;

/// Loop closure of a corrected clip `out` whose last P = preroll_out[c].size() frames should end where the
/// pre-roll ended: they blend into the pre-roll's output (weight rising to 1, raised cosine). Two ways, the
/// one with the shallower penetration kept: (a) the blend corrected again, from `before_window` (the
/// corrector before frame N - P), so contacts that the two corrected histories resolved on different sides
/// are resolved in the blend too; (b) the plain blend. A plain blend alone re-opened contacts mid-way
/// (issue 28: 17-66 mm on 1 s clips, 76 mm on a 4 s concert at 6.66/m^2, where the unclosed clip has 0 and
/// 16 mm), and so, less often, does (a); when both go deeper than the unclosed clip, the clip stays
/// unclosed: a seam rather than a collision.
void close_loop(const CrowdAnimation& input, const std::vector<std::vector<Pose>>& preroll_out,
                Corrector before_window, const CorrectorParams& params, CrowdAnimation& out,
                CorrectionReport& r) {
  const size_t n = out.characters.size();
  const int frames = out.frame_count(), preroll = static_cast<int>(preroll_out.front().size());
  const int first = frames - preroll;
  // (b): the plain blend, planted feet kept where they stand (blend_keeping_planted_feet.hpp).
  CrowdAnimation blended = out, corrected = out;
  blend_keeping_planted_feet(input, preroll_out, preroll, params, blended);
  // (a): corrected again from the corrector's state before the window, its targets the INPUT blended
  // into the pre-roll's output. Targets blended from the corrected clip (as before session 11) start off
  // the input by the correction: on the window's first frame every target foot then jumped by that
  // offset, the corrector released its holds and planted feet slid by up to 14 mm (tests/pipeline's
  // loop_seam.yaml).
  CrowdAnimation aims = input;
  blend_keeping_planted_feet(input, preroll_out, preroll, params, aims);
  std::vector<Pose> targets(n);
  for (int k = 0; k < preroll; ++k) {
    const size_t f = static_cast<size_t>(first + k);
    for (size_t c = 0; c < n; ++c) targets[c] = aims.characters[c].frames[f];
    const std::vector<Pose> stepped = before_window.step(targets);
    for (size_t c = 0; c < n; ++c) corrected.characters[c].frames[f] = stepped[c];
    if (before_window.last_stats().rejected) ++r.rejected_steps;
  }
  // (c): the corrected blend, its remaining distance to the pre-roll's output blended out over the
  // window's second half (feet kept again), which closes the loop exactly.
  CrowdAnimation finished = corrected;
  blend_keeping_planted_feet(input, preroll_out, std::max(1, preroll / 2), params, finished);
  // Exact closures first (the shallower of the two), then the corrected blend alone (the clip ends near
  // the pre-roll's end), then none.
  const double limit = deepest(out, 0, frames) + kClosureDepthSlackM;
  const double d_finished = deepest(finished, first, frames), d_blended = deepest(blended, first, frames);
  spdlog::debug(
      "correct_crowd: loop closure depths (m): unclosed {:.4f}, corrected blend {:.4f}, blend {:.4f}",
      limit - kClosureDepthSlackM, d_finished, d_blended);
  if (d_finished <= limit && d_finished <= d_blended) {
    out = std::move(finished);
    r.loop_closure = "corrected blend";
  } else if (d_blended <= limit) {
    out = std::move(blended);
    r.loop_closure = "blend";
  } else if (deepest(corrected, first, frames) <= limit) {
    out = std::move(corrected);
    r.loop_closure = "corrected, open";
  } else {
    r.loop_closure = "none";
  }
}

}  // namespace

// correct_crowd itself (one run, or several with anticipated contacts) is in anticipate_contacts.cpp.
CrowdAnimation correct_crowd_once(const CrowdAnimation& crowd, const CorrectorParams& params,
                                  Progress* progress, CorrectionReport* report) {
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
  // The corrector as it stood before frame N - P (P <= N - 1): the loop closure below runs on from there.
  std::optional<Corrector> before_window;
  for (int f = 0; f < frames; ++f) {
    for (size_t c = 0; c < n; ++c) targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
    const std::vector<Pose> corrected = corrector.step(targets);
    for (size_t c = 0; c < n; ++c) out.characters[c].frames[static_cast<size_t>(f)] = corrected[c];
    if (preroll > 0 && f == frames - preroll - 1) before_window = corrector;
    const StepStats& st = corrector.last_stats();
    contacts += st.contacts();
    iterations += st.cg_iterations;
    if (st.rejected) ++r.rejected_steps;
    if (!st.converged) ++r.unconverged_steps;
    if (progress) progress->advance();
  }
  if (before_window) close_loop(crowd, preroll_out, *before_window, params, out, r);
  r.contacts_mean = frames > 0 ? contacts / frames : 0.0;
  r.cg_iterations_mean = frames > 0 ? iterations / frames : 0.0;
  if (r.rejected_steps > 0)
    spdlog::warn(
        "correct_crowd: {} of {} steps were rejected (solver did not converge); the last stable state was "
        "kept",
        r.rejected_steps, frames);
  if (preroll > 0)
    spdlog::debug("correct_crowd: loop pre-roll of {} frames, closure: {}", preroll, r.loop_closure);
  if (report) *report = r;
  return out;
}

}  // namespace crowdlab
