#include "framework/correction/correct_crowd.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>

#include "framework/core/crowd_penetration_depth.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/joint_flips.hpp"
#include "framework/core/loop_seam_per_character.hpp"
#include "framework/correction/blend_keeping_planted_feet.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/loop_closure_choice.hpp"
#include "framework/correction/loop_closure_excerpt.hpp"
#include "framework/correction/loop_closure_laps.hpp"

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
  const std::vector<double> per_character = deepest_per_character(crowd, first, last);
  return per_character.empty() ? 0.0 : *std::max_element(per_character.begin(), per_character.end());
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
/// Depth a loop closure may always reach (m): issue 18's bound on the deepest contact. Session 15: on the
/// 4 s concert at 6.66/m^2 (seed 2024000001) the unclosed clip is 6.7 mm deep, and closing up to 10 mm
/// instead of 7.7 mm let 4 more characters close (V3 seam 1.521 -> 1.500, deepest 9.7 mm).
constexpr double kClosureDepthFloorM = 0.010;

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

/// Joint flips (core/joint_flips.hpp) of one character of `crowd` against its input.
long flips_of(const CrowdAnimation& input, const CrowdAnimation& crowd, size_t c) {
  CrowdAnimation one_in, one;
  one_in.meta = input.meta;
  one.meta = crowd.meta;
  one_in.characters = {input.characters[c]};
  one.characters = {crowd.characters[c]};
  return measure_joint_flips(one_in, one).count;
}

/// Per character, its joint flips in `crowd` against the input (flips_of).
std::vector<long> flips_per_character(const CrowdAnimation& input, const CrowdAnimation& crowd) {
  std::vector<long> flips(crowd.characters.size());
  for (size_t c = 0; c < flips.size(); ++c) flips[c] = flips_of(input, crowd, c);
  return flips;
}

/// allowed[c]: the closure `closed` gives character c no more joint flips than it has unclosed
/// (`unclosed_flips`, flips_per_character). Why (session 15): the start from the next lap and the arm
/// closures brought the corrector's own hand flips of those frames into the clip (4 s concert at 6.66/m^2:
/// flips 23 -> 35 and 25 -> 30, all hands).
std::vector<bool> without_new_flips(const CrowdAnimation& input, const CrowdAnimation& closed,
                                    const std::vector<long>& unclosed_flips) {
  std::vector<bool> allowed(unclosed_flips.size());
  for (size_t c = 0; c < allowed.size(); ++c) allowed[c] = flips_of(input, closed, c) <= unclosed_flips[c];
  return allowed;
}

bool all_allowed(const std::vector<bool>& allowed) {
  return std::all_of(allowed.begin(), allowed.end(), [](bool ok) { return ok; });
}

/// Closing window of the candidates that take joints from the next lap up to a cut inside the clip
/// (cut_joints_from_next_lap), in fifths of the closure's window W: 2/5 (24 frames, 0.8 s, at W = 60 and
/// 30 fps), with a cut every half such window from frame 0 to the clip's last window (9 cuts on a 4 s
/// clip). Measured (session 16, 4 s concert at 6.66/m^2, seeds 2024000001 / 2024000002, V3 seam): windows
/// of 60 frames 1.447 / 1.615, 40: 1.411 / 1.614, 24: 1.402 / 1.523, 18: 1.402 / 1.536, 12: 1.340 / 1.536
/// (without these candidates 1.460 / 1.619); shorter windows turn the limb back faster inside the clip.
constexpr int kCutWindowFifths = 2;
/// How far into the clip a cut may end, in closing windows W (see close_loop).
constexpr int kCutSpanWindows = 2;

/// The arm sets a closure may move alone: both arms, the left, the right (collar to hand).
std::array<std::vector<Joint>, 3> arm_sets() {
  std::vector<Joint> both(kLeftArmJoints.begin(), kLeftArmJoints.end());
  both.insert(both.end(), kRightArmJoints.begin(), kRightArmJoints.end());
  return {both, std::vector<Joint>(kLeftArmJoints.begin(), kLeftArmJoints.end()),
          std::vector<Joint>(kRightArmJoints.begin(), kRightArmJoints.end())};
}

