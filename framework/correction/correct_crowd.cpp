#include "framework/correction/correct_crowd.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "framework/core/crowd_penetration_depth.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/loop_seam_per_character.hpp"
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

/// Per character, its deepest penetration (m) with any other over frames [first, last) of a crowd.
std::vector<double> deepest_per_character(const CrowdAnimation& crowd, int first, int last) {
  std::vector<double> depth(crowd.characters.size(), 0.0);
  std::vector<WorldCapsules> bodies(crowd.characters.size());
  for (int f = first; f < last; ++f) {
    for (size_t c = 0; c < bodies.size(); ++c)
      bodies[c] =
          world_capsules(crowd.characters[c].shape, crowd.characters[c].frames[static_cast<size_t>(f)]);
    const std::vector<double> now = deepest_penetration_per_body(bodies);
    for (size_t c = 0; c < bodies.size(); ++c) depth[c] = std::max(depth[c], now[c]);
  }
  return depth;
}

/// Deepest inter-body penetration (m) over frames [first, last) of a crowd.
double deepest(const CrowdAnimation& crowd, int first, int last) {
  const std::vector<double> per_character = deepest_per_character(crowd, first, last);
  return per_character.empty() ? 0.0 : *std::max_element(per_character.begin(), per_character.end());
}

/// A closure of some characters only: every character starts on the first of `closures` (the closed
/// candidates, best first) and each whose penetration over frames [first, N) goes deeper than `limit_m`
/// moves to the next candidate, or back to its frames in `open` after the last (both sides of a too-deep
/// contact move on), again until no character is too deep. Terminates, since `open` alone stays within the
/// limit. Returns how many characters ended on each candidate.
std::vector<int> close_some_characters(const std::vector<const CrowdAnimation*>& closures, int first,
                                       double limit_m, CrowdAnimation& open) {
  const int frames = open.frame_count();
  const size_t rungs = closures.size();
  CrowdAnimation mixed = *closures.front();
  std::vector<size_t> rung(mixed.characters.size(), 0);
  for (bool moved = true; moved;) {
    moved = false;
    const std::vector<double> depth = deepest_per_character(mixed, first, frames);
    for (size_t c = 0; c < rung.size(); ++c) {
      if (rung[c] == rungs || depth[c] <= limit_m) continue;
      ++rung[c];
      mixed.characters[c].frames = (rung[c] < rungs ? closures[rung[c]] : &open)->characters[c].frames;
      moved = true;
    }
  }
  open = std::move(mixed);
  std::vector<int> on(rungs, 0);
  for (size_t r : rung)
    if (r < rungs) ++on[r];
  if (spdlog::should_log(spdlog::level::debug)) {
    std::string open_ones;
    for (size_t c = 0; c < rung.size(); ++c)
      if (rung[c] == rungs) open_ones += " " + open.characters[c].name;
    spdlog::debug("correct_crowd: the loop stays open for{}", open_ones.empty() ? " none" : open_ones);
  }
  return on;
}

/// Whole laps of the clip corrected (unrecorded) before the recorded one, for looping clips (issue 28):
/// the recorded clip starts from the end of the last, so its seam is the distance between two laps' ends.
/// A 2 s pre-roll from a freshly settled crowd left histories that resolved dense contacts on other sides
/// than the clip (gomez2024 concert, 4 s, 6.66/m^2: seam 1.64x, every closure 82-84 mm deep). Measured
/// there (V3, 320x180, load 11 on 2 cores) with the per-character closure below: one lead lap 1.76x
/// (the laps' ends up to 91 mm apart for the worst character), two 1.41x; 4.44/m^2 1.13x / 1.21x;
/// 2.22/m^2 0.90x / 0.89x. Session 13 (arms aimed at the input in the re-corrected closure, which left
/// fewer characters closable): two laps 1.57x, three 1.31x but the unclosed clip 15.6 mm deep, four 1.48x
/// and 9.8 mm (load 15-20; the laps are chaotic, so a seam varies by +-0.2 from crowd to crowd). Each lap
/// costs one correction of the clip (6 s of 60 characters x 120 frames at load 11).
constexpr int kLeadLaps = 4;

