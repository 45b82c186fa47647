// The collision proxies of a whole crowd (fit_crowd_proxies.hpp).
#include "framework/body/fit_crowd_proxies.hpp"

#include <spdlog/spdlog.h>

#include "framework/body/cover_capsules.hpp"

namespace crowdlab {
namespace {

/// The capsules of `shape` outside kUpperBodyProxies set back to `volume`'s, and the rest-pose contact
/// pairs found again for the mixed set.
void keep_volume_below_chest(BodyShape& shape, const std::array<Capsule, kJointCount>& volume) {
  for (int j = 0; j < kJointCount; ++j)
    if (!(kUpperBodyProxies >> j & 1u))
      shape.capsules[static_cast<size_t>(j)] = volume[static_cast<size_t>(j)];
  compute_rest_contact_pairs(shape);
}

}  // namespace

void fit_crowd_proxies(CrowdAnimation& crowd, ProxyFit fit) {
  if (fit == ProxyFit::volume) return;
  const bool per_surface = fit == ProxyFit::per_surface || fit == ProxyFit::upper_body;
  const SurfaceTolerances tolerances =
      per_surface ? SurfaceTolerances::per_surface() : SurfaceTolerances::uniform(0.005);
  double before = 0, after = 0, bounded = 0;
  int n = 0;
  for (CharacterAnimation& c : crowd.characters) {
    if (!c.mesh) continue;
    const std::array<Capsule, kJointCount> volume = c.shape.capsules;
    const CoverReport r = fit_capsules_to_mesh(c.shape, *c.mesh, tolerances, per_surface);
    if (fit == ProxyFit::upper_body) keep_volume_below_chest(c.shape, volume);
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
