#pragma once
// CorrectorParams: every tunable constant of the collision-correction solver (seed 000 §3.2-3.4),
// with its unit and the source of its default. The paper gives d = 0.006 and the structure of the
// terms but not the other numbers; where it is silent the choice and its reason are written here.
//
// Gain normalisation (our choice, the paper is silent on units): the control gains k and d of
// Eq. 4 are given PER UNIT OF EFFECTIVE INERTIA. Joint j's spring and damper are multiplied by the
// composite rotational inertia of the subtree it drives (kg m^2, rest pose, about the joint), the
// root translation by the total body mass (kg). One (k, d) pair therefore gives every joint the same
// natural frequency sqrt(2 k) rad/s and the same damping behaviour, from the hand to the trunk, the
// usual "inertia-scaled PD gains" choice (e.g. Tan, Liu & Turk 2011, "Stable proportional-derivative
// controllers", §4). With this normalisation d is dimensionless in the sense of Eq. 4 (its Frobenius
// norm of a rotation difference is ~ sqrt(2) x the angle).
//
// Damping normalisation (our choice, the paper is silent): the damper of every term is d times that
// term's spring, i.e. stiffness-proportional (Rayleigh) damping (the standard choice in structural
// dynamics and simulation, e.g. Bathe 1996, "Finite Element Procedures", ch. 9). With Eq. 4's d/h^2 the
// damping force is (d/h) k v_dev, so beta = d/h (s) and the damping ratio of a term with natural
// frequency w_n is zeta = (d/h) w_n / 2. At 30 fps and d = 0.006: zeta ~ 0.6 for the root translation
// (w_n ~ 6.3 rad/s) and ~ 1.4 for the joints (w_n ~ 15.5 rad/s), i.e. close to critical: the paper's
// "closely matches the target" (Fig. 4). d = 0 leaves only backward Euler's numerical damping (the
// body rings for seconds), d = 0.06 and 0.6 give zeta ~ 6-140 (the recovery drifts), as in Fig. 4.
// (Session 1 scaled d by the effective inertia instead, which left d = 0.006 at zeta ~ 0.14, visibly
// oscillating, and made d = 0.06 the best value, contradicting Fig. 4.)
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>

#include "framework/core/joint_scope.hpp"

