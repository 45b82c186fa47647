#include "framework/core/viewpoint_catalogue.hpp"

#include <cmath>

namespace crowdlab {

static_assert([] {
  for (std::size_t i = 0; i < kViewpointCatalogue.size(); ++i)
    if (static_cast<std::size_t>(kViewpointCatalogue[i].id) != i) return false;
  return true;
}());

const std::vector<std::string>& viewpoint_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const ViewpointPreset& p : kViewpointCatalogue) out.emplace_back(p.name);
    return out;
  }();
  return names;
}

std::optional<ViewpointId> find_viewpoint(std::string_view name) {
  for (const ViewpointPreset& p : kViewpointCatalogue)
    if (p.name == name) return p.id;
  return std::nullopt;
}

std::string camera_placement_problem(const CameraPlacement& p) {
  for (double x : p)
    if (!std::isfinite(x)) return "values must be finite";
  if (!(p[6] > 1.0 && p[6] < 170.0)) return "fov_deg must be in (1, 170)";
  const double dx = p[0] - p[3], dy = p[1] - p[4], dz = p[2] - p[5];
  if (std::sqrt(dx * dx + dy * dy + dz * dz) < 1e-6) return "the camera position equals its target";
  return "";
}

}  // namespace crowdlab
