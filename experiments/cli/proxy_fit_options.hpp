#pragma once
// The collision proxies a correction runs with, shared by `crowdlab correct` and `crowdlab experiment
// overlap-vs-density`: the volume-fitted capsules every body is built with (the default), or capsules
// fitted to each character's rendered mesh before correcting (framework/body/cover_capsules.hpp;
// docs/correction.md "Proxies fitted per surface" for what each costs in motion).
#include "experiments/cli/command.hpp"
#include "framework/core/crowd_animation.hpp"

namespace crowdlab::cli {

enum class ProxyFit {
  volume,       ///< the body's own capsules, fitted to the volume of the skin each bone carries
  cover_mesh,   ///< grown until every rendered surface lies within 5 mm (`--cover-mesh`)
  per_surface,  ///< fitted per surface, axes moved (`--fit-proxies`; SurfaceTolerances::per_surface)
};

/// Adds the mutually exclusive flags --cover-mesh and --fit-proxies to `cmd`, writing into `fit` (which
/// must outlive the parse). `what` ends both help texts: what becomes of the fitted capsules ("the
/// output carries them").
void add_proxy_fit_options(Command* cmd, ProxyFit& fit, const char* what);

/// Fits the capsules of every character of `crowd` that carries a rendered mesh as `fit` says (nothing for
/// ProxyFit::volume) and logs the share of rest-pose vertices within 5 mm before and after. Characters
/// without a mesh keep their capsules.
void fit_crowd_proxies(CrowdAnimation& crowd, ProxyFit fit);

}  // namespace crowdlab::cli
