#pragma once
// The work limits of a study, in one place (docs/spec-reference.md "Work limits"). Checked before anything
// is enumerated or allocated (issue 21: specs whose factor levels multiplied out, or whose clips were an
// hour at 240 fps, ran the machine out of memory; issue 32: practice blocks, duplicate levels, synthetic
// and benchmark crowds escaped them). A spec or option beyond one is refused (exit 2) with the estimate
// and the limit; such a study is split into several specs.

namespace crowdlab {

/// Conditions of a spec: factor levels x repetitions, plus the practice conditions.
inline constexpr double kMaxConditions = 10000;
/// Characters of one crowd: density x area, the characters factor, scenario agents, `render
/// --synthetic`, `bench correct --characters`.
inline constexpr double kMaxCharactersPerCrowd = 10000;
/// Characters x frames of one crowd (duration_s x fps): every pose of every frame is kept in memory and
/// corrected, measured and rendered, so the work and memory of a crowd grow with this product.
inline constexpr double kMaxCharacterFrames = 2e6;
/// Size of a spec file (the demo is 3 kB; YAML parsing takes memory many times the text).
inline constexpr unsigned long kMaxSpecBytes = 4ul << 20;
/// Participants x Likert items of `analyze report` (each item's cumulative link mixed model has one random
/// intercept per participant): 500 participants x 6 items took 29 s at load 11, 2,000 ran for minutes
/// (issue 33). `analyze report --max-participant-items` raises it.
inline constexpr double kMaxReportParticipantItems = 6000;

}  // namespace crowdlab
