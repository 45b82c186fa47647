#include "framework/surface/spec_surface.hpp"

#include <cmath>

#include "framework/core/error.hpp"
#include "framework/spec/estimate_work.hpp"
#include "framework/spec/locate_spec_key.hpp"
#include "framework/spec/yaml_section.hpp"
#include "framework/surface/surface_scenes.hpp"

namespace crowdlab {

SurfaceMesh load_spec_surface(const ExperimentSpec& spec) {
  try {
    return make_surface_scene(spec.scenario.mesh);
  } catch (const InputError& e) {
    throw InputError(locate_spec_key(spec.source_path, "scenario.mesh"), e.what());
  }
}

void check_surface_crowd_limits(const ExperimentSpec& spec, const SurfaceMesh& mesh) {
  const double characters = largest_crowd_on_area(spec, mesh.total_area_m2);
  const std::string crowd =
      "the largest crowd on '" + spec.scenario.mesh + "' (" + format_number(mesh.total_area_m2) + " m^2)";
  if (const auto problem =
          crowd_limit_problem(crowd, characters, std::ceil(spec.duration_s * spec.fps),
                              "lower the density (x the mesh's area) or use a smaller mesh",
                              "shorten the clip (duration_s x fps frames), lower fps or the density"))
    throw InputError(
        locate_spec_key(spec.source_path, spec.factor("density") ? "factors.density" : "factors"), *problem);
}

}  // namespace crowdlab
