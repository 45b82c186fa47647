// Lighting model (standard film/photography three-point lighting, e.g. Birn, "Digital Lighting and
// Rendering", 3rd ed., 2014, ch. 4): a key light with shadows (Lambert + Blinn-Phong highlight), a
// fill light at about a third of the key from the other side, a rim light from behind the subject
// that outlines silhouettes against the background, plus hemisphere ambient (sky above, ground
// bounce below). Shading is done in linear RGB and gamma-encoded at the end with gamma 2.0 (sqrt),
// a close, much cheaper stand-in for sRGB's ~2.2 on CPU rasterisers.
// Shadows: a directional shadow map with hardware 2x2 percentage-closer filtering (Reeves et al. 1987).
// Ground: a subtle 1 m checker (4.5 % contrast) times two octaves of tiling value noise from a texture.
// Fog: exponential-squared in distance (the classic OpenGL GL_EXP2 fog), fading to the background.
// Overlap mode (seed 000 Fig. 5, "in red, pixels of the image that contain overlapping volumes"): a
// character fragment is painted red (and flagged in the second render target) when its visible
// surface point lies inside a capsule of ANOTHER character, or when the pixel's ray, within 30 cm
// behind the visible surface, passes through a point inside both this character's capsules and
// another's. The second test is needed because an interpenetration volume is enclosed by the two
// bodies' surfaces and is never itself the visible surface.
// Characters that carry a rendered mesh are tested on that surface instead (issue 27: what is measured
// is what is shown): the CPU flags every drawn vertex inside another character's mesh (frame_plan.hpp),
// and after the characters a second pass (INSIDE_SURFACE) draws only the flagged surface, moved 30 cm
// toward the eye, with the depth test on and depth writes off. The surface of one body inside another
// bounds their common volume, so its pixels are the pixels whose ray meets that volume; the 30 cm shift
// keeps the capsule test's rule that it counts only within 30 cm behind the visible surface.
// Ground shadows on a cached ground (ground_cache.cpp): with one sample per pixel the ground is lit once per
// camera without any shadow (NO_SHADOW) and copied into each frame; the frame's shadows are then applied by
// a multiplicative pass (MATERIAL_GROUND_SHADOW) over the ground that stays visible. Its factor is the
// ratio of the lit ground with and without the shadow map's occlusion, from the same light() as the lit
// shader, square-rooted because the framebuffer holds gamma-2.0-encoded colour: sqrt(a * r) =
// sqrt(a) * sqrt(r). The ground's albedo cancels out of that ratio except in the (2 %) specular term, so
// the result is the ground shaded every frame up to that term and 8-bit rounding.
// Specialisation: the lit fragment shader is compiled once per material (MATERIAL_CHARACTER,
// MATERIAL_GROUND, MATERIAL_FLAT) and, for characters, with or without OVERLAP. A CPU rasteriser
// (llvmpipe) runs both sides of a non-uniform branch under a mask, so one shader with runtime material
// switches paid for the ground's texture lookups and the overlap ray march on every pixel.
#include "stimuli/shaders.hpp"

#include <string>

namespace crowdlab::stimuli::glsl {

const char* const kSkinnedVertex = R"(
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in uvec4 a_bones;
layout(location = 3) in vec4 a_weights;
layout(location = 4) in uint a_region;
layout(location = 5) in vec4 a_colour;  // sRGB vertex colour; alpha 1 replaces the palette colour
layout(location = 6) in float a_lips;   // lip weight of a skin vertex (MannequinVertex::lips)
layout(std430, binding = 0) readonly buffer SkinMatrices { mat4 skin[]; };
uniform mat4 u_view_proj;
uniform int u_skin_base;
out vec3 v_world;
out vec3 v_normal;
flat out uint v_region;
out vec4 v_colour;
out float v_lips;
out vec3 v_rest;
#ifdef INSIDE_SURFACE
// Overlap mode on rendered surfaces (frame_plan.hpp FramePlan::inside): this character's per-vertex flags.
layout(std430, binding = 2) readonly buffer InsideFlags { float inside[]; };
uniform int u_inside_offset;
uniform vec3 u_eye;
out float v_inside;
#endif
void main() {
  mat4 m = a_weights.x * skin[u_skin_base + int(a_bones.x)] + a_weights.y * skin[u_skin_base + int(a_bones.y)] +
           a_weights.z * skin[u_skin_base + int(a_bones.z)] + a_weights.w * skin[u_skin_base + int(a_bones.w)];
  vec4 world = m * vec4(a_position, 1.0);
  v_world = world.xyz;
  v_normal = mat3(m) * a_normal;
  v_region = a_region;
  v_colour = a_colour;
  v_lips = a_lips;
  v_rest = a_position;
#ifdef INSIDE_SURFACE
  v_inside = inside[u_inside_offset + gl_VertexID];
  // Drawn 30 cm nearer the eye than it is, so that it passes the depth test exactly where it lies within
  // 30 cm behind the visible surface (the capsule test's ray-march depth, kOverlapDepth below).
  world.xyz += normalize(u_eye - world.xyz) * 0.30;
#endif
  gl_Position = u_view_proj * world;
}
)";