/// The joint sets the next lap's cut candidates move, in the order they are tried: the upper body (spine,
/// neck, head and both arms), then the arm sets. Why the trunk too (session 16): with the arms alone the
/// hands still differed by the trunk's turn between the laps (4 s concert at 6.66/m^2: c049's arms 7.8 ->
/// 6.7 cm apart at the seam, trunk 1.6 cm).
std::vector<std::vector<Joint>> cut_joint_sets() {
  std::vector<Joint> upper = {kSpine1, kSpine2, kSpine3, kNeck, kHead};
  upper.insert(upper.end(), kLeftArmJoints.begin(), kLeftArmJoints.end());
  upper.insert(upper.end(), kRightArmJoints.begin(), kRightArmJoints.end());
  std::vector<std::vector<Joint>> sets = {upper};
  for (const std::vector<Joint>& arm : arm_sets()) sets.push_back(arm);
  return sets;
}

/// Debug log: the characters the loop closure leaves open (choice == open).
void log_open_characters(const CrowdAnimation& crowd, const std::vector<size_t>& choice, size_t open) {
  if (!spdlog::should_log(spdlog::level::debug)) return;
  std::string names;
  for (size_t c = 0; c < choice.size(); ++c)
    if (choice[c] == open) names += " " + crowd.characters[c].name;
  spdlog::debug("correct_crowd: the loop stays open for{}", names.empty() ? " none" : names);
}

/// The per-character closures' kinds, by the index close_per_character gives them: its report counts each
/// and the debug log names the one an open character came nearest to taking.
constexpr std::array<const char*, 6> kClosureKind = {
    "corrected blend", "blend", "next lap's start", "arms", "one arm", "arms from the next lap"};

/// Debug log: why each character the loop closure leaves open stays so (explain_open_characters; session
/// 18: the neighbours its best candidate meets, and how many candidates the flip filter took from it).
void log_why_open(const CrowdAnimation& crowd, const std::vector<OpenCharacterReason>& reasons,
                  const std::vector<int>& kinds, size_t candidates) {
  for (const OpenCharacterReason& why : reasons) {
    std::string met;
    for (const auto& [o, depth_m] : why.met)
      met += fmt::format("{} {} {:.1f} mm", met.empty() ? "" : ",", crowd.characters[o].name, 1e3 * depth_m);
    spdlog::debug(
        "correct_crowd: {} stays open: {} of {} candidates add joint flips; the best other ({} {}) meets{}",
        crowd.characters[why.character].name, why.excluded, candidates,
        why.best < candidates ? kClosureKind[static_cast<size_t>(kinds[why.best])] : "none", why.best,
        met.empty() ? " nobody" : met);
  }
}

/// Frames of the next lap the loop closure may read: the start's W, and the cuts' kCutSpanWindows W.
int next_lap_bound(int frames, int window) {
  return std::min(frames, kCutSpanWindows * window);
}

/// Counts the next lap's frames the closure never read as done: correction_steps counted its bound
/// (next_lap_bound), and the lap was stepped only as far as the closure read it.
void count_unread_next_lap(Progress* progress, const NextLap& next_lap, int frames, int window) {
  if (progress) progress->advance(static_cast<size_t>(next_lap_bound(frames, window) - next_lap.stepped()));
}

/// allowed[r][c] as without_new_flips gives it, for candidates r >= from and the characters in `open` only
/// (false for the others: the join moves only the characters the descent left unclosed).
std::vector<std::vector<bool>> without_new_flips_for(const CrowdAnimation& input,
                                                     const std::vector<const CrowdAnimation*>& closures,
                                                     size_t from, const CrowdAnimation& unclosed,
                                                     const std::vector<size_t>& open) {
  std::vector<std::vector<bool>> allowed(closures.size(), std::vector<bool>(unclosed.characters.size()));
  for (size_t c : open) {
    const long own = flips_of(input, unclosed, c);
    for (size_t r = from; r < closures.size(); ++r) allowed[r][c] = flips_of(input, *closures[r], c) <= own;
  }
  return allowed;
}

