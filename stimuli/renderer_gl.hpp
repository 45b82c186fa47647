#pragma once
// Private to the renderer's translation units (renderer.cpp, ground_cache.cpp): the OpenGL objects of a
// Renderer and the uniform setters they share. Not part of the stimuli library's interface.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "framework/core/forward_kinematics.hpp"
#include "stimuli/egl_context.hpp"
#include "stimuli/frame_plan.hpp"
#include "stimuli/gl_program.hpp"
#include "stimuli/gpu_geometry.hpp"
#include "stimuli/level_of_detail.hpp"
#include "stimuli/renderer.hpp"
#include "stimuli/scene_set.hpp"
#include "stimuli/shaders.hpp"

namespace crowdlab::stimuli {

inline void set_mat4(GLuint program, int location, const Mat4& m) {
  const Eigen::Matrix4f f = m.cast<float>();
  glProgramUniformMatrix4fv(program, location, 1, GL_FALSE, f.data());
}
inline void set_vec3(GLuint program, int location, const Vec3& v) {
  glProgramUniform3f(program, location, static_cast<float>(v.x()), static_cast<float>(v.y()),
                     static_cast<float>(v.z()));
}
inline void set_rgb(GLuint program, int location, const Rgb& c) {
  glProgramUniform3f(program, location, c[0], c[1], c[2]);
}

struct Renderer::Gl {
  EglContext context;
  GlProgram skinned_lit{glsl::specialise(glsl::kSkinnedVertex, "").c_str(),
                        glsl::specialise(glsl::kLitFragment, "MATERIAL_CHARACTER").c_str(), "skinned_lit"};
  GlProgram skinned_lit_overlap{glsl::specialise(glsl::kSkinnedVertex, "").c_str(),
                                glsl::specialise(glsl::kLitFragment, "MATERIAL_CHARACTER OVERLAP").c_str(),
                                "skinned_lit_overlap"};
  /// Overlap mode's second character pass: only the surface flagged inside another character's (shaders.cpp).
  GlProgram skinned_inside{glsl::specialise(glsl::kSkinnedVertex, "INSIDE_SURFACE").c_str(),
                           glsl::specialise(glsl::kLitFragment, "MATERIAL_CHARACTER INSIDE_SURFACE").c_str(),
                           "skinned_inside"};
  GlProgram ground_lit{glsl::kStaticVertex, glsl::specialise(glsl::kLitFragment, "MATERIAL_GROUND").c_str(),
                       "ground_lit"};
  GlProgram flat_lit{glsl::kStaticVertex, glsl::specialise(glsl::kLitFragment, "MATERIAL_FLAT").c_str(),
                     "flat_lit"};
  GlProgram skinned_depth{glsl::specialise(glsl::kSkinnedVertex, "").c_str(), glsl::kDepthFragment,
                          "skinned_depth"};
  GlProgram static_depth{glsl::kStaticVertex, glsl::kDepthFragment, "static_depth"};
  GlProgram ground_unshadowed{glsl::kStaticVertex,
                              glsl::specialise(glsl::kLitFragment, "MATERIAL_GROUND NO_SHADOW").c_str(),
                              "ground_unshadowed"};
  GlProgram contact{glsl::kContactVertex, glsl::kContactFragment, "contact"};
  GLuint empty_vao = 0;  ///< instanced passes take no vertex attributes
  GLuint contact_ssbo = 0;
  GLsizeiptr contact_capacity = 0;
  bool cpu_aa = false;  ///< the last frame is still to be anti-aliased on the CPU once read (fxaa_rgba.hpp)
  bool pbo_cpu_aa[2] = {false, false};  ///< cpu_aa of the frame each pixel buffer holds
  GlProgram ground_shadow{glsl::kStaticVertex,
                          glsl::specialise(glsl::kLitFragment, "MATERIAL_GROUND_SHADOW").c_str(),
                          "ground_shadow"};
  std::map<std::uint64_t, GpuMesh> mesh_cache;
  GpuMesh cube = make_unit_cube();
  GpuMesh ground;
  std::vector<GpuMesh> environment_meshes;
  std::vector<Mat4> box_models;    ///< the environment's boxes, then the set dressing's
  std::size_t physical_boxes = 0;  ///< how many of box_models are the environment's own
  std::vector<DecorBox> decor;     ///< the set dressing (stimuli/scene_set.hpp)
  std::map<std::uint64_t, std::vector<LodLevel>> lod_sets;  ///< mesh-set key -> its levels, finest first
  std::vector<std::uint64_t> character_lods;                ///< per character: its mesh-set key
  /// Per character: a one-level set of its shadow caster, or 0 when the caster is the level the colour pass
  /// draws (skinned surfaces).
  std::vector<std::uint64_t> character_shadow_mesh;
  GLuint noise_tex = 0;
  FrameScene scene;  ///< per crowd: what prepare_frame reads besides the poses (load_crowd)
  FramePlan plan;    ///< the frame being drawn (prepare_frame)
  GLuint skin_ssbo = 0, caps_ssbo = 0, inside_ssbo = 0;
  GLsizeiptr skin_capacity = 0, caps_capacity = 0, inside_capacity = 0;
  GLuint msaa_fbo = 0, msaa_color = 0, msaa_mask = 0, msaa_depth = 0;
  GLuint resolve_fbo = 0, resolve_color = 0, resolve_mask = 0;
  bool multisampled = true;  ///< false: the "msaa" targets have one sample and are read directly
  // The ground lit without shadows, drawn once per camera and copied into each frame (ground_cache.cpp).
  GLuint ground_fbo = 0, ground_color = 0, ground_depth = 0;
  std::uint64_t ground_key = 0;       ///< what ground_fbo holds; 0 = nothing
  Vec3 ground_centre = Vec3::Zero();  ///< the ground quad: the square ground_centre +- ground_half_m in x, z
  double ground_half_m = 150.0;
  void create_ground_targets(int width, int height);  ///< ground_cache.cpp
  GLuint shadow_fbo = 0, shadow_tex = 0;
  int shadow_size = 0;
  GLuint pbo[2] = {0, 0};
  std::vector<std::uint8_t> mask_pixels;

