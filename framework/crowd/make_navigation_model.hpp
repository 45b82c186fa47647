#pragma once
// The navigation model named by the spec (crowd.model): orca | social | cost | none.
// "none" walks every agent at its preferred velocity with no interaction at all (a baseline and the
// straight lines of controlled stimuli). Parameters come from CrowdSpec; see each model's header for
// its constants and their sources.
#include <memory>

#include "framework/crowd/navigation_model.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// Throws InputError for an unknown model name or out-of-range parameters ("crowd.<key>: ...").
std::shared_ptr<const NavigationModel> make_navigation_model(const CrowdSpec& crowd);

/// Agents that ignore each other and walk at their preferred velocity (capped at max speed).
class StraightLineModel final : public NavigationModel {
 public:
  explicit StraightLineModel(double neighbor_distance_m = 2.0) : neighbor_distance_(neighbor_distance_m) {}
  std::string_view name() const override { return "none"; }
  double neighbor_radius_m() const override { return neighbor_distance_; }
  void compute_velocities(const CrowdWorld& world, std::size_t begin, std::size_t end, double* new_vx,
                          double* new_vy) const override;

 private:
  double neighbor_distance_;
};

}  // namespace crowdlab