namespace crowdlab {

/// The set of the given joints (bit j = joint j).
constexpr BoneMask joint_set(std::initializer_list<int> joints) {
  BoneMask m = 0;
  for (int j : joints) m |= BoneMask{1} << j;
  return m;
}

/// Groups of joints for CorrectorParams::rate_limited_joints, by the names parse_joint_set takes.
/// "light": the distal joints, limited since session 9 (of 11,467 flips of a 3 s corridor at 6.66 /m^2
/// without a limit, 7,774 were hands, 2,204 wrists, 1,177 balls, 218 ankles).
inline constexpr BoneMask kLightJoints = joint_set(
    {kLeftWrist, kRightWrist, kLeftHand, kRightHand, kLeftAnkle, kRightAnkle, kLeftFoot, kRightFoot});
/// "elbows": limited since session 13 (stationary 6.66 /m^2: 214 elbow flips -> 0, docs/correction.md).
inline constexpr BoneMask kElbowJoints = joint_set({kLeftElbow, kRightElbow});
/// "head": neck and head; "shoulders": collars and shoulders (upper arms). Limited since session 15: on
/// 3 s gomez2024 clips the stationary crowd at 6.66 /m^2 had 21 head and shoulder flips, turned by the
/// Newton step; limited, 0, and p99 depth 12.5 -> 5.1 mm (docs/correction.md).
inline constexpr BoneMask kHeadJoints = joint_set({kNeck, kHead});
inline constexpr BoneMask kShoulderJoints =
    joint_set({kLeftCollar, kRightCollar, kLeftShoulder, kRightShoulder});
inline constexpr BoneMask kDefaultRateLimitedJoints =
    kLightJoints | kElbowJoints | kHeadJoints | kShoulderJoints;

struct CorrectorParams {
  // ---- Control, Eq. 4 (spring 1/2 k ||R - R_hat||_F^2, damper 1/2 d/h^2 ||R - R_old - R_hat +
  // R_hat_old||_F^2)
  /// Spring k for relative joint rotations (1/s^2, per unit effective inertia). 120 gives a natural
  /// frequency of sqrt(240) ~ 15 rad/s (2.5 Hz): soft enough that neighbours push limbs aside, stiff
  /// enough to recover within ~0.5 s (seed 000 Fig. 4 shows recovery within about a second). Measured
  /// at 6.66 /m^2 (docs/correction.md): mean joint deviation 6.3 deg stationary, 10.1 deg corridor
  /// (target <= 10 deg); 8.5 deg corridor with the rotation trust region below (2 s runs).
  double stiffness = 120.0;
  /// Damping d of Eq. 4 on the deviation velocity (s^2: the damper is d x the spring, see the header).
  /// Default 0.006: seed 000 §4.2 and Fig. 4.
  double damping = 0.006;
  /// Gain multiplier for the pelvis (root) and the feet (ankle and foot bones): seed 000 §3.3 "for the
  /// pelvis and the feet we use higher spring and damping coefficients" (value not given; 10x chosen so
  /// the root and the feet move ~3x less than other joints under the same push).
  double stiff_joint_gain = 10.0;
  /// Root translation spring (1/s^2, per kg of body mass, times stiff_joint_gain); the root is held
  /// absolutely (seed 000 §3.3). 4 x 10 = 40 1/s^2: a 70 kg body is held at 2800 N/m (natural frequency
  /// ~1 Hz), soft against contact forces so that crowded bodies give way instead of interpenetrating.
  double root_translation_stiffness = 4.0;
  /// World-position spring holding a PLANTED foot's ankle and ball joints on their anchors: the landing
  /// point horizontally, the input's height vertically (issue 18: held horizontally only, whole bodies
  /// floated 2-5 cm on their planted feet; stage_foot_holds.cpp, foot_goal) (1/s^2, per kg of body
  /// mass; multiplied by stiff_joint_gain; the damper is the root's). Seed 000
  /// §3.3 raises the feet gains "to avoid footskate"; relative joint rotations alone cannot hold a foot
  /// once the leg above it is pushed, so, like the root, planted feet are coupled in world space, and
  /// after each step the leg IK of stage_foot_holds.cpp puts them back exactly. 400 x 10 = 4000 1/s^2
  /// (2.8e5 N/m for 70 kg, ~10x a contact): the solve then knows a planted foot will not move and
  /// lets the rest of the body (and the other body) give way. Measured on gomez2024's corridor at
  /// 6.66 /m^2 (4 s): 40 -> 400 raised the overlap removed from 93.1 % to 96.6 % and lowered the mean
  /// deviation from 10.3 to 9.7 deg (docs/correction.md).
  double foot_anchor_stiffness = 400.0;
  /// World-position spring pulling a SWINGING foot's ankle and ball joints toward their targets (1/s^2,
  /// per kg, x stiff_joint_gain; the root's damper on the deviation velocity). 4 x 10 = 40 1/s^2
  /// (2,800 N/m for 70 kg, a tenth of a contact): swinging legs still step around neighbours' legs,
  /// but feet keep landing near where the input puts them. Without it, held feet planted wherever the
  /// swing ended and the crowd drifted: gomez2024's corridor at 6.66 /m^2 over the paper's 20 s kept
  /// only 89.9 % of the overlap removed (12.4 deg deviation, 62 mm skate). Measured over 20 s at 2.22 /
  /// 3.33 / 6.66 /m^2: 4 -> 97.8 / 98.7 / 98.1 % removed (8.0 deg at 6.66); 10 -> 97.2 / 98.1 / 97.6 %;
  /// and over 4 s, 10 left only 95.3 % at 2.22 /m^2 where 4 leaves 97.1 %. The session-2 rule (every
  /// foot on its target at 40) removes as much but slides planted feet by ~10 cm.
  double swing_foot_stiffness = 4.0;
  /// Foot holds (stage_foot_holds.cpp): a foot joint whose input moves slower than this (m/s) while
  /// below foot_plant_height_m is planted, and the corrected foot is held where it landed. 0.03 m/s
  /// is 1 mm per frame at 30 fps, the criterion of the skate measure (correction_quality.hpp).
  double foot_plant_speed_mps = 0.03;
  /// Highest a planted foot joint (ankle or ball) may be above the ground (m): 15 cm, above an adult
  /// ankle joint (~8-10 cm) with room for shoes and uneven input, below any swing-phase foot.
  double foot_plant_height_m = 0.15;
  /// A held foot whose solved ankle and ball are within this distance (m) of their anchors is left
  /// as the solve put it (no leg IK). 1 mm: a tenth of the skate target, and far below what shows at
  /// the viewing distances of the stimuli; a near-straight leg would otherwise bend its knee by degrees
  /// to move the ankle by a fraction of a millimetre. The world spring keeps pulling it to the anchor.
  double foot_hold_tolerance_m = 0.001;

