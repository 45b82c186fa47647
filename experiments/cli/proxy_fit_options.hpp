#pragma once
// The collision proxies a correction runs with, shared by `crowdlab correct` and `crowdlab experiment
// overlap-vs-density`: without a flag, the capsules the crowd file carries (`correct`) or the spec gives its
// scenario (`overlap-vs-density`, animation.collision_proxies); with one, capsules fitted to each character's
// rendered mesh before correcting (framework/body/cover_capsules.hpp;
// docs/correction.md "Proxies fitted per surface" for what each costs in motion). The fit itself is
// framework/body/fit_crowd_proxies.hpp.
#include <optional>

#include "experiments/cli/command.hpp"
#include "framework/body/fit_crowd_proxies.hpp"

namespace crowdlab::cli {

/// Adds the mutually exclusive flags --cover-mesh and --fit-proxies to `cmd`, writing into `fit` (which
/// must outlive the parse; left empty when neither is given). `what` ends both help texts: what becomes
/// of the fitted capsules ("the output carries them").
void add_proxy_fit_options(Command* cmd, std::optional<ProxyFit>& fit, const char* what);

}  // namespace crowdlab::cli
