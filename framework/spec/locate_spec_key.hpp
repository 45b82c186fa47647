#pragma once
// Where a key of a spec file is (file:line:column), for the stages that check what a spec refers to after
// it was loaded: the manifold mesh is read by the surface stage, and its problems (an unreadable OBJ, a
// crowd too large for its area) must still name the spec's line, in `validate` and in `run` (issue 33).
#include <string>

#include "framework/core/error.hpp"

namespace crowdlab {

/// SourceLocation{spec_path, line, column, key_path} of the value of the dotted `key_path`
/// ("scenario.mesh", or with list items "animation.walk_clips[1].file"); line and column are 0 when the file
/// or the key cannot be found.
SourceLocation locate_spec_key(const std::string& spec_path, const std::string& key_path);

}  // namespace crowdlab
