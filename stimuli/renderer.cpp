#include "stimuli/renderer.hpp"

#include "stimuli/renderer_gl.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <functional>
#include <numbers>
#include <set>

#include "framework/core/capsule_box.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/seed.hpp"
#include "stimuli/character_mesh.hpp"
#include "stimuli/egl_context.hpp"
#include "stimuli/elapsed_ms.hpp"
#include "stimuli/fxaa_rgba.hpp"
#include "stimuli/gl_program.hpp"
#include "stimuli/gltf_character.hpp"
#include "stimuli/gpu_geometry.hpp"
#include "stimuli/level_of_detail.hpp"
#include "stimuli/scene_set.hpp"
#include "stimuli/shaders.hpp"

namespace crowdlab::stimuli {
namespace {

// Grid spacing of the coarse mannequin meshes drawn into the shadow map: shadows are soft-edged and
// seen from afar, so a 4.5 cm mesh casts the same shadow at a fraction of the vertex work.
constexpr double kShadowVoxelM = 0.045;
using Clock = std::chrono::steady_clock;
/// Back-face culling for closed surfaces (`face` culled), none for open sheets (hair, garments).
void set_culling(bool two_sided, GLenum face) {
  if (two_sided) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(face);
  }
}

}  // namespace

Rgb parse_hex_colour(const std::string& text, const std::string& context) {
  std::string hex = !text.empty() && text[0] == '#' ? text.substr(1) : text;
  if (hex.size() != 6 || hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos)
    throw InputError(context + ": colour must be \"#rrggbb\", got \"" + text + "\"");
  Rgb c{};
  for (int i = 0; i < 3; ++i)
    c[static_cast<size_t>(i)] =
        static_cast<float>(std::stoi(hex.substr(static_cast<size_t>(2 * i), 2), nullptr, 16)) / 255.0f;
  return c;
}

Renderer::Renderer(MannequinOptions mesh_options)
    : gl_(std::make_unique<Gl>()), mesh_options_(mesh_options) {}
Renderer::~Renderer() {
  if (gl_) gl_->context.make_current();  // GL objects are deleted in this context
}

const std::string& Renderer::device() const {
  return gl_->context.renderer_description();
}
std::size_t Renderer::cached_meshes() const {
  return gl_->mesh_cache.size();
}

void Renderer::set_character_files(const std::vector<std::string>& files) {
  std::vector<std::shared_ptr<const GltfCharacter>> loaded;
  for (const std::string& f : files) {
    auto it = file_cache_.find(f);
    if (it == file_cache_.end())
      it = file_cache_.emplace(f, std::make_shared<const GltfCharacter>(load_gltf_character(f))).first;
    loaded.push_back(it->second);
  }
  file_characters_ = std::move(loaded);
}

