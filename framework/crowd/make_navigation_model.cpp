#include "framework/crowd/make_navigation_model.hpp"

#include <cmath>

#include "framework/core/error.hpp"
#include "framework/core/precondition.hpp"
#include "framework/crowd/cost_gradient_model.hpp"
#include "framework/crowd/orca_model.hpp"
#include "framework/crowd/social_force_model.hpp"

namespace crowdlab {

void StraightLineModel::compute_velocities(const CrowdWorld& w, std::size_t begin, std::size_t end,
                                           double* new_vx, double* new_vy) const {
  for (std::size_t k = begin; k < end; ++k) {
    const std::uint32_t i = w.grid->order(k);
    double vx = w.pref_vx[i], vy = w.pref_vy[i];
    clamp_speed(vx, vy, w.max_speed[i]);
    new_vx[k] = vx;
    new_vy[k] = vy;
  }
}

std::shared_ptr<const NavigationModel> make_navigation_model(const CrowdSpec& c) {
  // The spec loader checks these ranges (file:line:column); here they are preconditions.
  precondition(c.agent_radius_m > 0.0 && c.agent_radius_m <= 1.0, "crowd.agent_radius_m in (0, 1] m");
  precondition(c.max_speed_mps > 0.0 && std::isfinite(c.max_speed_mps), "crowd.max_speed_mps > 0");
  precondition(c.dt_s > 0.0 && std::isfinite(c.dt_s), "crowd.dt_s > 0");
  precondition(c.neighbor_distance_m > 0.0 && std::isfinite(c.neighbor_distance_m),
               "crowd.neighbor_distance_m > 0");
  precondition(!c.overlap_free || c.model == CrowdModel::orca,
               "crowd.overlap_free: applies to model orca only");
  switch (c.model) {
    case CrowdModel::orca: {
      OrcaParams p;
      p.neighbor_distance_m = c.neighbor_distance_m;
      p.max_neighbors = c.max_neighbors;
      p.time_horizon_s = c.time_horizon_s;
      p.obstacle_time_horizon_s = c.obstacle_time_horizon_s;
      p.resolve_overlaps = c.overlap_free;
      return std::make_shared<OrcaModel>(p);
    }
    case CrowdModel::social: {
      SocialForceParams p;
      p.neighbor_distance_m = c.neighbor_distance_m;
      return std::make_shared<SocialForceModel>(p);
    }
    case CrowdModel::cost: {
      CostGradientParams p = cost_gradient_params_from_weights(c.cost_weights);
      p.neighbor_distance_m = c.neighbor_distance_m;
      p.max_neighbors = std::max(c.max_neighbors, 1);
      return std::make_shared<CostGradientModel>(p);
    }
    case CrowdModel::none:
      return std::make_shared<StraightLineModel>(c.neighbor_distance_m);
  }
  throw InputError("crowd.model: not a navigation model");  // unreachable: every enumerator is handled
}

}  // namespace crowdlab