  // ---- Joints (soft constraint keeping a child's joint on its parent's attachment point)
  /// Joint spring (1/s^2, multiplied by the child bone's mass to give N/m). 1e5 keeps the joint gap
  /// below a millimetre under contact forces; it is stiff, which backward Euler tolerates (Gast et al.
  /// 2015). The gap is removed anyway when the state is projected back to a pose after each step.
  double joint_stiffness = 1.0e5;

  // ---- Collisions, E = 1/2 k_delta delta^2 (seed 000 §3.4)
  /// Penalty stiffness k_delta (N/m). 3e4 N/m, measured on the real scenarios (`crowdlab experiment
  /// overlap-vs-density --duration 2`, contacts detected at the predicted state, Rayleigh damping):
  /// 1e4 removes 99.2-99.4 % of the stationary overlap but only 77-94 % in the corridor; 3e4 removes
  /// 99.0-99.7 % and 93-98.5 %, with the mean joint deviation still <= 10 deg at 6.66 /m^2 (5.6 -> 6.3
  /// deg stationary, 8.5 -> 9.9 deg corridor). Stiffer contacts cost CG iterations (~9 -> ~12). With
  /// the session-1 start-of-step detection a stiffer penalty chattered on light bones and ended
  /// deeper (p99 1.5 cm at 1e4, 3.5 cm at 1e5); detecting at the predicted state removed that limit.
  double contact_stiffness = 3.0e4;
  /// Intra-body (self) penalty stiffness (N/m), a third of the inter-body one (ours; the paper gives
  /// both terms the same form and no values). The input animations already interpenetrate themselves
  /// (the procedural dance's forearms pass 11-16 mm into their own torso on average), and a forearm
  /// caught between its own torso and a neighbour's is pressed from both sides: with equal stiffness
  /// the two contacts cancel and it stays inside the neighbour. Measured on gomez2024 (4 s, before
  /// swing_foot_stiffness existed; 1e4 against 3e4): corridor overlap removed 96.6-99.9 % ->
  /// 97.1-99.8 %, p99 inter-body depth at 4.44 /m^2 51 -> 35 mm and at 6.66 /m^2 59 -> 57 mm, mean
  /// deviation at 6.66 /m^2 9.7 -> 9.2 deg; the arm-torso self-contacts left stay shallow (2 s runs:
  /// mean 4-5 mm, against 11-16 mm in the input).
  double intra_body_contact_stiffness = 1.0e4;
  /// Contact offset (m) for inter-body contacts: the penalty acts on depth + offset, as if every
  /// capsule were this much thicker (the "collision margin" of Bullet / PhysX contact offset). With
  /// one linearised step per frame a penalty contact chatters at the surface where it switches on;
  /// the offset moves that surface outward, so the true interpenetration stays below what one frame
  /// of motion carries in. 1 cm is invisible at the viewing distances of seed 000's stimuli and halves
  /// the residual overlap volume on the dense fixture.
  double contact_offset_m = 0.01;
  /// Ground penalty stiffness (N/m) per capsule end sphere touching y = 0 (the feet are also anchored,
  /// so the ground only matters for bodies pushed down).
  double ground_stiffness = 3.0e4;
  /// Environment penalty stiffness (N/m) per capsule, shared among the sample points it touches.
  double environment_stiffness = 3.0e4;
  /// Point spacing (m) used to sample static environment boxes and meshes (seed 000 §3.4).
  double environment_sample_spacing_m = 0.03;
  /// Most environment sample points the correction may make; more is refused before sampling, with the
  /// estimate (environment_point_tree.hpp). 10 million points take about 400 MB with their tree and
  /// cover the faces of a 60 x 60 x 3 m box at 3 cm; a 1000 m wide box would have taken a billion
  /// (issue 21: `correct` used 3.1 GB and ran out). `crowdlab correct --max-environment-points`.
  double max_environment_points = 1e7;

