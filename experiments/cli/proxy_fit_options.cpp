// The collision proxies a correction runs with (proxy_fit_options.hpp).
#include "experiments/cli/proxy_fit_options.hpp"

#include <spdlog/spdlog.h>

#include <string>

#include "framework/body/cover_capsules.hpp"

namespace crowdlab::cli {

void add_proxy_fit_options(Command* cmd, ProxyFit& fit, const char* what) {
  Option* cover = cmd->add_flag_callback(
      "--cover-mesh", [&fit] { fit = ProxyFit::cover_mesh; },
      std::string("Grow each character's capsules until its rendered mesh (MPFB2 skin, garments, hair) lies "
                  "within 5 mm of them in the rest pose, before correcting; ") +
          what);
  cmd->add_flag_callback(
         "--fit-proxies", [&fit] { fit = ProxyFit::per_surface; },
         std::string("Fit each character's capsules to its rendered mesh per surface before correcting: "
                     "skin, face, garments and shoe uppers within 5 mm, hair within 20 mm, soles not "
                     "bounded, each capsule's axis moved toward the surface it must take in "
                     "(docs/correction.md); ") +
             what)
      ->excludes(cover);
}

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

}  // namespace crowdlab::cli