const char* const kStaticVertex = R"(#version 450 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_view_proj;
uniform mat4 u_model;
out vec3 v_world;
out vec3 v_normal;
flat out uint v_region;
out vec4 v_colour;
out float v_lips;
out vec3 v_rest;
void main() {
  vec4 world = u_model * vec4(a_position, 1.0);
  v_rest = a_position;
  v_world = world.xyz;
  v_normal = mat3(u_model) * a_normal;
  v_region = 0u;
  v_colour = vec4(0.0);
  v_lips = 0.0;
  gl_Position = u_view_proj * world;
}
)";

const char* const kDepthFragment = R"(#version 450 core
void main() {}
)";

const char* const kLitFragment = R"(
in vec3 v_world;
in vec3 v_normal;
flat in uint v_region;
in vec4 v_colour;
in float v_lips;
in vec3 v_rest;  // the rest-pose position (character frame, metres): procedural detail that moves with the body
layout(location = 0) out vec4 o_color;
layout(location = 1) out float o_overlap;
layout(std430, binding = 1) readonly buffer OverlapCapsules { vec4 caps[]; };  // (a, r), (b, 0) pairs
uniform vec3 u_palette[12];      // LINEAR colour per SkinRegion (kPaletteSlots)
uniform vec3 u_base_color;       // sRGB, material 2
uniform float u_emission;        // MATERIAL_FLAT: 1 = a lamp, drawn at its own colour
uniform vec3 u_eye;
uniform vec3 u_key_dir, u_fill_dir, u_rim_dir;  // unit, toward the lights
uniform mat4 u_light_view_proj;
uniform sampler2DShadow u_shadow_map;
uniform sampler2D u_ground_noise;  // tiling value noise in [0, 1], 1 texel = 5 cm
uniform float u_shadow_texel;
uniform int u_soft_shadows;      // 1: four bilinear taps (soft edges); 0: one (hard, the raw path)
uniform vec3 u_background;       // sRGB
uniform float u_fog_density;     // 0 = no fog (1/m)
uniform int u_cap_offset;
uniform int u_own_offset;         // this character's own 24 capsules
uniform int u_cap_count;

vec3 to_linear(vec3 c) { return c * c; }  // gamma 2.0, matching the sqrt encode below

float shadow(vec3 p, vec3 n) {
#ifdef NO_SHADOW
  return 1.0;
#endif
  vec4 l = u_light_view_proj * vec4(p + n * 0.02, 1.0);
  vec3 s = l.xyz / l.w * 0.5 + 0.5;
  if (s.x < 0.0 || s.x > 1.0 || s.y < 0.0 || s.y > 1.0 || s.z > 1.0) return 1.0;
  // Slope-scaled bias: more where the surface turns away from the light, so grazing surfaces keep no acne
  // and lit ones no light leaks (pinholes) from a bias larger than needed.
  float bias = 0.0008 + 0.0022 * (1.0 - clamp(dot(n, u_key_dir), 0.0, 1.0));
  if (u_soft_shadows == 0) return texture(u_shadow_map, vec3(s.xy, s.z - bias));  // bilinear = 2x2 PCF
  // Four bilinear taps on a rotated grid 1.5 texels out: 16 depth compares, a ~4-texel penumbra.
  float t = u_shadow_texel;
  return 0.25 * (texture(u_shadow_map, vec3(s.xy + vec2(-0.6, -1.4) * t, s.z - bias)) +
                 texture(u_shadow_map, vec3(s.xy + vec2(1.4, -0.6) * t, s.z - bias)) +
                 texture(u_shadow_map, vec3(s.xy + vec2(0.6, 1.4) * t, s.z - bias)) +
                 texture(u_shadow_map, vec3(s.xy + vec2(-1.4, 0.6) * t, s.z - bias)));
}

