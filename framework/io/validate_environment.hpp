#pragma once
// Checks an Environment at a boundary (file readers and writers).
#include <string>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

/// Throws InputError "<context>: box <k>: ..." / "<context>: mesh '<name>': ..." when a box has a
/// non-finite centre or rotation or non-positive half extents, or a mesh has no triangles, non-finite
/// vertices or indices out of range.
void validate_environment(const Environment& env, const std::string& context);

}  // namespace crowdlab
