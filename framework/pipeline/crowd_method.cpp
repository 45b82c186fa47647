#include "framework/pipeline/crowd_method.hpp"

namespace crowdlab {

CrowdMethod crowd_method(const Condition& condition) {
  const FactorLevel* level = condition.level("method");
  return level && level->text == crowd_method_name(CrowdMethod::corrected) ? CrowdMethod::corrected
                                                                           : CrowdMethod::baseline;
}

const char* crowd_method_name(CrowdMethod method) {
  return method == CrowdMethod::corrected ? "ours" : "baseline";
}

}  // namespace crowdlab