/// Frames of the loop closure's window (0: no pre-roll): params.loop_preroll_s of a looping input, at most
/// all frames but one.
int loop_window_frames(const CrowdAnimation& crowd, const CorrectorParams& params) {
  const int frames = crowd.frame_count();
  return frames > 1 && params.loop_preroll_s > 0.0 && input_loops(crowd)
             ? std::min(frames - 1, static_cast<int>(std::lround(params.loop_preroll_s * crowd.meta.fps)))
             : 0;
}

/// Penetration a loop closure may add beyond the unclosed clip's deepest (m): below what shows.
constexpr double kClosureDepthSlackM = 0.001;

/// Joints whose aims in the re-corrected closure stay the input's: collars, shoulders, elbows, wrists, hands.
/// Aimed at the input blended into the last lap's output, the second correction turned hands and wrists
/// away from their input within a few frames (issue 27's flips: gomez2024 concert, 4 s, 6.66/m^2, 756
/// flip joint-frames in the window against 72 unclosed); aimed at the input, as the clip's own correction
/// is, it flips as that does, and the closing blend (c) brings the arms to the lap's over the window's
/// second half.
constexpr std::array<Joint, 10> kArmJoints = {kLeftCollar, kRightCollar, kLeftShoulder, kRightShoulder,
                                              kLeftElbow,  kRightElbow,  kLeftWrist,    kRightWrist,
                                              kLeftHand,   kRightHand};

/// The arm joints' local rotations on frames [first, N) of `aims` set back to the input's.
void arms_from_input(const CrowdAnimation& input, int first, CrowdAnimation& aims) {
  for (size_t c = 0; c < aims.characters.size(); ++c)
    for (size_t f = static_cast<size_t>(first); f < aims.characters[c].frames.size(); ++f)
      for (Joint j : kArmJoints)
        aims.characters[c].frames[f].local_rotations[static_cast<size_t>(j)] =
            input.characters[c].frames[f].local_rotations[static_cast<size_t>(j)];
}

/// Loop closure of a corrected clip `out` whose last W = preroll_out[c].size() frames should end where the
/// last lead lap ended (the state frame 0 continued from): they blend into that lap's output (weight rising
/// to 1, raised cosine). (a) the blend corrected again, from `before_window` (the corrector before frame
/// N - W), so contacts that the two laps resolved on different sides are resolved in the blend too, and
/// what then remains blended out; (b) the plain blend. The shallower is kept when it is no deeper than the
/// unclosed clip (+1 mm). A plain blend re-opened contacts mid-way (issue 28: 17-66 mm on 1 s clips, 76 mm
/// on a 4 s concert at 6.66/m^2, where the unclosed clip has 0 and 16 mm), and so, less often, does (a);
/// then (a) closes only the characters it keeps within that depth (close_some_characters), the others stay
/// unclosed: a seam for some rather than a collision (all of them stayed unclosed before session 12).
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
  arms_from_input(input, first, aims);
  std::vector<Pose> targets(n);
  for (int k = 0; k < preroll; ++k) {
    const size_t f = static_cast<size_t>(first + k);
    for (size_t c = 0; c < n; ++c) targets[c] = aims.characters[c].frames[f];
    const std::vector<Pose> stepped = before_window.step(targets);
    for (size_t c = 0; c < n; ++c) corrected.characters[c].frames[f] = stepped[c];
    if (before_window.last_stats().rejected) ++r.rejected_steps;
  }
  // The second correction lags a swinging foot and can set it down away from where it stood the frame
  // before (loop_seam.yaml: 12 mm, stance-foot drift p99 12.0 mm): planted feet follow the input instead.
  keep_planted_feet_planted(input, preroll, params, corrected);
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
  } else {
    const std::vector<int> on = close_some_characters({&finished, &blended}, first, limit, out);
    r.loop_closure = "corrected blend for " + std::to_string(on[0]) + ", blend for " + std::to_string(on[1]) +
                     " of " + std::to_string(n) + " characters";
  }
}

/// The targets of frame f: every character's input pose.
void frame_targets(const CrowdAnimation& crowd, int f, std::vector<Pose>& targets) {
  for (size_t c = 0; c < targets.size(); ++c) targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
}

/// Largest mean joint distance (m) of any character between the clip's last frame and the last lead lap's.
double lap_difference_m(const CrowdAnimation& clip, const std::vector<std::vector<Pose>>& lead_end) {
  double worst = 0.0;
  for (size_t c = 0; c < clip.characters.size(); ++c) {
    const auto pa = joint_positions(clip.characters[c].shape, clip.characters[c].frames.back());
    const auto pb = joint_positions(clip.characters[c].shape, lead_end[c].back());
    double sum = 0.0;
    for (size_t j = 0; j < pa.size(); ++j) sum += (pa[j] - pb[j]).norm();
    worst = std::max(worst, sum / static_cast<double>(pa.size()));
  }
  return worst;
}

