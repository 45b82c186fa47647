#pragma once
// Which loop closure each character of a looping clip takes (issue 28; used by correct_crowd.cpp's
// close_loop, which computes the candidates: whole-crowd closures of the clip's window).
//
// A closure candidate is the whole crowd with the clip's last frames brought to where frame 0 continues
// from (or, start_from_next_lap, its first frames brought from where its last frame continues). In a dense
// crowd every candidate goes deeper than the unclosed clip somewhere, because two laps resolved a contact on
// different sides and a blend passes a limb through the other's. So each character takes one candidate or
// stays unclosed, such that no character penetrates another deeper than a limit over the frames the
// candidates change (the window at the end, and the start window).
//
// choose_closures:
//  1. Descent (session 12): every character starts on the first candidate; all those too deep move to the
//     next candidate (after the last of the first `descent_rungs`: unclosed) at once, until none is.
//  2. Join (session 15), over the characters the descent left unclosed, largest seam first: a character
//     takes the first candidate (of all of them) that keeps it within the limit against everyone as they
//     now are; failing that, the first candidate on which it and the unclosed characters it would meet too
//     deeply (at most kMaxJoinedCharacters in all) close together within the limit. Why: the descent moves
//     every too-deep character at once, so a character too deep only against a neighbour that the same
//     step opens is opened too; and two neighbours can often close only together, each alone meeting the
//     other's unclosed limbs. Measured on the 4 s concert at 6.66/m^2 (docs/stimuli.md, session 15).
//     The join checks each candidate over the frames it changes (spans; session 16: candidates whose
//     window lies inside the clip, cut_joints_from_next_lap).
#include <array>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/correction/corrector_params.hpp"

