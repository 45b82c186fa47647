#pragma once
// The scene `crowdlab bench render` measures by default: a real stimulus of the seed 000 study, the
// stationary concert crowd at its densest level (D5, 6.66 characters/m^2 on 9 m^2: 60 dancing
// characters), animated exactly as `crowdlab run` animates baseline.glb
// (framework/pipeline/animate_scenario.hpp, animate_scenario), with the spec's body model (MPFB2 bodies
// unless told otherwise).
#include <optional>
#include <string>

#include "framework/core/crowd_animation.hpp"
#include "framework/spec/condition_kinds.hpp"

namespace crowdlab::cli {

struct BenchRenderScene {
  std::string spec_path;                ///< "" = the embedded gomez2024_stationary spec
  std::string condition_id;             ///< "" = the first condition whose density level is `density`
  double density = 6.66;                ///< characters per m^2 (used when condition_id is empty)
  std::optional<BodyModel> body_model;  ///< nullopt = the spec's
  double duration_s = 0.0;  ///< > 0: shorten the crowd to this many seconds (the start is unchanged)
};

/// Generates the crowd stage and the animation stage of the chosen condition. Throws InputError when the
/// spec, condition or body model cannot be used.
CrowdAnimation make_bench_render_crowd(const BenchRenderScene& scene);

}  // namespace crowdlab::cli