/// The per-character closure (close_loop's (a)-(e), choose_closures): the descent over the exact closures
/// and the next lap's start; only if it leaves a character unclosed, the join over every candidate, the
/// arm closures and the cuts built on an excerpt of the clip (loop_closure_excerpt.hpp) from the next
/// lap's first 2W frames. Why (session 17): the candidates are whole-crowd copies (36 cuts on a 4 s
/// clip, ~1.2 GB on a 20 s one) and most crowds need none of them; the result is the whole choice's.
/// `unclosed_flips` and `whole_allowed` are close_loop's: the clip's flips per character and
/// without_new_flips of `finished` and `blended`.
void close_per_character(const CrowdAnimation& input, const std::vector<std::vector<Pose>>& preroll_out,
                         NextLap& next_lap, const CorrectorParams& params, const CrowdAnimation& finished,
                         const CrowdAnimation& blended, const std::vector<long>& unclosed_flips,
                         std::vector<std::vector<bool>> whole_allowed, double limit, CrowdAnimation& out,
                         CorrectionReport& r) {
  const size_t n = out.characters.size();
  const int frames = out.frame_count(), preroll = static_cast<int>(preroll_out.front().size());
  const int first = frames - preroll;
  const CrowdAnimation started = start_from_next_lap(input, next_lap.first(preroll), params, out);
  const std::vector<const CrowdAnimation*> exact = {&finished, &blended, &started};
  std::vector<std::vector<bool>> allowed_exact = std::move(whole_allowed);
  allowed_exact.push_back(without_new_flips(input, started, unclosed_flips));
  std::vector<size_t> choice =
      descend_closures(exact, exact.size(), out, first, preroll, limit, allowed_exact);
  std::vector<size_t> open;
  for (size_t c = 0; c < n; ++c)
    if (choice[c] == exact.size()) open.push_back(c);
  std::array<int, kClosureKind.size()> on{};  // how many characters took each kind (kClosureKind)
  if (!open.empty()) {
    // The join's candidates, on the excerpt. Whole closures before partial ones (the upper body and both
    // arms cut from the next lap before one arm alone): the join gives each character the first that fits.
    // Session 16, seed 2024000001: with the cuts after the one-arm closures, 2 characters took a cut (V3
    // seam 1.450); before them, 6 (1.411).
    const int last_cut_end = next_lap_bound(frames, preroll);
    const ClosureExcerpt ex =
        ClosureExcerpt::of(frames, last_cut_end, preroll, flip_window(out.meta.fps).frames);
    const std::vector<std::vector<Pose>> lap = next_lap.first(last_cut_end);
    const CrowdAnimation out_ex = ex.cut(out), input_ex = ex.cut(input);
    // The join reads the new candidates' unclosed characters only (join_closures): they alone keep frames.
    CrowdAnimation open_ex = out_ex;
    for (size_t c = 0; c < n; ++c)
      if (choice[c] != exact.size()) std::vector<Pose>().swap(open_ex.characters[c].frames);
    std::vector<CrowdAnimation> candidates = {ex.cut(finished), ex.cut(blended), ex.cut(started)};
    std::vector<FrameSpan> spans = {ex.map({first, frames}), ex.map({first, frames}), ex.map({0, preroll})};
    std::vector<int> kinds = {0, 1, 2};
    const auto add = [&](CrowdAnimation candidate, FrameSpan span, int kind) {
      candidates.push_back(std::move(candidate));
      spans.push_back(ex.map(span));
      kinds.push_back(kind);
    };
    const int cut_window = std::max(1, preroll * kCutWindowFifths / 5);
    const auto add_cuts = [&](const std::vector<Joint>& joints) {
      for (int cut = 0; cut + cut_window <= last_cut_end; cut += std::max(1, cut_window / 2))
        add(cut_joints_from_next_lap(open_ex, lap, joints, cut, cut_window), {0, cut + cut_window}, 5);
    };
    const auto arms = arm_sets();
    const auto cut_sets = cut_joint_sets();
    add(close_joints(open_ex, preroll_out, arms[0]), {first, frames}, 3);
    add_cuts(cut_sets[0]);
    add_cuts(cut_sets[1]);
    for (size_t a = 1; a < arms.size(); ++a)
      add(close_joints(open_ex, preroll_out, arms[a]), {first, frames}, 4);
    for (size_t s = 2; s < cut_sets.size(); ++s) add_cuts(cut_sets[s]);
    std::vector<const CrowdAnimation*> closures;
    for (const CrowdAnimation& c : candidates) closures.push_back(&c);
    std::vector<std::vector<bool>> allowed =
        without_new_flips_for(input_ex, closures, exact.size(), out_ex, open);
    for (size_t k = 0; k < exact.size(); ++k) allowed[k] = allowed_exact[k];  // counted on the whole clip
    for (size_t& k : choice)
      if (k == exact.size()) k = closures.size();
    join_closures(closures, out_ex, limit, allowed, spans, choice);
    log_open_characters(out, choice, closures.size());
    if (spdlog::should_log(spdlog::level::debug))
      log_why_open(out, explain_open_characters(closures, out_ex, limit, allowed, spans, choice), kinds,
                   closures.size());
    std::string partial;  // the characters closed in part (their other limbs keep the seam)
    for (size_t c = 0; c < n; ++c) {
      if (choice[c] >= closures.size()) continue;
      ++on[static_cast<size_t>(kinds[choice[c]])];
      if (kinds[choice[c]] >= 3)
        partial += fmt::format(" {} ({})", out.characters[c].name,
                               kClosureKind[static_cast<size_t>(kinds[choice[c]])]);
      if (choice[c] < exact.size())
        out.characters[c].frames = exact[choice[c]]->characters[c].frames;
      else
        ex.put_back(closures[choice[c]]->characters[c], out.characters[c]);
    }
    spdlog::debug("correct_crowd: closed in part:{}", partial.empty() ? " none" : partial);
  } else {
    log_open_characters(out, choice, exact.size());
    for (size_t c = 0; c < n; ++c) ++on[static_cast<size_t>(choice[c])];
    out = mix_closures(exact, out, choice);
  }
  r.loop_open_characters = static_cast<int>(n) - std::accumulate(on.begin(), on.end(), 0);
  std::string counts;
  for (size_t k = 0; k < on.size(); ++k)
    counts += fmt::format("{}{} for {}", k ? ", " : "", kClosureKind[k], on[k]);
  r.loop_closure = fmt::format("{} of {} characters", counts, n);
}

