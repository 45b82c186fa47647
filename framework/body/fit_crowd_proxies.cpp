// The collision proxies of a whole crowd (fit_crowd_proxies.hpp).
#include "framework/body/fit_crowd_proxies.hpp"

#include <spdlog/spdlog.h>

#include "framework/body/cover_capsules.hpp"

namespace crowdlab {

void fit_crowd_proxies(CrowdAnimation& crowd, ProxyFit fit) {
  if (fit == ProxyFit::volume) return;
  const bool per_surface = fit == ProxyFit::per_surface;
  const SurfaceTolerances tolerances =
      per_surface ? SurfaceTolerances::per_surface() : SurfaceTolerances::uniform(0.005);
  double before = 0, after = 0, bounded = 0;
  int n = 0;
  for (CharacterAnimation& c : crowd.characters) {
    if (!c.mesh) continue;
    const CoverReport r = fit_capsules_to_mesh(c.shape, *c.mesh, tolerances, per_surface);
    before += r.within_before;
    after += r.within_after;
    bounded += r.bounded_within_after;
    ++n;
  }
  if (n > 0)
    spdlog::info(
        "capsules fitted to the rendered meshes of {} characters: {:.2f} % -> {:.2f} % of rest-pose "
        "vertices within 5 mm, {:.2f} % of the bounded ones within their surface's tolerance (means over "
        "characters)",
        n, 100 * before / n, 100 * after / n, 100 * bounded / n);
}

}  // namespace crowdlab