  // ---- Inertia and gravity
  /// Whole-body density (kg/m^3). Adult whole-body density measured by hydrostatic weighing lies in
  /// 1010-1060 kg/m^3 (Siri 1961; Brozek et al. 1963, "Densitometric analysis of body composition");
  /// 1045 is the middle of the lean-to-average range, matching core's ~70 L for a 75 kg man.
  double body_density_kg_m3 = 1045.0;
  /// Gravity (m/s^2), along -Y (E_gravity of Eq. 3).
  double gravity_mps2 = 9.81;
  /// When true (default) the controller adds gravity-compensation forces (Coros, van de Panne et al.
  /// 2010, "Generalized biped walking control", §4.3): the input animation already carries its own
  /// balance, so without contact the body reproduces it exactly instead of sagging by W / (2 k).
  bool gravity_compensation = true;

  /// Longest time step (s): a clip whose frames are farther apart is corrected in n substeps per frame,
  /// n = ceil(frame time / max_step_s) (a frame time up to 1 % longer still takes one step), the targets
  /// interpolated between the last frame's and this frame's (roots lerped, rotations slerped; the output
  /// is the last substep's). Why (session 26): every parameter above was tuned at 30 fps, and the solve
  /// is one linearised step; the demo's 15 fps clips, stepped once per frame, ended with a p99 capsule
  /// depth of 30 mm and a p99 deviation of 58 deg at 6.66 /m^2 where the same crowd at 30 fps has 8.4 mm.
  double max_step_s = 1.0 / 30.0;

  // ---- Offline correction (correct_crowd only; the online Corrector ignores it)
  /// Steps run on the first frame's targets before the output starts (see correct_crowd.hpp). 30 steps
  /// = 1 s at 30 fps: about two periods of the root's translation spring (natural frequency ~1 Hz,
  /// above), enough for the dense fixture's initial interpenetration to be pushed out.
  int settle_steps = 30;
  /// Looping clips (issue 28): > 0 and the input loops (every root's last frame within kLoopRootM of its
  /// first), the corrector settles on frame 0 and corrects four whole laps of the clip unrecorded before
  /// frame 0, so frame 0 continues from the state a lap ends in; the clip's last loop_preroll_s seconds of
  /// frames (at most N - 1) then blend into the last lap's (correct_crowd.hpp). 0: off (the online
  /// corrector and clips that play once).
  double loop_preroll_s = 0.0;
  /// Walking crowds (session 27; follow_root_offsets.hpp): > 0 and the clip is not corrected into a loop,
  /// correct_crowd corrects twice: half the first correction's horizontal root offsets, smoothed by a
  /// Gaussian of this sigma (s), move the input's roots and footprints (the legs re-posed onto them), and the
  /// second correction runs on that input from scratch. 0: one correction (the default here, for the
  /// online corrector and for crowds that stand). The run sets kWalkingFollowRootS for crowds that walk
  /// and play once (pipeline/crowd_recipes.hpp); a clip corrected into a loop keeps one correction, as its
  /// footprints, moved by the first correction's open offsets, would not loop.
  double follow_root_smoothing_s = 0.0;

