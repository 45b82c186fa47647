#include "framework/animation/shoulder_reactions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/closest_approach.hpp"
#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {

namespace {
constexpr double kHoldS = 0.1, kBlendOutS = 0.4, kMinRiseS = 0.25, kMaxRiseS = 0.7;

struct Reaction {
  double start_s, peak_s, target, w_start;
  double value(double t) const {
    if (t < start_s) return 0.0;
    if (t < peak_s)
      return w_start + (target - w_start) * anim::cosine_ease((t - start_s) / (peak_s - start_s));
    if (t < peak_s + kHoldS) return target;
    return target * (1.0 - anim::cosine_ease((t - peak_s - kHoldS) / kBlendOutS));
  }
};

bool is_risk(const ClosestApproach& ca, double ttca_th, double dtca_th) {
  return ca.ttca_s >= 0.0 && ca.ttca_s < ttca_th && ca.dtca_m < dtca_th;
}
}  // namespace

ShoulderReactions compute_shoulder_reactions(const CrowdTrajectories& traj,
                                             const ShoulderReactionParams& params, std::uint64_t seed) {
  if (!(params.ttca_threshold_s >= 0) || !(params.dtca_threshold_m >= 0))
    throw InputError("shoulder reactions: ttca and dtca thresholds must be >= 0");
  if (!(params.trigger_probability >= 0 && params.trigger_probability <= 1))
    throw InputError("shoulder reactions: trigger probability must be in [0, 1], got " +
                     std::to_string(params.trigger_probability));
  const size_t agents = traj.agents.size();
  const auto frames = static_cast<size_t>(traj.frame_count());
  for (const AgentTrajectory& a : traj.agents)
    if (a.position_m.size() != frames)
      throw InputError("shoulder reactions: every agent needs the same frame count");
  if (!(traj.fps > 0)) throw InputError("shoulder reactions: fps must be > 0");

  const bool forced = params.forced_count >= 0;
  const double dtca_th = forced ? std::max(params.dtca_threshold_m, 0.75) : params.dtca_threshold_m;
  std::vector<std::vector<Vec2>> vel(agents, std::vector<Vec2>(frames));
  for (size_t i = 0; i < agents; ++i)
    for (size_t f = 0; f < frames; ++f) vel[i][f] = trajectory_velocity(traj, i, f);

  // Forced mode: the reacting agents are drawn (seeded) among those that meet a risk at all, so that
  // "shoulder = 1" in a pair scene with bystanders still picks one of the crossing pair.
  std::vector<bool> forced_reacts(agents, false);
  if (forced) {
    auto has_risk = [&](size_t i) {
      for (size_t f = 0; f < frames; ++f)
        for (size_t j = 0; j < agents; ++j)
          if (j != i && is_risk(closest_approach(traj.agents[i].position_m[f], vel[i][f],
                                                 traj.agents[j].position_m[f], vel[j][f]),
                                params.ttca_threshold_s, dtca_th))
            return true;
      return false;
    };
    std::vector<size_t> order(agents);
    std::iota(order.begin(), order.end(), size_t{0});
    Rng rng(derive_seed(seed, "shoulder/forced"));
    for (size_t i = agents; i > 1; --i) std::swap(order[i - 1], order[uniform_index(rng, i)]);
    std::stable_partition(order.begin(), order.end(), has_risk);
    for (size_t k = 0; k < std::min(agents, static_cast<size_t>(params.forced_count)); ++k)
      forced_reacts[order[k]] = true;
  }

  ShoulderReactions out;
  out.weight.assign(agents, std::vector<double>(frames, 0.0));
  for (size_t i = 0; i < agents; ++i) {
    std::vector<bool> was_risk(agents, false);
    std::vector<Reaction> reactions;
    for (size_t f = 0; f < frames; ++f) {
      const double t = static_cast<double>(f) / traj.fps;
      const Vec2& pi = traj.agents[i].position_m[f];
      // Rising edges this frame.
      std::vector<ShoulderEvent> fresh;
      for (size_t j = 0; j < agents; ++j) {
        if (j == i) continue;
        const ClosestApproach ca = closest_approach(pi, vel[i][f], traj.agents[j].position_m[f], vel[j][f]);
        const bool risk = is_risk(ca, params.ttca_threshold_s, dtca_th);
        if (risk && !was_risk[j]) {
          ShoulderEvent e;
          e.agent = static_cast<int>(i);
          e.partner = static_cast<int>(j);
          e.frame = static_cast<int>(f);
          e.ttca_s = ca.ttca_s;
          e.dtca_m = ca.dtca_m;
          const Vec2 rel =
              (traj.agents[j].position_m[f] + vel[j][f] * ca.ttca_s) - (pi + vel[i][f] * ca.ttca_s);
          const double h = traj.agents[i].heading_rad[f];
          const double lateral = rel.x() * std::cos(h) - rel.y() * std::sin(h);  // along the agent's +X
          e.side = lateral >= 0 ? 1 : -1;
          const double p = forced ? (forced_reacts[i] ? 1.0 : 0.0) : params.trigger_probability;
          Rng rng(derive_seed(
              seed, "shoulder/" + std::to_string(i) + "/" + std::to_string(j) + "/" + std::to_string(f)));
          e.reacted = p >= 1.0 || (p > 0.0 && uniform01(rng) < p);
          fresh.push_back(e);
        }
        was_risk[j] = risk;
      }
      // React to the earliest closest approach among the accepted risks, unless still rising.
      int best = -1;
      for (size_t e = 0; e < fresh.size(); ++e)
        if (fresh[e].reacted && (best < 0 || fresh[e].ttca_s < fresh[static_cast<size_t>(best)].ttca_s))
          best = static_cast<int>(e);
      const bool rising = !reactions.empty() && t < reactions.back().peak_s;
      for (size_t e = 0; e < fresh.size(); ++e)
        if (static_cast<int>(e) != best || rising) fresh[e].reacted = false;
      if (best >= 0 && !rising) {
        const ShoulderEvent& b = fresh[static_cast<size_t>(best)];
        const double current = reactions.empty() ? 0.0 : reactions.back().value(t);
        reactions.push_back(
            {t, t + std::clamp(b.ttca_s, kMinRiseS, kMaxRiseS), static_cast<double>(b.side), current});
      }
      out.events.insert(out.events.end(), fresh.begin(), fresh.end());
      out.weight[i][f] = reactions.empty() ? 0.0 : std::clamp(reactions.back().value(t), -1.0, 1.0);
    }
  }
  return out;
}

}  // namespace crowdlab
