#pragma once
// The viewpoint a condition is shown from: its `viewpoint` factor level when the spec has that factor,
// else the default of the spec's scenario type (default_viewpoint() in core/viewpoint_catalogue.hpp:
// "pair" for pair_crossing, "tracking" for flow_a, "V1" otherwise). Chosen here, once, for the
// pipeline's render stage; the level itself was validated against the catalogue when the spec loaded.
#include <string>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

std::string condition_viewpoint(const ExperimentSpec& spec, const Condition& condition);

}  // namespace crowdlab
