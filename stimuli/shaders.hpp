#pragma once
// GLSL 4.50 sources of the renderer's programs (see shaders.cpp for the lighting model).
#include <string>

namespace crowdlab::stimuli::glsl {

/// Skinned characters: linear blend skinning from an SSBO of per-bone skin matrices (no #version line: use
/// specialise()).
extern const char* const kSkinnedVertex;
/// Static geometry (ground, boxes, meshes) with a model matrix.
extern const char* const kStaticVertex;
/// Depth-only fragment shader for the shadow pass.
extern const char* const kDepthFragment;
/// Lit fragment shader (no #version line: use specialise()) for every material, with shadows, fog
/// and the overlap test. Defines: MATERIAL_CHARACTER | MATERIAL_GROUND | MATERIAL_FLAT |
/// OVERLAP.
extern const char* const kLitFragment;

/// The clean image's contact darkening (SceneOptions::clean_image; its anti-aliasing runs on the CPU,
/// fxaa_rgba.hpp): quads of 4 vertices per instance, a triangle strip; instance i reads root (x, z) from
/// SSBO binding 2.
extern const char* const kContactVertex;
extern const char* const kContactFragment;

/// "#version 450 core", one "#define NAME" per space-separated word of `defines`, then `source`.

std::string specialise(const char* source, const std::string& defines);

}  // namespace crowdlab::stimuli::glsl
