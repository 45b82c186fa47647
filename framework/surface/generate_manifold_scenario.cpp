#include "framework/surface/generate_manifold_scenario.hpp"

#include <cmath>
#include <limits>
#include <memory>

#include "framework/core/error.hpp"
#include "framework/core/precondition.hpp"
#include "framework/core/seed.hpp"
#include "framework/surface/develop_surface_trajectories.hpp"
#include "framework/surface/smooth_surface_up.hpp"
#include "framework/surface/spec_surface.hpp"
#include "framework/surface/surface_crowd.hpp"
#include "framework/surface/surface_scenes.hpp"

namespace crowdlab {
namespace {

constexpr double kAgentHeightM = 1.8;
constexpr int kGoalCount = 8;
constexpr double kWarmUpS = 1.0;
constexpr double kFacingSpeedMps = 0.1;

SurfaceCrowdParams params_from_spec(const ExperimentSpec& spec) {
  SurfaceCrowdParams p;
  const CrowdModel model = spec.crowd.model;
  // The spec loader checks the surface crowd's model and ranges (file:line:column, check_manifold_crowd);
  // here they are preconditions.
  precondition(model == CrowdModel::orca || model == CrowdModel::social, "crowd.model: orca or social");
  p.avoidance = model == CrowdModel::orca ? SurfaceAvoidance::kOrca : SurfaceAvoidance::kSocialForces;
  precondition(spec.crowd.neighbor_distance_m > 0 && spec.crowd.neighbor_distance_m <= 10,
               "crowd.neighbor_distance_m in (0, 10] m");
  precondition(spec.crowd.max_neighbors >= 1 && spec.crowd.max_neighbors <= 32,
               "crowd.max_neighbors in [1, 32]");
  precondition(spec.crowd.time_horizon_s > 0 && spec.crowd.time_horizon_s <= 10,
               "crowd.time_horizon_s in (0, 10] s");
  precondition(2 * spec.crowd.agent_radius_m <= kAgentHeightM, "crowd.agent_radius_m <= 0.9 m");
  precondition(spec.scenario.walk_speed_mps > 0 && spec.scenario.walk_speed_mps <= 3,
               "scenario.walk_speed_mps in (0, 3] m/s");
  p.body.height_m = kAgentHeightM;
  p.body.sphere_radius_m = spec.crowd.agent_radius_m;
  p.neighbor_distance_m = spec.crowd.neighbor_distance_m;
  p.max_neighbors = spec.crowd.max_neighbors;
  p.orca_time_horizon_s = spec.crowd.time_horizon_s;
  p.preferred_speed_mps = spec.scenario.walk_speed_mps;
  p.max_speed_mps = std::max(spec.crowd.max_speed_mps, spec.scenario.walk_speed_mps);
  const double frame_s = 1.0 / spec.fps;
  const int substeps = std::max(1, static_cast<int>(std::ceil(frame_s / spec.crowd.dt_s - 1e-9)));
  p.dt_s = frame_s / substeps;
  p.relevant = RelevantMode::kVisibility;
  return p;
}

TriangleMesh environment_mesh(const SurfaceMesh& m) {
  TriangleMesh t;
  t.name = m.name;
  t.vertices_m = m.vertices_m;
  t.triangles = m.triangles;
  return t;
}

}  // namespace

ManifoldScenario generate_manifold_scenario(const ExperimentSpec& spec, const Condition& condition) {
  precondition(spec.fps > 0 && spec.duration_s > 0, "fps and duration_s > 0");
  precondition(!spec.scenario.mesh.empty(), "scenario.mesh: a manifold scenario needs one");
  const SurfaceCrowdParams params = params_from_spec(spec);
  auto mesh = std::make_shared<const SurfaceMesh>(load_spec_surface(spec));
  check_surface_crowd_limits(spec, *mesh);  // before scenario_character_count narrows the count to int
  const int n = scenario_character_count(spec, condition, mesh->total_area_m2);
  const std::uint64_t seed = derive_seed(condition.seed, "manifold");
  const SurfaceCrowdModel model = make_surface_crowd_model(mesh, params, kGoalCount, seed);
  SurfaceCrowdState state = spawn_surface_agents(model, n, seed);

  const int substeps = static_cast<int>(std::lround(1.0 / (spec.fps * params.dt_s)));
  for (long k = 0, warm = std::lround(kWarmUpS / params.dt_s); k < warm; ++k)
    step_surface_crowd(model, state);
  const int frames = std::max(1, static_cast<int>(std::lround(spec.duration_s * spec.fps)));

  ManifoldScenario out;
  out.triangles = mesh->face_count();
  out.surface.agents.resize(static_cast<size_t>(n));
  std::vector<Vec3> facing(static_cast<size_t>(n), Vec3::Zero());
  for (int f = 0; f < frames; ++f) {
    if (f > 0)
      for (int k = 0; k < substeps; ++k) step_surface_crowd(model, state);
    for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
      const SurfacePoint& p = state.points[i];
      const Vec3 up = smooth_surface_up(*mesh, p);
      Vec3 fwd = state.velocity_mps[i];
      if (fwd.norm() < kFacingSpeedMps) fwd = facing[i];
      fwd -= up * up.dot(fwd);
      if (fwd.norm() < 1e-9) {  // never moved yet: any tangent direction
        const Vec3 ref = std::abs(up.z()) < 0.9 ? Vec3::UnitZ() : Vec3::UnitX();
        fwd = ref - up * up.dot(ref);
      }
      fwd.normalize();
      facing[i] = fwd;
      SurfaceAgentTrajectory& a = out.surface.agents[i];
      a.feet_m.push_back(p.position_m);
      a.up.push_back(up);
      a.forward.push_back(fwd);
    }
  }

  ScenarioResult& r = out.result;
  r.trajectories = develop_surface_trajectories(out.surface, spec.fps, params.body.sphere_radius_m);
  r.environment.ground_plane = false;
  r.environment.meshes.push_back(environment_mesh(*mesh));
  r.area_m2 = mesh->total_area_m2;
  r.achieved_density_per_m2 = n / mesh->total_area_m2;
  double min_gap = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < static_cast<size_t>(n); ++i)
    for (size_t j = i + 1; j < static_cast<size_t>(n); ++j)
      min_gap = std::min(min_gap, (out.surface.agents[i].feet_m[0] - out.surface.agents[j].feet_m[0]).norm());
  r.min_spacing_m = std::isfinite(min_gap) ? min_gap : 0.0;
  r.scenario = ScenarioKind::manifold;
  return out;
}

}  // namespace crowdlab