  // ---- Solver
  // One Newton iteration per step, always (seed 000 §3.2: "just one Newton iteration per time step
  // worked well"); the assemble stage linearises at the start-of-step state.
  /// Preconditioned CG: stop when ||r|| <= cg_tolerance * ||b||, the forcing term of an inexact Newton
  /// step (Dembo, Eisenstat & Steihaug 1982). 1e-2 gave the same overlap, depth and deviation as 1e-4
  /// on the dense fixture with a quarter of the CG iterations. Since the depenetration pass removes what
  /// the step leaves, 2e-2: on gomez2024 (4 s per density) the p99 depth, overlap and deviation stay
  /// within run-to-run spread of 1e-2 (docs/correction.md), and CG takes 9 iterations instead of 12 at
  /// 200 characters (6.3 instead of 7.0 ms per step with the pass).
  double cg_tolerance = 2e-2;
  int cg_max_iterations = 100;
  /// Where contacts are detected (corrector_step.hpp): true = at the exact contact-free solution of the
  /// step (one extra tree factorisation per character), false = at the inertial prediction
  /// q_old + h v_old + h^2 a_target (no extra cost; the target's acceleration is the feed-forward).
  bool exact_prediction = true;
  /// Active set for the one-sided contact penalty (stage_solve.cpp): how many times per step the
  /// system is re-solved after removing contacts whose linearised depth ends negative ("pulling").
  /// Default 0 (off): on the dense fixture it doubles the CG iterations and changes the overlap left
  /// by < 0.1 percentage points; a pulling contact pulls at most by its 1 cm contact offset.
  int active_set_passes = 0;
  /// A step is rejected (the last stable state kept) if any bone would move faster than this (m/s).
  /// Human segment speeds stay below ~15 m/s even in throwing (Winter 2009); 50 leaves ample room.
  double max_bone_speed_mps = 50.0;
  /// Trust region on each bone's rotation increment (rad per step), measured from the contact-free
  /// step dq_free (stage_integrate.cpp); 0 = off. The Newton system linearises every point of a bone
  /// as dx + dtheta x r, which is only valid for small dtheta (the error is |r| |dtheta|^2 / 2): the
  /// standard remedy is to restrict the step to where the model holds (trust-region / step-length
  /// control, Nocedal & Wright 2006, "Numerical Optimization", ch. 4). Measured without it (corridor,
  /// 6.66 /m^2): light distal bones (hands, toes: tiny rotational inertia and control gain) took
  /// contact responses of 3-9 rad in ONE step, after which the projection snapped them back; this left
  /// a p99 joint deviation of ~90-100 deg. 0.5 rad per step (15 rad/s at 30 fps, above the segment
  /// angular velocities of walking and dancing) removes those spins and leaves ordinary contact
  /// responses untouched (docs/correction.md).
  double max_rotation_step_rad = 0.5;
  /// Depenetration pass (stage_depenetrate.cpp): at most how many times per step the inter-body capsule
  /// pairs of the projected poses deeper than depenetration_tolerance_m are pushed apart by the
  /// least-energy pose change; 0 = off (the paper's one Newton step alone). Each pass clears ~40 % of
  /// what is left (Jacobi over characters). Measured on the corridor at 6.66 /m^2 (4 s, an earlier
  /// variant without the joint-weight floor): p99 inter-body depth 14 / 10 / 7.7 mm after 6 / 10 / 16
  /// passes. With the floor, 8 passes give 7.8 mm there and 0.1-8.6 mm over all of gomez2024
  /// (docs/correction.md), for ~0.3 / 0.9 ms per step at 60 / 200 characters (with the wider narrow
  /// phase that lists its pairs).
  int depenetration_passes = 8;
  /// Depth (m) above which the depenetration pass separates a capsule pair (to touching). 5 mm: half
  /// the 1 cm p99 target and invisible at the stimuli's viewing distances; 2 mm cost 50 % more
  /// solves for the same p99.
  double depenetration_tolerance_m = 0.005;
  /// Foot motion budget (m per step) in the depenetration pass (stage_depenetrate.cpp, issue 18): a
  /// foot joint (ankle, ball) may move in one step at most this much farther than its input moved;
  /// beyond it, it becomes a row of the pass's least-energy solve that pulls it back onto the budget,
  /// and the rest of the two bodies is moved instead. The foot-pop measure flags 5 cm
  /// (metrics/foot_contact_quality.hpp). Measured on gomez2024 at 6.66 /m^2 (4 s, corridor): 0 (off)
  /// -> 69 foot pops, worst excess 19.9 cm, p99 depth 5.3 mm; 3 cm -> 1 pop (5.4 cm), 7.6 mm; 2 cm ->
  /// 0 pops (worst 3.7 cm), 6.3 mm, the same mean deviation (7.3 deg); 4 cm -> 1 pop, 7.3 mm. Runs are
  /// chaotic: on a 2 s clip of another crowd 2 / 3 / 4 cm left 1 / 3 / 1 pops of 78 with procedural
  /// bodies (p99 depth 19.9 / 12.4 / 11.5 mm against 10.7 without) and 2 of 12 with MPFB2 bodies at 2 cm.
  /// Since session 8 the pass prioritises these rows (kFootBudgetRowWeight) and a planted foot returns
  /// to the input's height at most at this rate: 0 pops on every 20 s clip of gomez2024.
  /// 0 = off.
  double foot_pop_budget_m = 0.02;

