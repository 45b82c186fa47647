#pragma once
// The spec's body model (animation.body_model) for one crowd: with `mpfb2` the characters' bodies are
// sampled from the MPFB2 / MakeHuman assets (body/sample_mpfb2_bodies.hpp: heights drawn by sex from
// the world distributions and matched on the shaped meshes; skeleton and capsules from the shaped
// mesh) and their skinned surfaces travel with the crowd for the renderer; with `procedural` nothing
// is set and animate_crowd() samples procedural bodies.
// Seeds: derive_seed(context.seed, "bodies"), as the procedural bodies.
// The asset folder is loaded once per process and shared (Mpfb2Model is immutable).
#include <cstddef>

#include "framework/animation/animate_crowd.hpp"
#include "framework/body/fit_crowd_proxies.hpp"

namespace crowdlab {

/// Fills context.shapes and context.meshes for `agents` characters when spec.body_model is "mpfb2".
/// Throws InputError when the asset folder is missing or broken (naming the file).
void apply_body_model(const AnimationSpec& spec, std::size_t agents, AnimationContext& context);

/// Loads the asset folder apply_body_model would load (once per process; nothing for procedural
/// bodies), so that `validate` refuses a broken folder as `run` would (issue 33). Throws InputError
/// naming the asset file.
void load_body_model_assets(const AnimationSpec& spec);

/// The collision proxies spec.collision_proxies asks for in a crowd of `scenario`: `auto` is `fitted` for
/// a stationary crowd of MPFB2 bodies and `volume` otherwise (experiment_spec.hpp says why).
CollisionProxies resolve_collision_proxies(const AnimationSpec& spec, ScenarioKind scenario);

/// The body fit of resolved proxies: per_surface for `fitted`, volume for `volume` (and `auto`, which
/// resolve_collision_proxies never returns).
ProxyFit proxy_fit(CollisionProxies resolved);

}  // namespace crowdlab