#ifdef OVERLAP
bool inside_capsules(vec3 p, int first, int count) {
  for (int i = first; i < first + count; ++i) {
    vec4 a = caps[2 * i];
    vec3 ab = caps[2 * i + 1].xyz - a.xyz;
    float t = clamp(dot(p - a.xyz, ab) / max(dot(ab, ab), 1e-12), 0.0, 1.0);
    vec3 d = p - (a.xyz + t * ab);
    if (dot(d, d) < a.w * a.w) return true;
  }
  return false;
}

// Does the pixel's ray pass through the volume shared by this character and another one, within
// kOverlapDepth behind the visible surface? (Depth 0 is the visible point itself.)
bool ray_hits_overlap(vec3 p) {
  if (u_cap_count == 0) return false;
  const int kSteps = 11;
  const float kOverlapDepth = 0.30;  // metres: about the depth of a torso
  vec3 dir = normalize(p - u_eye);
  for (int k = 0; k < kSteps; ++k) {
    vec3 q = p + dir * (kOverlapDepth * float(k) / float(kSteps - 1));
    if (k > 0 && !inside_capsules(q, u_own_offset, 24)) return false;  // the ray has left this body
    if (inside_capsules(q, u_cap_offset, u_cap_count)) return true;
  }
  return false;
}
#endif

// The three-point lighting of one surface point in linear RGB: albedo times ambient, key (scaled by the
// shadow factor sh) and fill, plus the key light's Blinn-Phong highlight.
vec3 light(vec3 albedo, vec3 n, vec3 v, float sh, float specular) {
  float key = max(dot(n, u_key_dir), 0.0) * sh;
  float fill = max(dot(n, u_fill_dir), 0.0);
  vec3 sky = vec3(0.62, 0.68, 0.78), bounce = vec3(0.42, 0.39, 0.35);
  vec3 ambient = mix(bounce, sky, 0.5 + 0.5 * n.y) * 0.42;
  vec3 h = normalize(u_key_dir + v);
  float nh = max(dot(n, h), 0.0);
  nh *= nh; nh *= nh; nh *= nh; nh *= nh; nh *= nh;  // ^32 by squaring (cheaper than pow on CPU rasterisers)
  return albedo * (ambient + vec3(1.0, 0.97, 0.92) * 1.05 * key + vec3(0.75, 0.82, 1.0) * 0.32 * fill) +
         vec3(nh * specular * sh);
}

#ifdef INSIDE_SURFACE
in float v_inside;
#endif

