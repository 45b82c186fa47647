// The collision proxies a correction runs with (proxy_fit_options.hpp).
#include "experiments/cli/proxy_fit_options.hpp"

#include <string>

namespace crowdlab::cli {

void add_proxy_fit_options(Command* cmd, std::optional<ProxyFit>& fit, const char* what) {
  Option* cover = cmd->add_flag_callback(
      "--cover-mesh", [&fit] { fit = ProxyFit::cover_mesh; },
      std::string("Grow each character's capsules until its rendered mesh (MPFB2 skin, garments, hair) lies "
                  "within 5 mm of them in the rest pose, before correcting; ") +
          what);
  Option* per_surface =
      cmd->add_flag_callback(
             "--fit-proxies", [&fit] { fit = ProxyFit::per_surface; },
             std::string("Fit each character's capsules to its rendered mesh per surface before correcting: "
                         "skin, face, garments and shoe uppers within 5 mm, hair within 20 mm, soles not "
                         "bounded, each capsule's axis moved toward the surface it must take in "
                         "(docs/correction.md); ") +
                 what)
          ->excludes(cover);
  cmd->add_flag_callback(
         "--fit-upper-proxies", [&fit] { fit = ProxyFit::upper_body; },
         std::string("As --fit-proxies for the chest, neck, head, collars and arms only; the pelvis, lower "
                     "spine and legs keep their volume-fitted capsules (docs/correction.md, session 26); ") +
             what)
      ->excludes(cover)
      ->excludes(per_surface);
}

}  // namespace crowdlab::cli
