#pragma once
// GLSL 4.50 sources of the renderer's programs (see shaders.cpp for the lighting model).
namespace crowdlab::stimuli::glsl {

/// Skinned characters: linear blend skinning from an SSBO of per-bone skin matrices.
extern const char* const kSkinnedVertex;
/// Static geometry (ground, boxes, meshes) with a model matrix.
extern const char* const kStaticVertex;
/// Depth-only fragment shader for the shadow pass.
extern const char* const kDepthFragment;
/// Lit fragment shader shared by every material, with shadows, fog and the overlap test.
extern const char* const kLitFragment;

}  // namespace crowdlab::stimuli::glsl
