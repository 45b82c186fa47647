#pragma once
// BVH (Biovision Hierarchy) motion import.
//
// Robust to the variants met in practice: any joint may carry 3 or 6 channels (or any subset of the
// six), in any order (e.g. "Zrotation Xrotation Yrotation"), positions on child joints (Bandai-Namco
// gives every joint 6 channels), End Sites, tabs or CRLF line ends, and frames wrapped over several
// lines. Semantics (the de-facto standard of the Biovision / CMU files):
//   - a joint's local translation is its OFFSET, with each position channel present REPLACING that
//     component (for the root this is the root position);
//   - the local rotation is the product of the rotation channels in the order listed (intrinsic
//     axes): "Zrotation Xrotation Yrotation" -> Rz * Rx * Ry; angles in degrees.
// Every malformed input (unknown keyword or channel, missing braces, non-numeric or non-finite
// values, a missing or inconsistent "Frames:" / "Frame Time:", a truncated or overlong MOTION
// section, joints nested deeper than kMaxBvhJointDepth, a Frame Time outside [kMinBvhFrameTime_s,
// kMaxBvhFrameTime_s]) throws InputError whose message starts "file:line:column:". Memory is bounded by
// the file's size: a header's `Frames:` count never drives an allocation beyond what the file holds.
#include <filesystem>
#include <string>
#include <vector>

#include "framework/core/math_types.hpp"

namespace crowdlab {

/// Deepest joint nesting accepted (the root is depth 1). The parser recurses per level; a bound keeps a
/// hostile file (30,000 nested JOINTs) from overflowing the stack. Human skeletons need fewer than 30.
inline constexpr int kMaxBvhJointDepth = 256;
/// Accepted Frame Time range: 10 kHz to 0.1 Hz. Outside it a clip's playback (loops per second, frames
/// per output frame) explodes: `Frame Time: 1e-9` is a billion frames per second.
inline constexpr double kMinBvhFrameTime_s = 1e-4;
inline constexpr double kMaxBvhFrameTime_s = 10.0;

enum class BvhChannel { kXposition, kYposition, kZposition, kXrotation, kYrotation, kZrotation };

struct BvhJoint {
  std::string name;
  int parent = -1;             ///< index into BvhMotion::joints, -1 for the root
  Vec3 offset = Vec3::Zero();  ///< in the parent's frame, file units
  std::vector<BvhChannel> channels;
  int first_channel = 0;  ///< index of its first value within a frame
  bool has_end_site = false;
  Vec3 end_site = Vec3::Zero();  ///< End Site offset (file units) when present
  int line = 0;                  ///< where the joint is declared
};

struct BvhMotion {
  std::string source;            ///< file name, for messages
  std::vector<BvhJoint> joints;  ///< parents precede children
  int channel_count = 0;         ///< values per frame
  int frame_count = 0;
  double frame_time_s = 0.0;
  std::vector<double> values;  ///< frame_count x channel_count, row-major

  double fps() const { return 1.0 / frame_time_s; }
  /// Local transform of joint j at frame f (translation in file units).
  RigidTransform local_transform(int joint, int frame) const;
  /// World transforms of all joints at frame f (file units and axes).
  std::vector<RigidTransform> world_transforms(int frame) const;
  /// Joint positions of the zero pose (all channels zero, offsets only), file units.
  std::vector<Vec3> zero_pose_positions() const;
  int find_joint(const std::string& name) const;  ///< -1 when absent (exact match)
};

/// Parses BVH text; `source` names it in error messages.
BvhMotion parse_bvh(const std::string& text, const std::string& source);

/// Reads and parses a .bvh file (InputError when it cannot be read).
BvhMotion import_bvh(const std::filesystem::path& path);

}  // namespace crowdlab
