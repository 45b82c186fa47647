#pragma once
// Reading a crowd file written by write_crowd_glb() (layout: framework/io/crowd_glb_format.hpp).
#include <string>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

/// Reads and validates `path`. Everything is checked at this boundary: the glTF container (truncated or
/// corrupt files), every accessor it reads (type, count, bounds inside its buffer, finite values), the
/// node/skin structure, the animation channels (one per joint plus the root translation, key times
/// f / fps) and finally validate_crowd(). Quaternions are renormalised after the float round trip.
/// Throws InputError "<path>: <node/accessor/character>: <problem>" on any problem.
CrowdAnimation read_crowd_glb(const std::string& path);

}  // namespace crowdlab
