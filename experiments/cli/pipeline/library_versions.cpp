#include "experiments/cli/pipeline/library_versions.hpp"

#include <opencv2/core/version.hpp>

#include "framework/pipeline/provenance.hpp"

extern "C" {
#include <libavcodec/version.h>
#include <libavformat/version.h>
}

namespace crowdlab::cli {

nlohmann::json library_versions() {
  nlohmann::json j = framework_library_versions();
  j["opencv"] = CV_VERSION;
  j["libavcodec"] = LIBAVCODEC_IDENT;
  j["libavformat"] = LIBAVFORMAT_IDENT;
  return j;
}

}  // namespace crowdlab::cli