  /// The framebuffer whose colour attachment 0 holds the finished frame (1: the overlap mask).
  GLuint output_fbo() const { return multisampled ? resolve_fbo : msaa_fbo; }

  Gl() {
    glCreateBuffers(1, &skin_ssbo);
    glCreateBuffers(1, &caps_ssbo);
    glCreateBuffers(1, &inside_ssbo);
    glCreateBuffers(1, &contact_ssbo);
    glCreateVertexArrays(1, &empty_vao);
    noise_tex = make_noise_texture();
  }
  ~Gl() {
    for (auto& [key, mesh] : mesh_cache) destroy(mesh);
    destroy(cube);
    destroy(ground);
    for (GpuMesh& m : environment_meshes) destroy(m);
    free_targets();
    glDeleteBuffers(1, &skin_ssbo);
    glDeleteBuffers(1, &caps_ssbo);
    glDeleteBuffers(1, &inside_ssbo);
    glDeleteBuffers(1, &contact_ssbo);
    glDeleteVertexArrays(1, &empty_vao);
    glDeleteTextures(1, &noise_tex);
  }
  void free_targets() {
    glDeleteFramebuffers(1, &msaa_fbo);
    glDeleteFramebuffers(1, &resolve_fbo);
    glDeleteFramebuffers(1, &ground_fbo);
    const GLuint ground_rbs[] = {ground_color, ground_depth};
    glDeleteRenderbuffers(2, ground_rbs);
    ground_fbo = ground_color = ground_depth = 0;
    ground_key = 0;
    glDeleteFramebuffers(1, &shadow_fbo);
    const GLuint rbs[] = {msaa_color, msaa_mask, msaa_depth, resolve_color, resolve_mask};
    glDeleteRenderbuffers(5, rbs);
    glDeleteTextures(1, &shadow_tex);
    glDeleteBuffers(2, pbo);
    msaa_fbo = resolve_fbo = shadow_fbo = shadow_tex = 0;
    pbo[0] = pbo[1] = 0;
  }
  /// Grows a buffer (never shrinks) and uploads data.
  static void upload(GLuint buffer, GLsizeiptr& capacity, const std::vector<float>& data) {
    const auto bytes = static_cast<GLsizeiptr>(std::max<size_t>(data.size(), 4) * sizeof(float));
    if (bytes > capacity) {
      glNamedBufferData(buffer, bytes, nullptr, GL_DYNAMIC_DRAW);
      capacity = bytes;
    }
    if (!data.empty())
      glNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(data.size() * sizeof(float)), data.data());
  }
};

}  // namespace crowdlab::stimuli
