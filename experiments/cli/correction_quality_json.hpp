#pragma once
// The JSON form of a correction's quality measures (framework/metrics/correction_quality.hpp and
// foot_contact_quality.hpp), shared by `crowdlab metrics --input`, `bench correct --quality --json`
// and `reproduce gomez2024`. Lengths in metres, angles in degrees.
#include <nlohmann/json.hpp>

#include "framework/metrics/correction_quality.hpp"

namespace crowdlab::cli {

nlohmann::json correction_quality_json(const CorrectionQuality& q);

}  // namespace crowdlab::cli
