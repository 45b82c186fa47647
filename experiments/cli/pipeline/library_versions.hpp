#pragma once
// Versions of every library the `crowdlab` binary was built against: the framework's (crowdlab, Eigen)
// plus the stimuli stage's (OpenCV, libavcodec, libavformat). Recorded in every provenance sidecar.
#include <nlohmann/json.hpp>

namespace crowdlab::cli {

nlohmann::json library_versions();

}  // namespace crowdlab::cli