void main() {
#ifdef INSIDE_SURFACE
  // The part of a character's rendered surface that lies inside another character's (interpolated flags:
  // the red region ends halfway along an edge from a flagged to an unflagged vertex).
  if (v_inside < 0.5) discard;
  vec3 ni = normalize(v_normal);
  if (!gl_FrontFacing) ni = -ni;
  float lit = 0.45 + 0.55 * max(dot(ni, u_key_dir), 0.0) + 0.3 * max(dot(ni, u_fill_dir), 0.0);
  o_color = vec4(sqrt(clamp(vec3(0.9, 0.02, 0.02) * lit, 0.0, 1.0)), 1.0);
  o_overlap = 1.0;
  return;
#endif
#ifdef MATERIAL_GROUND_SHADOW
  // The factor that turns the ground lit without shadows into the ground lit with this frame's shadows.
  vec3 up = vec3(0.0, 1.0, 0.0), to_eye = normalize(u_eye - v_world), base = to_linear(u_base_color);
  float sh_ground = shadow(v_world, up);
  vec3 ratio = light(base, up, to_eye, sh_ground, 0.02) / max(light(base, up, to_eye, 1.0, 0.02), vec3(1e-4));
  o_color = vec4(sqrt(clamp(ratio, 0.0, 1.0)), 1.0);
  o_overlap = 0.0;
  return;
#endif
  vec3 n = normalize(v_normal);
  if (!gl_FrontFacing) n = -n;
  vec3 albedo;
  float specular = 0.06;
  bool overlap = false;
#if defined(MATERIAL_CHARACTER)
  albedo = v_colour.a > 0.5 ? to_linear(v_colour.rgb) : u_palette[min(v_region, 11u)];
  // Lips: the skin takes the lip colour (slot 9, SkinRegion::kLips) where the interpolated lip weight
  // passes 0.5, blended over about a pixel either side (its screen-space rate), so the outline is a
  // smooth, anti-aliased curve rather than the triangles' edges.
  float lip_edge = max(fwidth(v_lips), 1e-4);
  albedo = mix(albedo, u_palette[9], smoothstep(0.5 - lip_edge, 0.5 + lip_edge, v_lips));
  // Procedural material detail from one noise lookup in rest-pose coordinates (no textures ship): hair gets
  // streaks along its fall (fine across, long down), garments a soft mottle like folds and weave, skin
  // nothing; the eyes get a wet highlight.
  bool hair = v_region == 1u || v_region == 10u;
  bool cloth = v_region >= 2u && v_region <= 6u;
  vec2 uv = hair ? vec2((v_rest.x + v_rest.z) * 9.0, v_rest.y * 0.9) : v_rest.xy * 1.6 + v_rest.z * 0.7;
  float detail = texture(u_ground_noise, uv).r;
  albedo *= hair ? 0.62 + 0.76 * detail : cloth ? 0.94 + 0.12 * detail : 1.0;
  specular = hair ? 0.10 : (v_region == 7u || v_region == 8u) ? 0.6 : cloth ? 0.03 : 0.06;
#ifdef OVERLAP
  overlap = ray_hits_overlap(v_world);
#endif
#elif defined(MATERIAL_GROUND)
  vec2 g = v_world.xz;
  float checker = mod(floor(g.x) + floor(g.y), 2.0) == 0.0 ? 1.0 : 0.955;
  float grain = 0.92 + 0.08 * texture(u_ground_noise, g * 0.078).r + 0.05 * texture(u_ground_noise, g * 0.0061).r;
  albedo = to_linear(u_base_color) * checker * grain;
  specular = 0.02;
#else
  albedo = to_linear(u_base_color);
#endif
  vec3 v = normalize(u_eye - v_world);
  float sh = shadow(v_world, n);
  vec3 color = light(albedo, n, v, sh, specular);
#ifdef MATERIAL_FLAT
  color = mix(color, to_linear(u_base_color), u_emission);
#endif
#if defined(MATERIAL_CHARACTER)
  float grazing = 1.0 - max(dot(n, v), 0.0);
  float rim = grazing * grazing * grazing * max(dot(n, u_rim_dir) + 0.3, 0.0);
  color += vec3(0.22) * rim * albedo + vec3(0.05) * rim;
#endif
#ifdef OVERLAP
  float fill = max(dot(n, u_fill_dir), 0.0);
  if (overlap) color = vec3(0.9, 0.02, 0.02) * (0.45 + 0.55 * max(dot(n, u_key_dir), 0.0) * sh + 0.3 * fill);
#endif
  if (u_fog_density > 0.0) {
    float d = length(u_eye - v_world) * u_fog_density;
    color = mix(to_linear(u_background), color, exp(-d * d));
  }
  o_color = vec4(sqrt(clamp(color, 0.0, 1.0)), 1.0);  // gamma 2.0 encode (sqrt: far cheaper than pow on llvmpipe)
  o_overlap = overlap ? 1.0 : 0.0;
}
)";

// Contact darkening: a soft dark disc on the ground under each character (the occlusion of the sky by a
// body standing on the floor, which the key light's shadow map does not give where that shadow falls
// elsewhere), drawn as one instanced quad per character and multiplied into the framebuffer:
// factor = 1 - 0.32 exp(-d^2 / (2 * 0.22^2)), d the horizontal distance from the character's root (m);
// strength and width chosen on rendered frames so feet read as standing on the floor.
const char* const kContactVertex = R"(#version 450 core
layout(std430, binding = 2) readonly buffer Contacts { vec4 contacts[]; };  // root x, z per character
uniform mat4 u_view_proj;
out vec2 v_offset;
void main() {
  vec2 corner = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? -1.0 : 1.0) * 0.6;
  vec4 c = contacts[gl_InstanceID];
  v_offset = corner;
  gl_Position = u_view_proj * vec4(c.x + corner.x, 0.004, c.y + corner.y, 1.0);
}
)";

const char* const kContactFragment = R"(#version 450 core
in vec2 v_offset;
layout(location = 0) out vec4 o_color;
void main() {
  float d2 = dot(v_offset, v_offset);
  o_color = vec4(vec3(1.0 - 0.32 * exp(-d2 / (2.0 * 0.22 * 0.22))), 1.0);
}
)";

std::string specialise(const char* source, const std::string& defines) {
  std::string out = "#version 450 core\n";
  for (size_t begin = 0; begin < defines.size();) {
    size_t end = defines.find(' ', begin);
    if (end == std::string::npos) end = defines.size();
    if (end > begin) out += "#define " + defines.substr(begin, end - begin) + "\n";
    begin = end + 1;
  }
  return out + source;
}

}  // namespace crowdlab::stimuli::glsl