/// Loop closure of a corrected clip `out` whose last W = preroll_out[c].size() frames should end where the
/// last lead lap ended (the state frame 0 continued from): they blend into that lap's output (weight rising
/// to 1, raised cosine). (a) the blend corrected again, from `before_window` (the corrector before frame
/// N - W), so contacts that the two laps resolved on different sides are resolved in the blend too, and
/// what then remains blended out; (b) the plain blend. The shallower is kept when it is no deeper than the
/// limit (the unclosed clip's deepest + 1 mm, or kClosureDepthFloorM if deeper) and adds no joint flips to
/// any character. A plain blend re-opened
/// contacts mid-way (issue 28: 17-66 mm on 1 s clips, 76 mm on a 4 s concert at 6.66/m^2, where the
/// unclosed clip has 0 and 16 mm), and so, less often, does (a); then each character takes (a), (b),
/// (c) the clip's START blended from `next_lap` (the corrector's next lap after the clip's own end;
/// loop_closure_choice.hpp, start_from_next_lap), (d) its arms alone closed toward the lap's
/// (close_joints: both, left, right), or (e) its upper body or arms from the next lap up to a cut inside
/// the clip (cut_joints_from_next_lap; session 16), whichever keeps everyone within the limit
/// (close_per_character: the descent over (a)-(c), then the join over all), or stays unclosed: a seam for
/// some rather than a collision. The next lap is stepped only for that choice. progress (optional) is
/// advanced once per step of (a) (the next lap advances it for its own steps).
void close_loop(const CrowdAnimation& input, const std::vector<std::vector<Pose>>& preroll_out,
                NextLap& next_lap, Corrector before_window, const CorrectorParams& params,
                CrowdAnimation& out, CorrectionReport& r, Progress* progress) {
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
    if (progress) progress->advance();
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
  const double unclosed_m = deepest(out, 0, frames);
  const double limit = std::max(unclosed_m + kClosureDepthSlackM, kClosureDepthFloorM);
  const double d_finished = deepest(finished, first, frames), d_blended = deepest(blended, first, frames);
  spdlog::debug(
      "correct_crowd: loop closure depths (m): unclosed {:.4f}, corrected blend {:.4f}, blend {:.4f}",
      unclosed_m, d_finished, d_blended);
  // Whole-crowd closures too must add no joint flips to any character (without_new_flips), as the
  // per-character ones must. Session 26: the demo's 2 s clips at 3.33/m^2 took the corrected blend whole
  // and gained 9 flips (feet and a hand inside the window) over the unclosed clip's 0.
  const std::vector<long> unclosed_flips = flips_per_character(input, out);
  std::vector<std::vector<bool>> allowed = {without_new_flips(input, finished, unclosed_flips),
                                            without_new_flips(input, blended, unclosed_flips)};
  const bool finished_ok = d_finished <= limit && all_allowed(allowed[0]);
  const bool blended_ok = d_blended <= limit && all_allowed(allowed[1]);
  if (finished_ok && (!blended_ok || d_finished <= d_blended)) {
    out = std::move(finished);
    r.loop_closure = "corrected blend";
  } else if (blended_ok) {
    out = std::move(blended);
    r.loop_closure = "blend";
  } else {
    close_per_character(input, preroll_out, next_lap, params, finished, blended, unclosed_flips,
                        std::move(allowed), limit, out, r);
  }
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

/// The last `window` frames of every character of a clip (poses[c][k]: frame N - window + k).
std::vector<std::vector<Pose>> last_frames(const CrowdAnimation& clip, int window) {
  std::vector<std::vector<Pose>> poses;
  for (const CharacterAnimation& c : clip.characters)
    poses.emplace_back(c.frames.end() - window, c.frames.end());
  return poses;
}

/// Laps recorded after the first, each only while the closure of the last one leaves a character open
/// (loop_closure_laps.hpp, session 19). Measured on the 4 s concert at 6.66/m^2, seed 2024000001 (the
/// first lap leaves 3 open, world seam 1.88x, deepest 10.0 mm): laps 5-8 seam 1.30 / 1.33 / 1.62 / 1.49x,
/// deepest 16.5 / 16.5 / 12.6 / 13.4 mm (their unclosed clips 15.5 / 16.5 / 11.8 / 12.5 mm), so none is
/// kept; more laps would cost one correction of the clip each (docs/stimuli.md, session 19).
constexpr int kExtraLaps = 1;

/// What decides between recorded laps (keep_extra_lap) for a closed clip and its closure's report.
ClosedLap closed_lap(const CrowdAnimation& clip, const CorrectionReport& r) {
  return {world_seam_step_ratio(clip), deepest(clip, 0, clip.frame_count()), r.loop_open_characters};
}

/// Where the closure of the recorded clip `out` leaves characters open (r.loop_open_characters > 0): the
/// next lap stepped whole and recorded in the clip's place, its own end blending into the clip's
/// (`lead_end`: the unclosed clip's last W frames), closed as the clip was (close_loop), and kept in the
/// clip's place when keep_extra_lap says so (a smaller seam, no deeper contact). Then (up to kExtraLaps)
/// its next lap likewise while its closure leaves characters open.
/// progress (optional): the clips that need an extra lap are not known before (correction_steps), so each
/// extra lap grows the total by the steps it adds, F + W: the lap's frames not yet stepped as the last next
/// lap (F - s, whose s are counted), its closure's re-corrected window (W), and its own next lap's bound
/// (2W at most), less what the last next lap's bound left uncounted (2W - s). Why (session 20): uncounted,
/// the progress sat at 100 % for a whole lap (a 20 s concert clip: minutes) before the output was written.
/// The last next lap's frames never read are counted done at the end, as correct_crowd_once does.
void record_extra_laps(const CrowdAnimation& crowd, const CorrectorParams& params, NextLap next_lap,
                       std::vector<std::vector<Pose>> lead_end, CrowdAnimation& out, CorrectionReport& r,
                       Progress* progress) {
  const int frames = crowd.frame_count(), window = static_cast<int>(lead_end.front().size());
  ClosedLap kept = closed_lap(out, r);
  int rejected = r.rejected_steps;  // over every lap and closure (the next lap's counted when spent)
  int open = r.loop_open_characters;
  for (int extra = 1; extra <= kExtraLaps; ++extra) {
    if (progress)
      progress->grow(static_cast<size_t>(frames + window),
                     fmt::format("an extra lap for {} open character{}", open, open == 1 ? "" : "s"));
    RecordedLap lap = std::move(next_lap).record();
    CorrectionReport lap_r;
    lap_r.frames = frames;
    lap_r.settle_steps = r.settle_steps;
    lap_r.preroll_frames = (kLeadLaps + extra) * frames;
    lap_r.unconverged_steps = lap.unconverged_steps;
    lap_r.contacts_mean = lap.contacts_mean;
    lap_r.cg_iterations_mean = lap.cg_iterations_mean;
    rejected += lap.rejected_steps;
    std::vector<std::vector<Pose>> lap_end = last_frames(lap.clip, window);
    next_lap = NextLap(std::move(lap.after), crowd, window, progress);
    close_loop(crowd, lead_end, next_lap, std::move(*lap.before_window), params, lap.clip, lap_r, progress);
    lap_r.next_lap_frames = next_lap.stepped();
    rejected += lap_r.rejected_steps;  // the closure's re-corrected window
    const ClosedLap closed = closed_lap(lap.clip, lap_r);
    const bool keep = keep_extra_lap(kept, closed, kClosureDepthFloorM);
    spdlog::debug(
        "correct_crowd: extra lap {}: seam {:.3f}x (kept {:.3f}x), deepest {:.4f} m (kept {:.4f} m), open {} "
        "(kept {}), closure: {}; {}",
        extra, closed.seam_step_ratio, kept.seam_step_ratio, closed.deepest_m, kept.deepest_m,
        closed.open_characters, kept.open_characters, lap_r.loop_closure, keep ? "kept" : "not kept");
    if (keep) {
      out = std::move(lap.clip);
      r = lap_r;
      kept = closed;
    }
    r.extra_laps = extra;
    open = closed.open_characters;
    if (open == 0) break;
    lead_end = std::move(lap_end);
  }
  r.rejected_steps = rejected + next_lap.rejected_steps();
  count_unread_next_lap(progress, next_lap, frames, window);
}

}  // namespace