  // ---- Free joints (stage_free_joints.cpp, issue 27): the correction changes only what collides
  /// Release of free joints: a joint whose contact scope (core/joint_scope.hpp: the bones it moves;
  /// the whole body for the pelvis and the legs) has not been within free_joint_margin_m of another
  /// character or an environment box for free_joint_hold_s is returned to its input rotation (at most
  /// free_joint_return_radps), instead of keeping what the dynamics of a pushed body, self-contacts and
  /// the ground gave it. false = the session-8 solver (every joint follows the solve).
  bool release_free_joints = true;
  /// Capsule distance (m) at the predicted state within which a bone counts as in contact for the
  /// release: kNearMargin_m (4 cm), the depenetration pass's list, so every bone the pass may move is in
  /// contact.
  double free_joint_margin_m = 0.04;
  /// How long (s) a joint stays engaged after its scope was last in contact. Without a hold, a limb
  /// leaving a contact would return toward an input that still reaches into the neighbour, be pushed
  /// again and chatter; 0.2 s is about one contact-response time of the joints (2.5 Hz springs).
  double free_joint_hold_s = 0.2;
  /// Rate (rad/s) at which a released joint's deviation from its input returns to zero. 3 rad/s is
  /// 5.7 deg per frame at 30 fps: 17 deg within 3 frames, under the flip measure's 20 deg
  /// (core/joint_flips.hpp), and a 45 deg deviation is gone in a quarter of a second.
  double free_joint_return_radps = 3.4;
  /// The joints that, while engaged, turn at most free_joint_return_radps from their last deviation, in
  /// the step and in the depenetration pass, where a joint's column gets weight 0 once its turn is used
  /// so that the joints that may still move, and the neighbour, separate the contact
  /// (stage_free_joints.cpp). At 30 fps the rate is 6.5 deg per frame, 19.5 deg within 3 frames: under
  /// the flip measure's 20 deg (core/joint_flips.hpp), so a limited joint never flips. A set over the
  /// 24 joints (bit j = joint j; parse_joint_set names them). Default kDefaultRateLimitedJoints. Not the
  /// knees and hips: held legs are posed by the leg IK after the limit, so their flips moved to the ankles
  /// and the legs stopped separating contacts (session 15, corridor 6.66 /m^2: 121-221 flips left, p99
  /// depth 9-10 -> 11-17 mm, 0 -> 9-24 foot pops, docs/correction.md).
  BoneMask rate_limited_joints = kDefaultRateLimitedJoints;
  /// Engaged knees whose ankles are rate-limited (and that are not in rate_limited_joints) are hinges for
  /// the rate limit: they keep the flexion about their hinge that the solve and the pass give them, and
  /// turn off it (abduction, twist about the shank) at most free_joint_return_radps from their last
  /// deviation, after the Newton step and in the depenetration pass (stage_free_joints.cpp). false = the
  /// session-15 solver (only the twist about the shank limited, after the step and the pass). Measured on
  /// 3 s corridor clips (session 16, docs/correction.md): held knees' flips changed 12-15 deg per flip
  /// window off the hinge on main; with the hinge, flips 21-34 -> 11-15 at 4.44 /m^2 and 192-273 ->
  /// 188-218 at 6.66 /m^2 over three runs each, p99 depth 5.0-6.2 -> 5.3-6.0 and 9.5-10.5 -> 7.0-9.5 mm.
  bool knee_hinge = true;
  /// Knees at lift-off (issue 27, sessions 17-18): an engaged knee of a leg whose foot is not held and
  /// whose last output is off the input's flexion by more than 3 turns of free_joint_return_radps turns at
  /// most that rate (all of it, flexion included; no leg IK sets it), after the Newton step and in the
  /// depenetration pass; and a foot held at its ball only (the input's heel rising) whose knee's flexion
  /// deviates by more than 4 such turns (26 deg at 30 fps) pivots about the ball, its knee returning at the
  /// rate (stage_foot_holds.cpp), so that what a stance built up (a held leg kept 15-37 deg straighter than
  /// the input's) is not turned back within 1-3 frames by the Newton step's pull at the end of the hold.
  /// Measured on 3 s corridor clips over three runs each (session 18, docs/correction.md): flips at 6.66
  /// /m^2 188-218 -> 144-195 (knees 93-98 -> 55-68), at 4.44 /m^2 11-15 -> 11-15. Session 17 let the ball
  /// go instead, and it slid (the walking corridor's foot skate 2.8 -> 17.2 cm): off by default until then.
  bool lift_off_knees = true;
  /// Held legs' twist in the depenetration pass (issue 27, session 19): the ankle of a held foot whose
  /// rotation the rate limits (rate_limited_joints) turns about its up axis (y) at most
  /// free_joint_return_radps from its last deviation, as a row of the pass's solve on the shank's world turn
  /// about that axis (depenetration_solve.hpp, AnkleTwist). The held foot keeps its world rotation, so the
  /// leg's swivel about its hip-ankle line, which the pass used to move knees out of contacts, became the
  /// ankle's twist when hold_feet re-planted the foot: 22-41 deg per flip window (session 18's trace).
  /// Measured on 3 s corridor clips over three runs each (session 19, docs/correction.md): flips at 6.66
  /// /m^2 144-195 -> 87-114 (ankles 57-77 -> 27-33, hips 27-50 -> 7-19), p99 depth 7.6-9.8 -> 8.5-9.1 mm,
  /// pops 0; at 4.44 /m^2 11-15 -> 10-19; the standing crowds' outputs unchanged. Off by default: on the
  /// 20 s corridor clip at 6.66 /m^2 it halves the ankle flips (914-933 -> 433-439) but pops 2-8 -> 8-14 and
  /// one foot ends 147-212 mm below the ground (main 50-64 mm), which no 3 s clip shows (session 19's merge).
  bool held_ankle_twist_in_pass = false;

