#pragma once
// The local transform of a glTF node as a 4x4 matrix: its `matrix` (column-major) when given, otherwise
// T * R * S from translation, rotation (x, y, z, w) and scale (glTF 2.0 §3.5.3).
#include <tiny_gltf.h>

#include <Eigen/Core>

namespace crowdlab {

Eigen::Matrix4d gltf_node_matrix(const tinygltf::Node& node);

}  // namespace crowdlab