namespace crowdlab {

/// Frames [begin, end) of the clip that a closure candidate changes: the join checks its depths there.
struct FrameSpan {
  int begin = 0, end = 0;
};

/// Per character, its deepest penetration (m) with any other over frames [first, last) of a crowd.
std::vector<double> deepest_per_character(const CrowdAnimation& crowd, int first, int last);

/// Most characters that join to close together (the one tried and those it would meet too deeply).
inline constexpr std::size_t kMaxJoinedCharacters = 4;

/// Per character, the index in `closures` of the candidate it takes, or closures.size() for `unclosed`.
/// The descent uses the first `descent_rungs` candidates, the join all of them. Depths are checked over
/// frames [first, N) and [0, min(start_window, first)). Needs every character within limit_m in `unclosed`
/// against `unclosed` (then the result keeps every character within it).
/// allowed[r][c]: whether character c may take candidate r at all (correct_crowd.cpp offers none that
/// adds joint flips to it). spans[r]: the frames candidate r changes, where the join checks it (empty:
/// every candidate over the frames the descent checks).
std::vector<std::size_t> choose_closures(const std::vector<const CrowdAnimation*>& closures,
                                         std::size_t descent_rungs, const CrowdAnimation& unclosed, int first,
                                         int start_window, double limit_m,
                                         const std::vector<std::vector<bool>>& allowed,
                                         const std::vector<FrameSpan>& spans = {});

/// choose_closures' two steps apart (header, steps 1 and 2), for a caller that builds the join's
/// candidates only when the descent leaves a character unclosed (correct_crowd.cpp: the next lap's cuts,
/// session 17). descend_closures returns what choose_closures' descent does; join_closures then runs the
/// join on `rung` (closures.size() = unclosed) over every candidate, each checked over spans[r] (not
/// empty: one per candidate). The join reads candidate r's character c only where rung[c] is r or
/// unclosed, so a candidate that no character takes in the descent may hold the frames of the unclosed
/// characters only (correct_crowd.cpp: the others' frames empty).
std::vector<std::size_t> descend_closures(const std::vector<const CrowdAnimation*>& closures,
                                          std::size_t descent_rungs, const CrowdAnimation& unclosed,
                                          int first, int start_window, double limit_m,
                                          const std::vector<std::vector<bool>>& allowed);
void join_closures(const std::vector<const CrowdAnimation*>& closures, const CrowdAnimation& unclosed,
                   double limit_m, const std::vector<std::vector<bool>>& allowed,
                   const std::vector<FrameSpan>& spans, std::vector<std::size_t>& rung);

/// Why a character stays unclosed after the join: a diagnostic for the debug log (session 18: on the 4 s
/// concert at 6.66/m^2, seed 2024000001, three characters stayed open and each candidate they may take met
/// one to seven neighbours 15-80 mm deep; docs/stimuli.md).
struct OpenCharacterReason {
  std::size_t character = 0;
  /// Candidates it may not take (allowed[r][c] false: they add joint flips to it).
  std::size_t excluded = 0;
  /// Of those it may take, the one on which it meets the fewest others beyond the limit (then the
  /// shallowest deepest contact, then the first); closures.size() if it may take none.
  std::size_t best = 0;
  /// On `best`, with everyone else as rung places them: each character met beyond the limit, and how deep
  /// (m), in index order.
  std::vector<std::pair<std::size_t, double>> met;
};

/// For every character rung leaves unclosed (rung[c] == closures.size()), in index order, why: the
/// arguments are join_closures' (spans: one per candidate), rung its result.
std::vector<OpenCharacterReason> explain_open_characters(const std::vector<const CrowdAnimation*>& closures,
                                                         const CrowdAnimation& unclosed, double limit_m,
                                                         const std::vector<std::vector<bool>>& allowed,
                                                         const std::vector<FrameSpan>& spans,
                                                         const std::vector<std::size_t>& rung);

/// `unclosed` with each character's frames from its chosen candidate (choose_closures).
CrowdAnimation mix_closures(const std::vector<const CrowdAnimation*>& closures,
                            const CrowdAnimation& unclosed, const std::vector<std::size_t>& choice);

/// `clip` whose first W = next_start[c].size() frames blend from `next_start` (the corrector's poses that
/// continue from the clip's own last frame, as a next lap would start) into the clip's own: frame 0 takes
/// next_start's first pose, so it follows the clip's last frame as any frame follows the one before, and
/// the weight falls to 0 over the window (raised cosine). Planted feet stay planted: this is
/// blend_keeping_planted_feet on the time-reversed clip and input. Why (session 15): a character whose
/// change of contact side no closure of the clip's END can pass without meeting a neighbour may pass it at
/// the START, over other frames of its dance. W < the clip's frame count.
CrowdAnimation start_from_next_lap(const CrowdAnimation& input,
                                   const std::vector<std::vector<Pose>>& next_start,
                                   const CorrectorParams& params, const CrowdAnimation& clip);

/// The joints of each arm, collar to hand.
inline constexpr std::array<Joint, 5> kLeftArmJoints = {kLeftCollar, kLeftShoulder, kLeftElbow, kLeftWrist,
                                                        kLeftHand};
inline constexpr std::array<Joint, 5> kRightArmJoints = {kRightCollar, kRightShoulder, kRightElbow,
                                                         kRightWrist, kRightHand};

/// `clip` with the local rotations of `joints` on its last W = lap_end[c].size() frames slerped toward
/// lap_end's (weight raised_cosine(k + 1, W): the last frame takes lap_end's), the rest of each body the
/// clip's. Why (session 14's trace): the characters no whole-body closure could close carried the dense
/// concert's seam by their ARMS (arms 10-12 cm from the lap's, legs <= 3.2 cm). Characters without frames
/// stay so (join candidates hold only the characters the join may move; join_closures).
CrowdAnimation close_joints(const CrowdAnimation& clip, const std::vector<std::vector<Pose>>& lap_end,
                            std::span<const Joint> joints);

/// `clip` with the local rotations of `joints` taken from `next_lap` (the corrector's poses that continue
/// from the clip's last frame, a whole lap: next_lap[c][f] is frame f of the lap after the clip) on frames
/// [0, cut), slerped back to the clip's own over [cut, cut + window) (the clip's weight rising as a raised
/// cosine), and the clip's own from cut + window on. Those joints then continue from the clip's last frame
/// into frame 0, and their seam moves to the window inside the clip. Why (session 16): on the dense concert
/// the last open characters went 83-108 mm into a neighbour on every closure at the clip's end or start,
/// the two laps holding an arm on opposite sides of the neighbour there; elsewhere in the dance both laps
/// may hold it on the same side, and a window there passes no limb through another. The root, legs and
/// trunk stay the clip's, so planted feet stay planted. Needs 0 <= cut, window >= 1, cut + window <= N.
/// Characters without frames stay so (as close_joints).
CrowdAnimation cut_joints_from_next_lap(const CrowdAnimation& clip,
                                        const std::vector<std::vector<Pose>>& next_lap,
                                        std::span<const Joint> joints, int cut, int window);

}  // namespace crowdlab
