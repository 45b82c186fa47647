#include "framework/surface/spec_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "framework/core/error.hpp"
#include "framework/spec/locate_spec_key.hpp"
#include "framework/spec/work_limits.hpp"
#include "framework/surface/surface_scenes.hpp"

namespace crowdlab {

namespace {

std::string number_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace

SurfaceMesh load_spec_surface(const ExperimentSpec& spec) {
  try {
    return make_surface_scene(spec.scenario.mesh);
  } catch (const InputError& e) {
    throw InputError(locate_spec_key(spec.source_path, "scenario.mesh"), e.what());
  }
}

double largest_surface_crowd(const ExperimentSpec& spec, double area_m2) {
  double most = spec.scenario.agents;
  if (const Factor* characters = spec.factor("characters")) {
    for (const FactorLevel& l : characters->levels) most = std::max(most, l.number.value_or(0.0));
    return most;
  }
  if (const Factor* density = spec.factor("density"))
    for (const FactorLevel& l : density->levels)
      most = std::max(most, std::round(l.number.value_or(0.0) * area_m2));
  return most;
}

void check_surface_crowd_limits(const ExperimentSpec& spec, const SurfaceMesh& mesh) {
  const double characters = largest_surface_crowd(spec, mesh.total_area_m2);
  const double frames = std::ceil(spec.duration_s * spec.fps);
  const SourceLocation where =
      locate_spec_key(spec.source_path, spec.factor("density") ? "factors.density" : "factors");
  const std::string size = "the largest crowd on '" + spec.scenario.mesh + "' (" +
                           number_text(mesh.total_area_m2) + " m^2) has " + number_text(characters) +
                           " characters";
  if (characters > kMaxCharactersPerCrowd)
    throw InputError(where, size + ", more than the limit of " + number_text(kMaxCharactersPerCrowd) +
                                " (density x the mesh's area); lower the density or use a smaller mesh");
  if (characters * frames > kMaxCharacterFrames)
    throw InputError(where,
                     size + " x " + number_text(frames) + " frames (duration_s x fps) = " +
                         number_text(characters * frames) + " character-frames, more than the limit of " +
                         number_text(kMaxCharacterFrames) + "; shorten the clip, lower fps or the density");
}

}  // namespace crowdlab