/// Debug log: the characters that add most to the closed clip's seam, and where on the body
/// (loop_seam_per_character.hpp; issue 28, session 14: at 6.66/m^2 the seam was a few open characters'
/// arms).
void log_seam_carriers(const CrowdAnimation& clip) {
  const std::vector<CharacterSeam> seams = loop_seam_per_character(clip);
  std::vector<size_t> order(seams.size());
  for (size_t c = 0; c < order.size(); ++c) order[c] = c;
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return seams[a].excess_m() > seams[b].excess_m(); });
  std::string worst;
  for (size_t i = 0; i < std::min<size_t>(5, order.size()); ++i) {
    const CharacterSeam& s = seams[order[i]];
    worst += fmt::format(" {} +{:.3f} m (arms {:.3f}, legs {:.3f}, trunk {:.3f});",
                         clip.characters[order[i]].name, s.excess_m(), s.arms_m, s.legs_m, s.trunk_m);
  }
  spdlog::debug("correct_crowd: the seam's largest carriers:{}", worst);
}

}  // namespace

std::size_t correction_steps(const CrowdAnimation& crowd, const CorrectorParams& params) {
  const auto frames = static_cast<size_t>(crowd.frame_count());
  return loop_window_frames(crowd, params) > 0 ? (1 + kLeadLaps) * frames : frames;
}

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
  const int window = loop_window_frames(crowd, params);
  r.preroll_frames = window > 0 ? kLeadLaps * frames : 0;
  if (frames > 0) {
    frame_targets(crowd, 0, targets);
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
  // Lead laps (unrecorded), each from the previous one's end; the recorded clip starts from the last's end,
  // whose final window frames its own end blends into.
  std::vector<std::vector<Pose>> lead_end(n);
  for (int l = 0; l < (window > 0 ? kLeadLaps : 0); ++l) {
    for (int f = 0; f < frames; ++f) {
      frame_targets(crowd, f, targets);
      const std::vector<Pose> corrected = corrector.step(targets);
      if (l == kLeadLaps - 1 && f >= frames - window)
        for (size_t c = 0; c < n; ++c) lead_end[c].push_back(corrected[c]);
      if (corrector.last_stats().rejected) ++r.rejected_steps;
      if (progress) progress->advance();
    }
  }
  // The corrector as it stood before frame N - W: the loop closure below runs on from there.
  std::optional<Corrector> before_window;
  for (int f = 0; f < frames; ++f) {
    frame_targets(crowd, f, targets);
    const std::vector<Pose> corrected = corrector.step(targets);
    for (size_t c = 0; c < n; ++c) out.characters[c].frames[static_cast<size_t>(f)] = corrected[c];
    if (window > 0 && f == frames - window - 1) before_window = corrector;
    const StepStats& st = corrector.last_stats();
    contacts += st.contacts();
    iterations += st.cg_iterations;
    if (st.rejected) ++r.rejected_steps;
    if (!st.converged) ++r.unconverged_steps;
    if (progress) progress->advance();
  }
  if (before_window) {
    if (spdlog::should_log(spdlog::level::debug))
      spdlog::debug("correct_crowd: the recorded lap ends {:.4f} m from the lead lap (worst character)",
                    lap_difference_m(out, lead_end));
    close_loop(crowd, lead_end, *before_window, params, out, r);
    if (spdlog::should_log(spdlog::level::debug)) log_seam_carriers(out);
  }
  r.contacts_mean = frames > 0 ? contacts / frames : 0.0;
  r.cg_iterations_mean = frames > 0 ? iterations / frames : 0.0;
  if (r.rejected_steps > 0)
    spdlog::warn(
        "correct_crowd: {} of {} steps were rejected (solver did not converge); the last stable state was "
        "kept",
        r.rejected_steps, frames);
  if (window > 0)
    spdlog::debug("correct_crowd: loop pre-roll of {} frames, closure: {}", r.preroll_frames, r.loop_closure);
  if (report) *report = r;
  return out;
}

}  // namespace crowdlab
