#pragma once
// The JSON form of a crowd's metrics, shared by `crowdlab metrics --json` and the per-crowd
// metrics.json files that `crowdlab run` writes (volumes in litres, lengths in metres).
#include <nlohmann/json.hpp>

#include "framework/metrics/measure_crowd.hpp"

namespace crowdlab {

/// Summary, per-character means and colliding pairs; per-frame series too when `per_frame`.
nlohmann::json crowd_metrics_json(const CrowdMetrics& m, bool per_frame);

}  // namespace crowdlab
