// The cached ground of the one-sample fast path (see shaders.cpp, "Ground shadows on a cached ground").
//
// Why: with one sample per pixel the ground was the largest fixed cost of a 1080p frame on llvmpipe (about
// 36 of 50 ms of the colour pass for the real D5 scene): two trilinear noise lookups, the shadow-map lookup
// and the lighting on every visible ground pixel. The ground's lit colour without shadows depends only on
// the camera, so it is drawn once per camera; each frame then copies it (a plain memory copy) and applies
// the frame's shadows with one shadow-map lookup per pixel, only where a shadow can fall.
#include <algorithm>
#include <string_view>
#include <utility>
#include <vector>

#include "framework/core/seed.hpp"
#include "stimuli/renderer.hpp"
#include "stimuli/renderer_gl.hpp"

namespace crowdlab::stimuli {
namespace {
// Raw image copies of a colour and a depth renderbuffer of equal formats and size, not a blit: llvmpipe blits
// depth by drawing a textured quad, while glCopyImageSubData is a memory copy.
void copy_colour_and_depth(GLuint from_colour, GLuint from_depth, GLuint to_colour, GLuint to_depth,
                           int width, int height) {
  for (const auto& [from, to] : {std::pair{from_colour, to_colour}, std::pair{from_depth, to_depth}})
    glCopyImageSubData(from, GL_RENDERBUFFER, 0, 0, 0, 0, to, GL_RENDERBUFFER, 0, 0, 0, 0, width, height, 1);
}
}  // namespace

bool Renderer::uses_ground_cache(const SceneOptions& options) const {
  return !gl_->multisampled && crowd_->environment.ground_plane && options.fog_density <= 0.0;
}

std::uint64_t Renderer::ground_cache_key(const Camera& camera, const SceneOptions& options) const {
  std::vector<double> data = {camera.eye.x(),
                              camera.eye.y(),
                              camera.eye.z(),
                              camera.target.x(),
                              camera.target.y(),
                              camera.target.z(),
                              camera.fov_y_deg,
                              camera.near_m,
                              camera.far_m,
                              static_cast<double>(width_),
                              static_cast<double>(height_),
                              static_cast<double>(crowd_generation_)};
  for (const Rgb& c : {options.background, options.ground}) data.insert(data.end(), c.begin(), c.end());
  return stable_hash(
      std::string_view(reinterpret_cast<const char*>(data.data()), data.size() * sizeof(double)));
}

// The ground lit without shadows, with its depth, into ground_fbo. The uniforms are the current frame's
// (same camera, hence same lights). Leaves the frame's colour target cleared to the background.
void Renderer::draw_ground_cache(const SceneOptions& options) {
  Gl& g = *gl_;
  glBindFramebuffer(GL_FRAMEBUFFER, g.msaa_fbo);
  glViewport(0, 0, width_, height_);
  const GLenum colour = GL_COLOR_ATTACHMENT0;
  glNamedFramebufferDrawBuffers(g.msaa_fbo, 1, &colour);
  const float bg[4] = {options.background[0], options.background[1], options.background[2], 1.0f};
  const float one = 1.0f;
  glClearNamedFramebufferfv(g.msaa_fbo, GL_COLOR, 0, bg);
  glClearNamedFramebufferfv(g.msaa_fbo, GL_DEPTH, 0, &one);
  const GLuint p = g.ground_unshadowed.id();
  glUseProgram(p);
  set_rgb(p, g.ground_unshadowed.uniform("u_base_color"), options.ground);
  set_mat4(p, g.ground_unshadowed.uniform("u_model"), Mat4::Identity());
  glBindVertexArray(g.ground.vao);
  glDrawElements(GL_TRIANGLES, g.ground.count, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  copy_colour_and_depth(g.msaa_color, g.msaa_depth, g.ground_color, g.ground_depth, width_, height_);
}

// The cached ground (colour and depth) into the frame's targets.
void Renderer::copy_ground_cache() {
  Gl& g = *gl_;
  copy_colour_and_depth(g.ground_color, g.ground_depth, g.msaa_color, g.msaa_depth, width_, height_);
}

namespace {
// The model matrix that maps the ground quad (the square [c - h, c + h] in x and z, renderer.cpp) onto the
// ground region where shadows can fall: every caster lies inside the scene bounds [lo, hi] (characters'
// whole motion and the boxes), so its shadow lies in the bounds' footprint on y = 0 along the key light.
// Environment meshes are not in the bounds: with any of them the whole ground is kept.
Mat4 shadow_footprint(const Vec3& lo, const Vec3& hi, const Vec3& key_dir, const Vec3& quad_centre,
                      double quad_half_m) {
  Eigen::Vector2d min(lo.x(), lo.z()), max(hi.x(), hi.z());
  const double slope = 1.0 / std::max(key_dir.y(), 0.05);  // the key light is above the horizon
  for (const double y : {lo.y(), hi.y()})
    for (const double x : {lo.x(), hi.x()})
      for (const double z : {lo.z(), hi.z()}) {
        const Eigen::Vector2d shadow(x - key_dir.x() * y * slope, z - key_dir.z() * y * slope);
        min = min.cwiseMin(shadow);
        max = max.cwiseMax(shadow);
      }
  min.array() -= 0.1;  // the lookup's normal offset and filter footprint
  max.array() += 0.1;
  Mat4 model = Mat4::Identity();
  model(0, 0) = (max.x() - min.x()) / (2.0 * quad_half_m);
  model(2, 2) = (max.y() - min.y()) / (2.0 * quad_half_m);
  model(0, 3) = min.x() - model(0, 0) * (quad_centre.x() - quad_half_m);
  model(2, 3) = min.y() - model(2, 2) * (quad_centre.z() - quad_half_m);
  return model;
}
}  // namespace

// The frame's shadows on the visible ground: a multiplicative pass after the characters and the
// environment, so the depth test keeps it off them. Pixels already darkened once are not darkened again
// because each ground pixel is covered by one fragment of the (flat, non-overlapping) footprint quad.
void Renderer::draw_ground_shadows(const Rgb& ground, const Vec3& key_dir) {
  Gl& g = *gl_;
  const GLenum colour = GL_COLOR_ATTACHMENT0;
  glNamedFramebufferDrawBuffers(g.msaa_fbo, 1, &colour);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_FALSE);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(-1.0f, -4.0f);  // a hair nearer than the cached ground itself
  glEnable(GL_BLEND);
  glBlendFunc(GL_DST_COLOR, GL_ZERO);  // multiply
  const GLuint p = g.ground_shadow.id();
  glUseProgram(p);
  set_rgb(p, g.ground_shadow.uniform("u_base_color"), ground);
  const Mat4 model =
      g.environment_meshes.empty()
          ? shadow_footprint(g.scene.bounds_lo, g.scene.bounds_hi, key_dir, g.ground_centre, g.ground_half_m)
          : Mat4::Identity();
  set_mat4(p, g.ground_shadow.uniform("u_model"), model);
  glBindVertexArray(g.ground.vao);
  glDrawElements(GL_TRIANGLES, g.ground.count, GL_UNSIGNED_INT, nullptr);
  glBindVertexArray(0);
  glDisable(GL_BLEND);
  glDisable(GL_POLYGON_OFFSET_FILL);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
}

// The cache's colour and depth targets, one sample each (the cache is used only without MSAA).
void Renderer::Gl::create_ground_targets(int width, int height) {
  glCreateFramebuffers(1, &ground_fbo);
  GLuint rbs[2];
  glCreateRenderbuffers(2, rbs);
  ground_color = rbs[0];
  ground_depth = rbs[1];
  glNamedRenderbufferStorage(ground_color, GL_RGBA8, width, height);
  glNamedRenderbufferStorage(ground_depth, GL_DEPTH_COMPONENT24, width, height);
  glNamedFramebufferRenderbuffer(ground_fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, ground_color);
  glNamedFramebufferRenderbuffer(ground_fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, ground_depth);
}

}  // namespace crowdlab::stimuli
