#pragma once
// Offline interface: correct a whole CrowdAnimation (seed 000's "Ours" condition). Runs the online
// Corrector over every frame in order at the crowd's fps, with its environment, and returns a copy of
// the crowd whose poses are the corrected ones (shapes, names, palettes, environment and metadata
// unchanged).
//
// Settling (offline only; params.settle_steps): the online corrector starts at rest ON its first
// targets, so its first output frame is the input's, interpenetrations included, and the next frames
// push the bodies apart with a visible jump. Offline, the whole first frame is known in advance, so
// the corrector is first run settle_steps times on frame 0's targets (time frozen), as a simulation is
// settled before recording; frame 0 of the output is the settled state and the animation then
// proceeds normally. The settling steps are not part of the output.
//
// Loop pre-roll (offline only; params.loop_preroll_s, for clips shown looping): when the input loops, the
// settling runs on frame 0 and four whole laps of the clip are corrected first, unrecorded, each from the
// previous one's end; the recorded clip starts from the last one's end. Its own end still differs (dense
// contacts do not forget their history: measured, a 2 s pre-roll alone left a 3.2x seam, and laps' ends
// stay up to 5-9 cm apart for some characters at 6.66/m^2), so its last W = loop_preroll_s x fps frames
// blend into the last lap's (weight rising 0 -> 1, raised cosine, rotations slerped), the blend corrected
// again from the corrector's state before frame N - W, or plainly blended, whichever penetrates less; when
// both penetrate deeper than the unclosed clip, only the characters the corrected closure keeps within
// that depth are closed (correct_crowd.cpp, close_loop, says why). The re-corrected blend's planted feet
// stay where they stood before the input set them down (keep_planted_feet_planted: the second correction
// set a lagging foot down 12 mm off, session 13), and its arms aim at the input's (aimed at the blend, the
// hands flipped); characters the corrected closure leaves too deep try the plain blend, then a start from
// the next lap (the corrector runs a whole lap past the clip's end, and the clip's first frames blend from
// its first W), then their arms alone, or (session 16) their upper body or arms taken from that next lap up
// to a cut inside the clip, alone or together with the open neighbours they meet (loop_closure_choice.hpp;
// session 15), and otherwise stay open. A closure may always reach 10 mm.
// Every blend keeps planted feet where
// they stand and moves a foot only while the input lifts it (blend_keeping_planted_feet.hpp): a plain
// blend slid standing feet, and `ours`' stance-foot drift failed its check (issue 28, session 10).
//
// Throws InputError for an invalid crowd (validate_crowd: empty crowd, NaN/Inf poses,
// missing/zero-length bones, unequal frame counts) or invalid params.
#include <cstddef>
#include <string>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/progress.hpp"
#include "framework/correction/corrector_params.hpp"
#include "framework/correction/corrector_state.hpp"

namespace crowdlab {

/// Summary of an offline correction.
struct CorrectionReport {
  int frames = 0;
  int settle_steps = 0;    ///< steps run on the first target frame before the output starts
  int preroll_frames = 0;  ///< frames stepped before frame 0 (loop pre-roll: four laps of the clip)
  /// How the loop pre-roll's clip was closed: "corrected blend", "blend", "corrected blend for K, blend
  /// for L, next lap's start for S, arms for A, one arm for B, arms from the next lap for C of N
  /// characters" (both closures went deeper than the limit; the others stay unclosed; C counts the upper
  /// body and arm cuts of cut_joints_from_next_lap), or empty without a pre-roll.
  std::string loop_closure;
  /// Frames of the next lap after the clip that the loop closure stepped: 0 where an exact closure closes
  /// the whole crowd, W for the next lap's start, up to 2W for its cuts (correct_crowd.cpp, NextLap).
  int next_lap_frames = 0;
  /// Characters the loop closure left open (session 19).
  int loop_open_characters = 0;
  /// Laps recorded after the first because the closure left characters open (session 19,
  /// loop_closure_laps.hpp); preroll_frames counts the laps before the one kept.
  int extra_laps = 0;
  int rejected_steps = 0;      ///< steps whose solve failed (state kept)
  int unconverged_steps = 0;   ///< steps where CG stopped above its tolerance (result still used)
  double contacts_mean = 0.0;  ///< mean contacts per step
  double cg_iterations_mean = 0.0;
};

/// Whether correct_crowd corrects `crowd` twice, the second time toward its input moved where the first
/// put the bodies (params.follow_root_smoothing_s > 0 and the clip is not corrected into a loop;
/// follow_root_offsets.hpp).
bool follows_root_offsets(const CrowdAnimation& crowd, const CorrectorParams& params);

/// The corrector steps of correct_crowd's first run (both runs where it follows the root offsets), the
/// total its progress counts at the start: the frames, and for a looping clip with a pre-roll the lead
/// laps before them (four laps of the clip, correct_crowd.cpp), the closure's re-corrected window (W
/// frames) and the frames of the next lap after them that the closure may read (its start, and the joints cut
/// from it: at most 2W; stepped only where the per-character closure needs them, the rest counted as done).
/// Where the closure leaves characters open, an extra lap grows the progress's total by F + W while it runs
/// (Progress::grow; session 20).
std::size_t correction_steps(const CrowdAnimation& crowd, const CorrectorParams& params);

/// progress (optional) is advanced once per step of the first run (correction_steps, and the extra laps
/// it grows by), and reaches its total as the run ends. report (optional)
/// receives the summary of the last run. Where follows_root_offsets, the clip is corrected once, its input
/// re-planned on the corrected roots (follow_root_offsets.hpp) and corrected again; the result is that
/// second correction, and anticipated contacts (below) ramp toward the re-planned input. With
/// params.anticipated_joints other than "none", the clip is
/// corrected 1 + params.anticipation_runs times, each run's contact deviations ramped into the next run's
/// targets (anticipate_contacts.hpp).
CrowdAnimation correct_crowd(const CrowdAnimation& crowd, const CorrectorParams& params,
                             Progress* progress = nullptr, CorrectionReport* report = nullptr);

/// One run of the corrector over the clip (settling, loop pre-roll and closure as above), whatever
/// params.anticipated_joints says.
CrowdAnimation correct_crowd_once(const CrowdAnimation& crowd, const CorrectorParams& params,
                                  Progress* progress = nullptr, CorrectionReport* report = nullptr);

}  // namespace crowdlab