bool follows_root_offsets(const CrowdAnimation& crowd, const CorrectorParams& params) {
  return params.follow_root_smoothing_s > 0.0 && loop_window_frames(crowd, params) == 0;
}

std::size_t correction_steps(const CrowdAnimation& crowd, const CorrectorParams& params) {
  const auto frames = static_cast<size_t>(crowd.frame_count());
  const auto window = static_cast<size_t>(loop_window_frames(crowd, params));
  if (window > 0)
    return (1 + kLeadLaps) * frames + window +
           static_cast<size_t>(next_lap_bound(static_cast<int>(frames), static_cast<int>(window)));
  return follows_root_offsets(crowd, params) ? 2 * frames : frames;
}

// correct_crowd itself (one run, two where it follows the root offsets, more with anticipated contacts) is
// in anticipate_contacts.cpp.
CrowdAnimation correct_crowd_once(const CrowdAnimation& crowd, const CorrectorParams& params,
                                  Progress* progress, CorrectionReport* report) {
  validate_crowd(crowd, "correct_crowd");
  std::vector<BodyShape> shapes;
  shapes.reserve(crowd.characters.size());
  for (const CharacterAnimation& ch : crowd.characters) shapes.push_back(ch.shape);
  Corrector corrector(std::move(shapes), params, crowd.environment, crowd.meta.fps);

  const size_t n = crowd.characters.size();
  const int frames = crowd.frame_count();
  std::vector<Pose> targets(n);
  CorrectionReport r;
  r.frames = frames;
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
  // The recorded lap, from the last lead lap's end; the corrector as it stood before frame N - W is kept
  // for the loop closure below, which runs on from there.
  RecordedLap recorded = NextLap(std::move(corrector), crowd, window, progress).record();
  CrowdAnimation out = std::move(recorded.clip);
  r.rejected_steps += recorded.rejected_steps;
  r.unconverged_steps += recorded.unconverged_steps;
  r.contacts_mean = recorded.contacts_mean;
  r.cg_iterations_mean = recorded.cg_iterations_mean;
  if (recorded.before_window) {
    // The next lap, continuing from the clip's end (start_from_next_lap, cut_joints_from_next_lap), stepped
    // only as far as the closure reads it; the progress counts the frames it may read.
    NextLap next_lap(std::move(recorded.after), crowd, window, progress);
    if (spdlog::should_log(spdlog::level::debug))
      spdlog::debug("correct_crowd: the recorded lap ends {:.4f} m from the lead lap (worst character)",
                    lap_difference_m(out, lead_end));
    std::vector<std::vector<Pose>> recorded_end = last_frames(out, window);
    close_loop(crowd, lead_end, next_lap, *recorded.before_window, params, out, r, progress);
    r.next_lap_frames = next_lap.stepped();
    if (r.loop_open_characters > 0) {
      // The next lap's frames not read yet are recorded as the extra lap (counted there).
      record_extra_laps(crowd, params, std::move(next_lap), std::move(recorded_end), out, r, progress);
    } else {
      r.rejected_steps += next_lap.rejected_steps();
      count_unread_next_lap(progress, next_lap, frames, window);
    }
    if (spdlog::should_log(spdlog::level::debug)) log_seam_carriers(out);
  }
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
