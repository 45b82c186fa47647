#include "stimuli/gpu_geometry.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cmath>
#include <cstddef>

#include "framework/core/seed.hpp"

namespace crowdlab::stimuli {

GpuMesh upload_static(const std::vector<StaticVertex>& vertices, const std::vector<std::uint32_t>& indices) {
  GpuMesh m;
  glCreateVertexArrays(1, &m.vao);
  glCreateBuffers(1, &m.vbo);
  glCreateBuffers(1, &m.ibo);
  glNamedBufferStorage(m.vbo, static_cast<GLsizeiptr>(vertices.size() * sizeof(StaticVertex)),
                       vertices.data(), 0);
  glNamedBufferStorage(m.ibo, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(),
                       0);
  glVertexArrayVertexBuffer(m.vao, 0, m.vbo, 0, sizeof(StaticVertex));
  glVertexArrayElementBuffer(m.vao, m.ibo);
  glEnableVertexArrayAttrib(m.vao, 0);
  glEnableVertexArrayAttrib(m.vao, 1);
  glVertexArrayAttribFormat(m.vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(StaticVertex, position));
  glVertexArrayAttribFormat(m.vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(StaticVertex, normal));
  glVertexArrayAttribBinding(m.vao, 0, 0);
  glVertexArrayAttribBinding(m.vao, 1, 0);
  m.count = static_cast<GLsizei>(indices.size());
  return m;
}

GpuMesh upload_mannequin(const MannequinMesh& mesh) {
  GpuMesh m;
  glCreateVertexArrays(1, &m.vao);
  glCreateBuffers(1, &m.vbo);
  glCreateBuffers(1, &m.ibo);
  glNamedBufferStorage(m.vbo, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(MannequinVertex)),
                       mesh.vertices.data(), 0);
  glNamedBufferStorage(m.ibo, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                       mesh.indices.data(), 0);
  glVertexArrayVertexBuffer(m.vao, 0, m.vbo, 0, sizeof(MannequinVertex));
  glVertexArrayElementBuffer(m.vao, m.ibo);
  for (GLuint a = 0; a < 7; ++a) {
    glEnableVertexArrayAttrib(m.vao, a);
    glVertexArrayAttribBinding(m.vao, a, 0);
  }
  glVertexArrayAttribFormat(m.vao, 0, 3, GL_FLOAT, GL_FALSE, offsetof(MannequinVertex, position));
  glVertexArrayAttribFormat(m.vao, 1, 3, GL_FLOAT, GL_FALSE, offsetof(MannequinVertex, normal));
  glVertexArrayAttribIFormat(m.vao, 2, 4, GL_UNSIGNED_BYTE, offsetof(MannequinVertex, bones));
  glVertexArrayAttribFormat(m.vao, 3, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(MannequinVertex, weights));
  glVertexArrayAttribIFormat(m.vao, 4, 1, GL_UNSIGNED_BYTE, offsetof(MannequinVertex, region));
  glVertexArrayAttribFormat(m.vao, 5, 4, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(MannequinVertex, colour));
  glVertexArrayAttribFormat(m.vao, 6, 1, GL_UNSIGNED_BYTE, GL_TRUE, offsetof(MannequinVertex, lips));
  m.count = static_cast<GLsizei>(mesh.indices.size());
  m.two_sided = mesh.two_sided;
  return m;
}

void destroy(GpuMesh& m) {
  glDeleteVertexArrays(1, &m.vao);
  glDeleteBuffers(1, &m.vbo);
  glDeleteBuffers(1, &m.ibo);
  m = {};
}

/// The unit cube [-1, 1]^3 with per-face normals, counter-clockwise outside.
GpuMesh make_unit_cube() {
  std::vector<StaticVertex> v;
  std::vector<std::uint32_t> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {-1, 1}) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      const auto base = static_cast<std::uint32_t>(v.size());
      const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        StaticVertex sv{};
        sv.position[axis] = static_cast<float>(sign);
        sv.position[u] = c[0] * static_cast<float>(sign);
        sv.position[w] = c[1];
        sv.normal[axis] = static_cast<float>(sign);
        v.push_back(sv);
      }
      idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  return upload_static(v, idx);
}

GpuMesh make_environment_mesh(const TriangleMesh& mesh) {
  std::vector<StaticVertex> v;
  std::vector<std::uint32_t> idx;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Vec3 a = mesh.vertices_m.at(static_cast<size_t>(t.x())),
               b = mesh.vertices_m.at(static_cast<size_t>(t.y())),
               c = mesh.vertices_m.at(static_cast<size_t>(t.z()));
    Vec3 n = (b - a).cross(c - a);
    n = n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitY();
    for (const Vec3* p : {&a, &b, &c}) {
      StaticVertex sv{};
      for (int k = 0; k < 3; ++k) {
        sv.position[k] = static_cast<float>((*p)[k]);
        sv.normal[k] = static_cast<float>(n[k]);
      }
      idx.push_back(static_cast<std::uint32_t>(v.size()));
      v.push_back(sv);
    }
  }
  return upload_static(v, idx);
}

/// A 256 x 256 tiling value-noise texture (bilinear upsampling of 32 x 32 random lattice values),
/// mip-mapped; generated from a fixed seed so every run draws the same ground.
GLuint make_noise_texture() {
  constexpr int kLattice = 32, kSize = 256;
  Rng rng(derive_seed(0x6772'6f75'6e64ULL, "ground-noise"));
  std::vector<double> lattice(kLattice * kLattice);
  for (double& v : lattice) v = uniform01(rng);
  std::vector<std::uint8_t> texels(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const double fx = x * kLattice / static_cast<double>(kSize),
                   fy = y * kLattice / static_cast<double>(kSize);
      const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
      double u = fx - x0, w = fy - y0;
      u = u * u * (3 - 2 * u);
      w = w * w * (3 - 2 * w);
      auto at = [&](int i, int j) {
        return lattice[static_cast<size_t>((j % kLattice) * kLattice + (i % kLattice))];
      };
      const double v = (1 - w) * ((1 - u) * at(x0, y0) + u * at(x0 + 1, y0)) +
                       w * ((1 - u) * at(x0, y0 + 1) + u * at(x0 + 1, y0 + 1));
      texels[static_cast<size_t>(y * kSize + x)] = static_cast<std::uint8_t>(std::lround(255.0 * v));
    }
  GLuint tex = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &tex);
  glTextureStorage2D(tex, 9, GL_R8, kSize, kSize);
  glTextureSubImage2D(tex, 0, 0, 0, kSize, kSize, GL_RED, GL_UNSIGNED_BYTE, texels.data());
  glGenerateTextureMipmap(tex);
  glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_REPEAT);
  return tex;
}

}  // namespace crowdlab::stimuli
