#include "framework/core/viewpoint_catalogue.hpp"

namespace crowdlab {

const std::vector<std::string>& viewpoint_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const ViewpointPreset& p : kViewpointCatalogue) out.emplace_back(p.name);
    return out;
  }();
  return names;
}

const ViewpointPreset* find_viewpoint(std::string_view name) {
  for (const ViewpointPreset& p : kViewpointCatalogue)
    if (p.name == name) return &p;
  return nullptr;
}

}  // namespace crowdlab
