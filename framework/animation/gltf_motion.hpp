#pragma once
// Skinned-animation import from glTF 2.0 (.gltf / .glb, e.g. Mixamo characters converted to glTF), via
// tinygltf. The result is a BvhMotion (6 channels per joint: positions, then Z-X-Y Euler rotations in
// degrees), so the same retargeting (retarget.hpp) and looping apply to BVH and glTF sources alike.
//
// Skeleton: the joints of skin `skin_index` (or, for a file without skins, every node an animation
// targets plus their ancestors), ordered parents first. Non-joint ancestors of the skeleton roots
// (e.g. an "Armature" node with a 0.01 scale) are baked into the roots; a uniform scale on the path
// scales every offset. Rest pose: the nodes' own TRS.
// Animation `animation_index`: translation and rotation channels of joints (scale and morph weights
// are ignored); LINEAR (slerp for rotations), STEP and CUBICSPLINE samplers (CUBICSPLINE keys are
// interpolated linearly between their values, ignoring tangents: exact at the keys). Sampled at `fps`
// from the earliest to the latest key time.
// Errors (unreadable file, bad JSON, missing skin/animation, accessors of the wrong type or size, a node
// hierarchy that is not a forest, a clip beyond kMaxGltfClipValues) throw InputError naming the file and the
// glTF element ("animations[0].channels[3]", "nodes[5]").
#include <filesystem>

#include "framework/animation/bvh.hpp"

namespace crowdlab {

/// Most values (frames x 6 channels per joint) a clip may be sampled into: 20 million doubles, 160 MB,
/// e.g. 100 joints over 18 minutes at 30 fps. Key times in milliseconds, or a fuzzed time of 1e7 s,
/// would otherwise allocate without bound (issue 21).
inline constexpr double kMaxGltfClipValues = 2e7;

BvhMotion import_gltf_animation(const std::filesystem::path& path, int animation_index = 0,
                                int skin_index = 0, double fps = 30.0);

}  // namespace crowdlab
