#pragma once
// The JSON form of a crowd's metrics, shared by `crowdlab metrics --json` and the per-crowd
// metrics.json files that `crowdlab run` writes (volumes in litres, lengths in metres, angles in
// degrees); and of a correction's quality measures against its input (framework/metrics/
// correction_quality.hpp and foot_contact_quality.hpp), shared by `crowdlab metrics --input`,
// `bench correct --quality --json`, `reproduce gomez2024` and the metrics.json of `crowdlab run`
// (its "correction_quality" object).
#include <nlohmann/json.hpp>

#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/measure_crowd.hpp"

namespace crowdlab {

/// Summary, per-character means and colliding pairs; per-frame series too when `per_frame`.
nlohmann::json crowd_metrics_json(const CrowdMetrics& m, bool per_frame);

/// Depth, joint deviation, stance-foot drift, foot pops (with their frames), ground penetration and
/// floating of the feet; free-limb deviation, joint flips (the first few listed) and environment
/// penetration (issue 27), with where their worst cases are (character, SMPL joint name, frame).
nlohmann::json correction_quality_json(const CorrectionQuality& q);

}  // namespace crowdlab