  // ---- Feet on the ground (stage_depenetrate.cpp, stage_settle_feet.cpp, issue 27, sessions 12-13)
  /// Whether held feet are brought to the input's height: a held ball's goal height is its input's (not
  /// where it landed, shifted with the ankle); the depenetration pass asks each held foot joint for its
  /// goal height (low-priority rows beside the contacts, session 13), and the characters the pass did
  /// not pose have their root moved vertically (at most foot_pop_budget_m) last in the step so that
  /// held feet stand at their goal heights. false = the session-11 solver.
  /// Off by default: on 3 s corridor clips (session 13) the planted-foot float fell (p99 30.8 -> 16.2 mm
  /// at 6.66 /m^2, 20.2 -> 11.0 at 4.44) with the p99 inter-body depth within issue 18's 10 mm (9.6 -> 9.4,
  /// 6.8 -> 9.2 mm), but issue 27's feet targets (10 mm) are not met and at 4.44 /m^2 the feet below the
  /// ground went 25.5 -> 31.9 mm (docs/correction.md). Session 12's settle of every body after the pass
  /// raised the depth past 10 mm (12.3, 18.2 mm). `run` turns it on, with feet_above_input_ground, for crowds
  /// that walk on the flat ground (pipeline/crowd_recipes.hpp walking_correction; session 27).
  bool held_feet_at_input_height = false;
  /// Whether hold_feet lifts a foot (held or swinging) that lies more than 5 mm below the input's ground,
  /// min(0, the input's sole), back to 5 mm below it by the least-change leg IK (issue 27, session 17,
  /// stage_foot_holds.cpp: keep_feet_above_ground). false = the session-16 solver.
  /// Off by default: on the 3 s corridor clips (docs/correction.md, session 17, 3 runs each) the depth it
  /// adds below the ground falls from 17.5-21.0 to 5.9-6.0 mm at 4.44 /m^2 and 28.0-40.9 to 6.0 mm at
  /// 6.66 /m^2, but alone it flips more at 6.66 /m^2 (188-218 -> 200-267) and leaves the float. With
  /// held_feet_at_input_height too, the corridor's flips (8-12, 92-163), p99 depth (<= 9.3 mm) and the
  /// feet below the ground (<= 6 mm) meet their targets and the float falls (4.44 /m^2: 19.4-19.6 ->
  /// 11.0-11.2 mm; 6.66: 28.8-30.3 -> 16.0-19.4) with the stationary p99 depth at 7.3-9.3 mm. Not the
  /// default (session 19, main fe1feeb with the knee pivot): both on reach depth p99 10.5 mm and environment
  /// p99 5.2 mm in one of three runs at 6.66 /m^2, the dense fixture's 10.5 mm (a ball-only hold whose
  /// offset keeps a 60 deg tilt hangs its ankle 2.5-3.1 cm low), and on a 20 s corridor clip at 6.66 /m^2
  /// depth p99 9.8-11.2 mm and 1-3 foot pops (main 14.1-14.5 mm, 2-8 pops; float 38.7-39.4 -> 22.1-22.6,
  /// feet below 49.7-54.8 -> 6.0 mm; docs/correction.md "Session 19: the feet options at 20 s"). `run` turns
  /// both on for crowds that walk on the flat ground, where the corridor's feet targets need them (session
  /// 27: feet below the ground 5.3-6.7 mm at every density, docs/correction.md).
  bool feet_above_input_ground = false;

