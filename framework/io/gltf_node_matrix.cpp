#include "framework/io/gltf_node_matrix.hpp"

#include "framework/core/math_types.hpp"

namespace crowdlab {

Eigen::Matrix4d gltf_node_matrix(const tinygltf::Node& n) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (n.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = n.matrix[static_cast<size_t>(c * 4 + r)];
    return m;
  }
  if (n.scale.size() == 3) m.block<3, 3>(0, 0) = Vec3(n.scale[0], n.scale[1], n.scale[2]).asDiagonal();
  if (n.rotation.size() == 4)
    m.block<3, 3>(0, 0) =
        Quat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]).normalized().toRotationMatrix() *
        m.block<3, 3>(0, 0);
  if (n.translation.size() == 3)
    m.block<3, 1>(0, 3) = Vec3(n.translation[0], n.translation[1], n.translation[2]);
  return m;
}

}  // namespace crowdlab