void Renderer::set_size(int width, int height, int samples, int shadow_map_size) {
  gl_->context.make_current();
  if (width <= 0 || height <= 0 || width > 16384 || height > 16384)
    throw InputError("render size must be in 1..16384 pixels, got " + std::to_string(width) + "x" +
                     std::to_string(height));
  Gl& g = *gl_;
  requested_samples_ = samples;
  shadow_map_size_ = shadow_map_size;
  GLint max_samples = 1;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  samples = std::clamp(samples, 1, static_cast<int>(max_samples));
  g.free_targets();
  width_ = width;
  height_ = height;
  glCreateFramebuffers(1, &g.msaa_fbo);
  GLuint rbs[5];
  glCreateRenderbuffers(5, rbs);
  g.msaa_color = rbs[0];
  g.msaa_mask = rbs[1];
  g.msaa_depth = rbs[2];
  g.resolve_color = rbs[3];
  g.resolve_mask = rbs[4];
  g.multisampled = samples > 1;
  g.create_ground_targets(width, height);
  // One sample: plain renderbuffers, read directly (no resolve copy).
  const auto storage = [&](GLuint rb, GLenum format) {
    if (g.multisampled)
      glNamedRenderbufferStorageMultisample(rb, samples, format, width, height);
    else
      glNamedRenderbufferStorage(rb, format, width, height);
  };
  storage(g.msaa_color, GL_RGBA8);
  storage(g.msaa_mask, GL_R8);
  storage(g.msaa_depth, GL_DEPTH_COMPONENT24);
  glNamedFramebufferRenderbuffer(g.msaa_fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g.msaa_color);
  glNamedFramebufferRenderbuffer(g.msaa_fbo, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, g.msaa_mask);
  glNamedFramebufferRenderbuffer(g.msaa_fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g.msaa_depth);
  const GLenum both[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  glNamedFramebufferDrawBuffers(g.msaa_fbo, 2, both);
  glCreateFramebuffers(1, &g.resolve_fbo);
  glNamedRenderbufferStorage(g.resolve_color, GL_RGBA8, width, height);
  glNamedRenderbufferStorage(g.resolve_mask, GL_R8, width, height);
  glNamedFramebufferRenderbuffer(g.resolve_fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, g.resolve_color);
  glNamedFramebufferRenderbuffer(g.resolve_fbo, GL_COLOR_ATTACHMENT1, GL_RENDERBUFFER, g.resolve_mask);
  g.shadow_size = shadow_map_size;
  glCreateTextures(GL_TEXTURE_2D, 1, &g.shadow_tex);
  glTextureStorage2D(g.shadow_tex, 1, GL_DEPTH_COMPONENT24, shadow_map_size, shadow_map_size);
  glTextureParameteri(g.shadow_tex, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  glTextureParameteri(g.shadow_tex, GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  glTextureParameteri(g.shadow_tex, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  glTextureParameteri(g.shadow_tex, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(g.shadow_tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(g.shadow_tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glCreateFramebuffers(1, &g.shadow_fbo);
  glNamedFramebufferTexture(g.shadow_fbo, GL_DEPTH_ATTACHMENT, g.shadow_tex, 0);
  glNamedFramebufferDrawBuffer(g.shadow_fbo, GL_NONE);
  glNamedFramebufferReadBuffer(g.shadow_fbo, GL_NONE);
  for (GLuint fbo : {g.msaa_fbo, g.resolve_fbo, g.shadow_fbo, g.ground_fbo})
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw RuntimeError("OpenGL: a framebuffer is incomplete (" + device() + ")");
  glCreateBuffers(2, g.pbo);
  for (GLuint pbo : g.pbo)
    glNamedBufferData(pbo, static_cast<GLsizeiptr>(width) * height * 4, nullptr, GL_STREAM_READ);
}

void Renderer::load_crowd(const CrowdAnimation& crowd) {
  gl_->context.make_current();
  validate_crowd(crowd, "render");
  Gl& g = *gl_;
  crowd_ = &crowd;
  ++crowd_generation_;
  const size_t n = crowd.characters.size();
  // Build the meshes of shapes not yet cached, in parallel (one result slot per job), then upload
  // them in job order. Each shape gets its level-of-detail meshes and a coarse one for the shadow pass.
  MannequinOptions shadow_options = mesh_options_;
  shadow_options.voxel_m = std::max(mesh_options_.voxel_m, kShadowVoxelM);
  shadow_options.inset_m =
      0.4 * shadow_options.voxel_m;  // keep the coarse caster inside the visible skin (no acne bands)
  g.character_lods.resize(n);
  g.character_shadow_mesh.resize(n);
  // A job builds every level of one character's mesh set (or the shadow caster) and says each level's
  // geometric error; sets already built are reused from the caches.
  struct Job {
    size_t character;
    std::uint64_t set_key;
    std::function<std::vector<CharacterLod>()> build;
  };
  std::vector<Job> jobs;
  std::set<std::uint64_t> queued;
  auto want = [&](size_t character, std::uint64_t set_key, std::function<std::vector<CharacterLod>()> build) {
    if (!g.lod_sets.count(set_key) && queued.insert(set_key).second)
      jobs.push_back({character, set_key, std::move(build)});
  };
  for (size_t i = 0; i < n; ++i) {
    const CharacterAnimation& ch = crowd.characters[i];
    if (!file_characters_.empty()) {  // one fitted mesh serves every pass (no LOD for file meshes)
      const GltfCharacter& file = *file_characters_[i % file_characters_.size()];
      const std::uint64_t key = stable_hash("gltf:" + file.source + ":" +
                                            std::to_string(mannequin_cache_key(ch.shape, mesh_options_)));
      g.character_lods[i] = key;
      g.character_shadow_mesh[i] = key;
      want(i, key, [&file, &ch] {
        return std::vector<CharacterLod>{{fit_gltf_character(file, ch.shape), 0.0}};
      });
      continue;
    }
    const MannequinOptions options = mesh_options_;
    g.character_lods[i] = character_lod_set_key(ch, options);
    want(i, g.character_lods[i], [&ch, options] { return build_character_lods(ch, options); });
    // A skinned surface casts its shadow with the level the viewer sees: no more detail than is drawn,
    // and the shadow's outline is the body's own. A procedural mannequin casts with a coarse inset copy.
    g.character_shadow_mesh[i] = 0;
    if (ch.mesh) continue;
    g.character_shadow_mesh[i] = character_mesh_key(ch, shadow_options);
    want(i, g.character_shadow_mesh[i], [&ch, shadow_options] {
      return std::vector<CharacterLod>{{build_character_mesh(ch, shadow_options), 0.0}};
    });
  }
  std::vector<std::vector<CharacterLod>> built(jobs.size());
  tbb::parallel_for(size_t{0}, jobs.size(), [&](size_t k) { built[k] = jobs[k].build(); });
  for (size_t k = 0; k < jobs.size(); ++k) {
    std::vector<LodLevel>& levels = g.lod_sets[jobs[k].set_key];
    for (size_t l = 0; l < built[k].size(); ++l) {
      const std::uint64_t key = stable_hash(std::to_string(jobs[k].set_key) + "/lod" + std::to_string(l));
      g.mesh_cache.emplace(key, upload_mannequin(built[k][l].mesh));
      levels.push_back(
          {key, built[k][l].error_m, static_cast<int>(built[k][l].mesh.indices.size()), nullptr});
      // Overlap mode flags the drawn vertices of characters with a rendered mesh on the CPU (frame_plan.hpp).
      if (crowd.characters[jobs[k].character].mesh)
        levels.back().vertices =
            std::make_shared<const std::vector<MannequinVertex>>(std::move(built[k][l].mesh.vertices));
      spdlog::debug("mesh set {:016x} level {}: {} triangles, error {:.4f} m", jobs[k].set_key, l,
                    built[k][l].mesh.indices.size() / 3, built[k][l].error_m);
    }
  }
  // What prepare_frame reads besides the poses.
  FrameScene& scene = g.scene;
  scene.inverse_rest.resize(n);
  scene.lod_sets.resize(n);
  for (size_t i = 0; i < n; ++i) {
    scene.inverse_rest[i] = inverse_rest_transforms(crowd.characters[i].shape);
    scene.lod_sets[i] = &g.lod_sets.at(g.character_lods[i]);
  }
  // Environment.
  for (GpuMesh& m : g.environment_meshes) destroy(m);
  g.environment_meshes.clear();
  for (const TriangleMesh& m : crowd.environment.meshes)
    if (!m.triangles.empty()) g.environment_meshes.push_back(make_environment_mesh(m));
  g.box_models.clear();
  scene.boxes = crowd.environment.boxes;
  Vec3 lo = Vec3::Constant(1e30), hi = Vec3::Constant(-1e30);
  for (const Box& b : crowd.environment.boxes) {
    Mat4 model = Mat4::Identity();
    model.block<3, 3>(0, 0) = b.rotation.normalized().toRotationMatrix() * b.half_extents_m.asDiagonal();
    model.block<3, 1>(0, 3) = b.center_m;
    g.box_models.push_back(model);
    const double r = b.half_extents_m.norm();
    lo = lo.cwiseMin(b.center_m - Vec3::Constant(r));
    hi = hi.cwiseMax(b.center_m + Vec3::Constant(r));
  }
  for (const CharacterAnimation& c : crowd.characters)
    for (const Pose& p : c.frames) {
      lo = lo.cwiseMin(p.root_position_m - Vec3(1.0, 1.2, 1.0));
      hi = hi.cwiseMax(p.root_position_m + Vec3(1.0, 1.2, 1.0));
    }
  lo.y() = std::min(lo.y(), 0.0);
  // Snapped outward to a 2 m grid: the shadow map and the ground follow these bounds, and the two methods
  // of a condition (bodies a few centimetres apart) must get the same shadow map and ground.
  scene.bounds_lo = (2.0 * (0.5 * lo).array().floor()).matrix();
  scene.bounds_hi = (2.0 * (0.5 * hi).array().ceil()).matrix();
  // Set dressing (stimuli/scene_set.hpp) after the environment's boxes, which keep indices 0..n-1.
  g.physical_boxes = crowd.environment.boxes.size();
  g.decor = make_scene_set(crowd, scene.bounds_lo, scene.bounds_hi);
  for (const DecorBox& d : g.decor) {
    Mat4 model = Mat4::Identity();
    model.block<3, 3>(0, 0) =
        d.box.rotation.normalized().toRotationMatrix() * d.box.half_extents_m.asDiagonal();
    model.block<3, 1>(0, 3) = d.box.center_m;
    g.box_models.push_back(model);
    scene.boxes.push_back(d.box);
  }
  destroy(g.ground);
  const Vec3 c = 0.5 * (scene.bounds_lo + scene.bounds_hi);
  const float half = 150.0f, cx = static_cast<float>(c.x()), cz = static_cast<float>(c.z());
  std::vector<StaticVertex> quad = {{{cx - half, 0, cz - half}, {0, 1, 0}},
                                    {{cx - half, 0, cz + half}, {0, 1, 0}},
                                    {{cx + half, 0, cz + half}, {0, 1, 0}},
                                    {{cx + half, 0, cz - half}, {0, 1, 0}}};
  g.ground = upload_static(quad, {0, 1, 2, 0, 2, 3});
  g.ground_centre = Vec3(cx, 0.0, cz);
  g.ground_half_m = half;
}

void Renderer::draw(int frame, const Camera& camera, const SceneOptions& options) {
  gl_->context.make_current();
  if (!crowd_) throw RuntimeError("Renderer::draw: no crowd loaded");
  if (width_ == 0) throw RuntimeError("Renderer::draw: set_size() first");
  Gl& g = *gl_;
  auto stage_start = Clock::now();
  // Ends a timed stage: with options.time_passes the rasteriser finishes it first (llvmpipe rasterises at
  // flush time), so each pass's time is its own.
  const auto end_stage = [&](double& ms, bool gpu) {
    if (gpu && options.time_passes) glFinish();
    ms = gpu && !options.time_passes ? 0.0 : ms_since(stage_start);
    stage_start = Clock::now();
  };
  pass_times_ = {};
  g.scene.height_px = height_;
  prepare_frame(*crowd_, frame, camera, options, g.scene, g.plan);
  upload_frame(g);
  end_stage(pass_times_.prepare_ms, false);
  set_frame_uniforms(g, camera, options);
  shadow_pass(g, options);
  end_stage(pass_times_.shadow_ms, true);
  colour_pass(g, camera, options);
  end_stage(pass_times_.colour_ms, true);
  resolve_pass(g, options);
  end_stage(pass_times_.resolve_ms, true);
}

// The frame's skin matrices, overlap capsules and inside flags, into the shader storage buffers 0, 1 and 2.
void Renderer::upload_frame(Gl& g) {
  Gl::upload(g.skin_ssbo, g.skin_capacity, g.plan.skin_matrices);
  Gl::upload(g.caps_ssbo, g.caps_capacity, g.plan.capsules);
  Gl::upload(g.inside_ssbo, g.inside_capacity, g.plan.inside);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, g.skin_ssbo);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, g.caps_ssbo);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, g.inside_ssbo);
}

// The uniforms every lit program shares: camera, lights, shadow map, ground noise, background and fog.
void Renderer::set_frame_uniforms(Gl& g, const Camera& camera, const SceneOptions& options) {
  const FrameLights& lights = g.plan.lights;
  glBindTextureUnit(0, g.shadow_tex);
  glBindTextureUnit(1, g.noise_tex);
  for (GlProgram* prog : {&g.ground_lit, &g.flat_lit, &character_program(g, options), &g.ground_unshadowed,
                          &g.ground_shadow, &g.skinned_inside}) {
    const GLuint id = prog->id();
    set_mat4(id, prog->uniform("u_view_proj"), g.plan.view_proj);
    set_mat4(id, prog->uniform("u_light_view_proj"), lights.light_view_proj);
    set_vec3(id, prog->uniform("u_eye"), camera.eye);
    set_vec3(id, prog->uniform("u_key_dir"), lights.key_dir);
    set_vec3(id, prog->uniform("u_fill_dir"), lights.fill_dir);
    set_vec3(id, prog->uniform("u_rim_dir"), lights.rim_dir);
    glProgramUniform1i(id, prog->uniform("u_shadow_map"), 0);
    glProgramUniform1i(id, prog->uniform("u_ground_noise"), 1);
    glProgramUniform1f(id, prog->uniform("u_shadow_texel"), 1.0f / static_cast<float>(g.shadow_size));
    set_rgb(id, prog->uniform("u_background"), options.background);
    glProgramUniform1f(id, prog->uniform("u_fog_density"), static_cast<float>(options.fog_density));
    glProgramUniform1i(id, prog->uniform("u_soft_shadows"), options.clean_image ? 1 : 0);
  }
}

GlProgram& Renderer::character_program(Gl& g, const SceneOptions& options) {
  return options.overlap ? g.skinned_lit_overlap : g.skinned_lit;
}

// Characters and environment into the key light's depth map.
void Renderer::shadow_pass(Gl& g, const SceneOptions& options) {
  const FramePlan& plan = g.plan;
  begin_shadow_pass(g);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_FRONT);  // back faces cast the shadow: less acne on lit surfaces
  GLuint p = g.skinned_depth.id();
  glUseProgram(p);
  set_mat4(p, g.skinned_depth.uniform("u_view_proj"), plan.lights.light_view_proj);
  const int depth_base = g.skinned_depth.uniform("u_skin_base");
  const size_t n = options.characters ? crowd_->characters.size() : 0;
  for (size_t i = 0; i < n; ++i) {
    const std::uint64_t caster = g.character_shadow_mesh[i] == 0
                                     ? plan.mesh[i]
                                     : g.lod_sets.at(g.character_shadow_mesh[i]).front().key;
    const GpuMesh& m = g.mesh_cache.at(caster);
    glProgramUniform1i(p, depth_base, static_cast<int>(i * kJointCount));
    set_culling(m.two_sided, GL_FRONT);
    glBindVertexArray(m.vao);
    glDrawElements(GL_TRIANGLES, m.count, GL_UNSIGNED_INT, nullptr);
  }
  p = g.static_depth.id();
  glUseProgram(p);
  set_mat4(p, g.static_depth.uniform("u_view_proj"), plan.lights.light_view_proj);
  glDisable(GL_CULL_FACE);
  draw_environment(g, p, g.static_depth.uniform("u_model"), -1, -1, nullptr);
  glDisable(GL_POLYGON_OFFSET_FILL);
}

// The colour pass: the ground (cached, or cleared and drawn last), then characters near to far, the
// environment and the ground or its shadows. Characters first, ground last: early depth rejection then
// skips ground pixels behind people.
void Renderer::colour_pass(Gl& g, const Camera& camera, const SceneOptions& options) {
  glBindFramebuffer(GL_FRAMEBUFFER, g.msaa_fbo);
  glViewport(0, 0, width_, height_);
  const float bg[4] = {options.background[0], options.background[1], options.background[2], 1.0f};
  const float zero[4] = {0, 0, 0, 0};
  const float one = 1.0f;
  // The overlap mask is drawn, cleared and resolved only in overlap mode (a full-screen multisampled
  // target less to write and resolve otherwise).
  const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  const bool cached_ground = uses_ground_cache(options);
  if (cached_ground) {
    const std::uint64_t wanted = ground_cache_key(camera, options);
    if (wanted != g.ground_key) {
      draw_ground_cache(options);
      g.ground_key = wanted;
    }
    copy_ground_cache();
  } else {
    glClearNamedFramebufferfv(g.msaa_fbo, GL_COLOR, 0, bg);
    glClearNamedFramebufferfv(g.msaa_fbo, GL_DEPTH, 0, &one);
  }
  glNamedFramebufferDrawBuffers(g.msaa_fbo, options.overlap ? 2 : 1, attachments);
  if (options.overlap) glClearNamedFramebufferfv(g.msaa_fbo, GL_COLOR, 1, zero);
  draw_characters(g, options);
  if (options.overlap) draw_inside_surfaces(g);
  const GLuint p = g.flat_lit.id();
  glUseProgram(p);
  draw_environment(g, p, g.flat_lit.uniform("u_model"), g.flat_lit.uniform("u_base_color"),
                   g.flat_lit.uniform("u_emission"), &options.environment);
  if (cached_ground)
    draw_ground_shadows(options.ground, g.plan.lights.key_dir);
  else if (crowd_->environment.ground_plane)
    draw_ground(g, options.ground);
  if (options.clean_image && crowd_->environment.ground_plane) draw_contacts(g, options);
  glBindVertexArray(0);
}

// Each character in the plan's near-to-far order, with its palette, skin matrices and overlap candidates.
void Renderer::draw_characters(Gl& g, const SceneOptions& options) {
  const FramePlan& plan = g.plan;
  GlProgram& program = character_program(g, options);
  const GLuint p = program.id();
  glUseProgram(p);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  const int lit_base = program.uniform("u_skin_base"), palette_loc = program.uniform("u_palette");
  const int offset_loc = program.uniform("u_cap_offset"), count_loc = program.uniform("u_cap_count");
  const int own_loc = program.uniform("u_own_offset");
  triangles_ = 0;
  for (const size_t i : plan.order) {
    const GpuMesh& m = g.mesh_cache.at(plan.mesh[i]);
    const Palette pal = character_palette(crowd_->characters[i].palette);
    float colours[kPaletteSlots * 3];
    for (int r = 0; r < kPaletteSlots; ++r) {
      const Rgb c =
          pal.colour(static_cast<SkinRegion>(std::min(r, static_cast<int>(SkinRegion::kCount) - 1)));
      for (int k = 0; k < 3; ++k)
        colours[3 * r + k] = c[static_cast<size_t>(k)] * c[static_cast<size_t>(k)];  // gamma 2.0 -> linear
    }
    glProgramUniform3fv(p, palette_loc, kPaletteSlots, colours);
    glProgramUniform1i(p, lit_base, static_cast<int>(i * kJointCount));
    glProgramUniform1i(p, offset_loc, plan.cap_offset[i]);
    glProgramUniform1i(p, count_loc, plan.cap_count[i]);
    glProgramUniform1i(p, own_loc, plan.own_offset[i]);
    set_culling(m.two_sided, GL_BACK);
    glBindVertexArray(m.vao);
    glDrawElements(GL_TRIANGLES, m.count, GL_UNSIGNED_INT, nullptr);
    triangles_ += static_cast<size_t>(m.count) / 3;
  }
  glDisable(GL_CULL_FACE);
}

// Overlap mode, characters with a rendered mesh: the part of their surface inside another character's, drawn
// 30 cm nearer the eye over the finished characters (depth test on, no depth writes, both sides: an inside
// surface may face away from the eye; shaders.cpp).
void Renderer::draw_inside_surfaces(Gl& g) {
  const FramePlan& plan = g.plan;
  if (plan.inside.empty()) return;
  GlProgram& program = g.skinned_inside;
  const GLuint p = program.id();
  glUseProgram(p);
  glDisable(GL_CULL_FACE);
  glDepthMask(GL_FALSE);
  const int base_loc = program.uniform("u_skin_base"), offset_loc = program.uniform("u_inside_offset");
  for (const size_t i : plan.order) {
    if (plan.inside_offset[i] < 0) continue;
    const GpuMesh& m = g.mesh_cache.at(plan.mesh[i]);
    glProgramUniform1i(p, base_loc, static_cast<int>(i * kJointCount));
    glProgramUniform1i(p, offset_loc, plan.inside_offset[i]);
    glBindVertexArray(m.vao);
    glDrawElements(GL_TRIANGLES, m.count, GL_UNSIGNED_INT, nullptr);
  }
  glDepthMask(GL_TRUE);
}

// Resolves the multisampled colour attachment (and the overlap mask in overlap mode); nothing to do at
// one sample per pixel, where the frame is read from the drawn target itself and the clean image's
// anti-aliasing runs on the CPU once the pixels are read (fxaa_rgba.hpp says why).
void Renderer::resolve_pass(Gl& g, const SceneOptions& options) {
  overlap_drawn_ = options.overlap;
  g.cpu_aa = !g.multisampled && options.clean_image;
  const GLenum attachments[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  for (int k = 0; k < (!g.multisampled ? 0 : options.overlap ? 2 : 1); ++k) {
    const GLenum attachment = attachments[k];
    glNamedFramebufferReadBuffer(g.msaa_fbo, attachment);
    glNamedFramebufferDrawBuffer(g.resolve_fbo, attachment);
    glBlitNamedFramebuffer(g.msaa_fbo, g.resolve_fbo, 0, 0, width_, height_, 0, 0, width_, height_,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

// Contact darkening: one multiplied quad on the ground per drawn character (shaders.cpp), only colour
// attachment 0, over the depth buffer without writing it.
void Renderer::draw_contacts(Gl& g, const SceneOptions& options) {
  if (g.plan.contacts.empty()) return;
  Gl::upload(g.contact_ssbo, g.contact_capacity, g.plan.contacts);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, g.contact_ssbo);
  const GLuint p = g.contact.id();
  glUseProgram(p);
  set_mat4(p, g.contact.uniform("u_view_proj"), g.plan.view_proj);
  const GLenum first = GL_COLOR_ATTACHMENT0;
  glNamedFramebufferDrawBuffers(g.msaa_fbo, 1, &first);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  glEnable(GL_BLEND);
  glBlendFunc(GL_DST_COLOR, GL_ZERO);
  glBindVertexArray(g.empty_vao);
  glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, static_cast<GLsizei>(g.plan.contacts.size() / 4));
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDepthFunc(GL_LESS);
  (void)options;
}

// The static environment (visible boxes, then meshes in world coordinates), drawn the same way by the
// shadow pass and the colour pass; only the program and its model-matrix uniform differ.
void Renderer::draw_environment(Gl& g, unsigned program, int model_location, int colour_location,
                                int emission_location, const Rgb* environment) {
  // The shadow pass (no colour) draws the environment's own boxes; the set dressing casts no shadow.
  const size_t boxes = environment ? g.box_models.size() : g.physical_boxes;
  for (size_t b = 0; b < boxes; ++b) {
    if (g.plan.box_hidden[b]) continue;
    if (environment) {
      const bool decor = b >= g.physical_boxes;
      set_rgb(program, colour_location, decor ? g.decor[b - g.physical_boxes].colour : *environment);
      glProgramUniform1f(program, emission_location, decor ? g.decor[b - g.physical_boxes].emission : 0.0f);
    }
    set_mat4(program, model_location, g.box_models[b]);
    glBindVertexArray(g.cube.vao);
    glDrawElements(GL_TRIANGLES, g.cube.count, GL_UNSIGNED_INT, nullptr);
  }
  set_mat4(program, model_location, Mat4::Identity());
  if (environment) {
    set_rgb(program, colour_location, *environment);
    glProgramUniform1f(program, emission_location, 0.0f);
  }
  for (const GpuMesh& m : g.environment_meshes) {
    glBindVertexArray(m.vao);
    glDrawElements(GL_TRIANGLES, m.count, GL_UNSIGNED_INT, nullptr);
  }
}

// An empty shadow map, bound for drawing, with the depth bias that keeps lit surfaces free of acne.
void Renderer::begin_shadow_pass(Gl& g) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindFramebuffer(GL_FRAMEBUFFER, g.shadow_fbo);
  glViewport(0, 0, g.shadow_size, g.shadow_size);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.5f, 2.0f);
}

// The ground plane, fully shaded (checker, noise, shadow map) with the current frame's uniforms.
void Renderer::draw_ground(Gl& g, const Rgb& colour) {
  const GLuint p = g.ground_lit.id();
  glUseProgram(p);
  set_rgb(p, g.ground_lit.uniform("u_base_color"), colour);
  set_mat4(p, g.ground_lit.uniform("u_model"), Mat4::Identity());
  glBindVertexArray(g.ground.vao);
  glDrawElements(GL_TRIANGLES, g.ground.count, GL_UNSIGNED_INT, nullptr);
}

void Renderer::read_rgba(std::vector<std::uint8_t>& rgba) {
  gl_->context.make_current();
  rgba.resize(static_cast<size_t>(width_) * height_ * 4);
  glNamedFramebufferReadBuffer(gl_->output_fbo(), GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, gl_->output_fbo());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  if (gl_->cpu_aa) fxaa_rgba(rgba, width_, height_);
}

void Renderer::begin_read_rgba(int slot) {
  gl_->context.make_current();
  glNamedFramebufferReadBuffer(gl_->output_fbo(), GL_COLOR_ATTACHMENT0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, gl_->output_fbo());
  glBindBuffer(GL_PIXEL_PACK_BUFFER, gl_->pbo[slot & 1]);
  gl_->pbo_cpu_aa[slot & 1] = gl_->cpu_aa;
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
}

bool Renderer::finish_read_rgba(int slot, std::vector<std::uint8_t>& rgba) {
  gl_->context.make_current();
  const size_t bytes = static_cast<size_t>(width_) * height_ * 4;
  rgba.resize(bytes);
  const GLuint pbo = gl_->pbo[slot & 1];
  const void* data = glMapNamedBufferRange(pbo, 0, static_cast<GLsizeiptr>(bytes), GL_MAP_READ_BIT);
  if (!data) throw RuntimeError("OpenGL: mapping the pixel buffer failed");
  std::memcpy(rgba.data(), data, bytes);
  glUnmapNamedBuffer(pbo);
  return gl_->pbo_cpu_aa[slot & 1];
}

double Renderer::overlap_fraction() {
  if (!overlap_drawn_) return 0.0;  // overlap mode was off: nothing is flagged
  gl_->context.make_current();
  Gl& g = *gl_;
  g.mask_pixels.resize(static_cast<size_t>(width_) * height_);
  glNamedFramebufferReadBuffer(g.output_fbo(), GL_COLOR_ATTACHMENT1);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, g.output_fbo());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RED, GL_UNSIGNED_BYTE, g.mask_pixels.data());
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  size_t red = 0;
  for (std::uint8_t v : g.mask_pixels) red += v >= 128;
  return static_cast<double>(red) / static_cast<double>(g.mask_pixels.size());
}

}  // namespace crowdlab::stimuli