  // ---- Anticipated contacts (correct_crowd only; anticipate_contacts.hpp, issue 27, session 13)
  /// Which joints' contact deviations the offline correction anticipates: after a first run, each such
  /// joint's deviation from the input is ramped up before every contact and down after it at
  /// anticipation_rate_radps, and the ramped poses are the targets of another run. "none" (default: one
  /// run), "arms" (collars, shoulders, elbows), "upper" (arms, spine, neck, head), "legs" (hips, knees)
  /// or "all". Not the default (docs/correction.md, session 13): with "arms" the stationary flips at
  /// 6.66 /m^2 fell 226 -> 46 but the corridor's rose (4.44 /m^2: 39 -> 52), and each run folds the
  /// ramped elbows further; "all" let planted feet drift (p99 108-150 mm, 13-111 pops). The elbow rate
  /// limit (rate_limited_joints) removes more flips in one run.
  std::string anticipated_joints = "none";
  /// Rate (rad/s) of the ramps: at 30 fps 2.4 rad/s is 4.6 deg per frame, 13.8 deg within 3 frames, which
  /// leaves the next run 6 deg under the flip measure's 20 deg for what it adds.
  double anticipation_rate_radps = 2.4;
  /// Runs after the first when anticipated_joints is not "none", each ramping the previous run's
  /// deviations (each costs one more correction of the clip). Stationary 6.66 /m^2, "arms": flips 123
  /// after one, 42 after two, 25 after four, while the ramped elbows fold further each run.
  int anticipation_runs = 2;
};

/// Throws InputError naming the field when a parameter is out of range or not finite.
void validate_corrector_params(const CorrectorParams& params);

/// A joint set from a comma-separated list of group names ("none", "light", "elbows", "head": neck and
/// head, "shoulders": collars and shoulders, "spine", "hips", "knees") and SMPL joint names
/// ("right_knee"), e.g. "light,elbows,knees". Throws InputError naming the unknown item.
BoneMask parse_joint_set(std::string_view list);
/// The list parse_joint_set reads back into `set`: whole groups by their names, the rest by joint name.
std::string joint_set_name(BoneMask set);

}  // namespace crowdlab
