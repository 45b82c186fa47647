#include "framework/crowd/crowd_simulation.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {
namespace {
// Agents per parallel task: large enough to amortise scheduling, small enough to balance two cores.
constexpr std::size_t kGrain = 256;

bool finite2(const Vec2& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y());
}
}  // namespace

CrowdSimulation::CrowdSimulation(std::shared_ptr<const NavigationModel> model, std::vector<AgentInit> agents,
                                 std::vector<ObstacleSegment> obstacles, double dt_s)
    : model_(std::move(model)), obstacles_(std::move(obstacles)), dt_(dt_s) {
  if (!model_) throw InputError("crowd simulation: no navigation model");
  if (!(dt_s > 0.0) || !std::isfinite(dt_s))
    throw InputError("crowd.dt_s: must be a positive number of seconds");
  for (std::size_t i = 0; i < agents.size(); ++i) {
    const AgentInit& a = agents[i];
    const std::string who = "crowd simulation: agent " + std::to_string(i) + ": ";
    if (!finite2(a.position) || !finite2(a.velocity) || !finite2(a.goal))
      throw InputError(who + "position, velocity and goal must be finite");
    if (!(a.radius_m > 0.0) || !std::isfinite(a.radius_m))
      throw InputError(who + "radius must be positive, got " + std::to_string(a.radius_m) + " m");
    if (!(a.max_speed_mps > 0.0) || !std::isfinite(a.max_speed_mps) || !(a.preferred_speed_mps >= 0.0) ||
        !std::isfinite(a.preferred_speed_mps))
      throw InputError(who + "max speed must be positive and preferred speed non-negative");
  }
  for (const ObstacleSegment& s : obstacles_)
    if (!finite2(s.a) || !finite2(s.b)) throw InputError("crowd simulation: obstacle segment is not finite");
  const double max_h = model_->max_step_s();
  substeps_ = max_h < dt_ ? static_cast<int>(std::ceil(dt_ / max_h - 1e-9)) : 1;
  const std::size_t n = agents.size();
  for (auto* v : {&px_, &py_, &vx_, &vy_, &gx_, &gy_, &pref_speed_, &max_speed_, &radius_, &pref_vx_,
                  &pref_vy_, &grid_vx_, &grid_vy_, &pre_x_, &pre_y_})
    v->assign(n, 0.0);
  contact_flags_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    px_[i] = agents[i].position.x(), py_[i] = agents[i].position.y();
    vx_[i] = agents[i].velocity.x(), vy_[i] = agents[i].velocity.y();
    gx_[i] = agents[i].goal.x(), gy_[i] = agents[i].goal.y();
    radius_[i] = agents[i].radius_m;
    pref_speed_[i] = agents[i].preferred_speed_mps;
    max_speed_[i] = agents[i].max_speed_mps;
  }
  grid_.set_cell_size(model_->neighbor_radius_m());
  grid_.rebuild(px_.data(), py_.data(), n);
}

void CrowdSimulation::set_preferred_velocity_jitter(double mps, std::uint64_t seed) {
  if (!(mps >= 0.0) || !std::isfinite(mps)) throw InputError("crowd simulation: jitter must be >= 0 m/s");
  jitter_ = mps;
  jitter_seed_ = seed;
}

void CrowdSimulation::update_preferred_velocity(double h, std::size_t i) {
  const double dx = gx_[i] - px_[i], dy = gy_[i] - py_[i];
  const double dist = std::sqrt(dx * dx + dy * dy);
  const double speed = std::min(pref_speed_[i], dist / h);
  const double s = dist > 1e-12 ? speed / dist : 0.0;
  pref_vx_[i] = dx * s;
  pref_vy_[i] = dy * s;
  if (jitter_ > 0.0) {
    // Uniform in the disc: angle and sqrt-radius from two hashed 53-bit fractions.
    const std::uint64_t h1 =
        mix64(jitter_seed_ ^ mix64(static_cast<std::uint64_t>(substep_count_) * 0x100000001b3ull + i));
    const std::uint64_t h2 = mix64(h1);
    const double a = 2.0 * 3.14159265358979323846 * static_cast<double>(h1 >> 11) * 0x1.0p-53;
    const double rad = jitter_ * std::sqrt(static_cast<double>(h2 >> 11) * 0x1.0p-53);
    pref_vx_[i] += rad * std::cos(a);
    pref_vy_[i] += rad * std::sin(a);
  }
}

void CrowdSimulation::substep(double h) {
  const std::size_t n = px_.size();
  // Three parallel passes. Each writes one contiguous block per task (agent order, grid order,
  // agent order), so the two cores never write the same cache line: writing agent slots in grid
  // order, which is spatially scattered, made the second core cost about a third more CPU.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i) update_preferred_velocity(h, i);
                    });
  CrowdWorld world;
  world.count = n;
  world.px = px_.data(), world.py = py_.data(), world.vx = vx_.data(), world.vy = vy_.data();
  world.pref_vx = pref_vx_.data(), world.pref_vy = pref_vy_.data();
  world.radius = radius_.data(), world.max_speed = max_speed_.data();
  world.grid = &grid_;
  world.obstacles = &obstacles_;
  world.dt = h;
  const bool resolve = model_->resolves_overlaps();
  if (resolve) {
    std::fill(contact_flags_.begin(), contact_flags_.end(), 0);
    world.needs_contact_check = contact_flags_.data();
  }
  // Phase 1: new velocities from the old state, in grid order.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      model_->compute_velocities(world, r.begin(), r.end(), grid_vx_.data(), grid_vy_.data());
                    });
  // Phase 2: commit (each agent its own slot). Each agent's cell in the next grid is found here too,
  // in parallel (NeighborGrid::prepare_point writes only its own scratch slot, not what position_of
  // reads), so only the counting sort of finish_rebuild stays serial.
  grid_.begin_rebuild(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i < r.end(); ++i) {
                        const std::size_t k = grid_.position_of(i);
                        vx_[i] = grid_vx_[k];
                        vy_[i] = grid_vy_[k];
                        px_[i] += h * vx_[i];
                        py_[i] += h * vy_[i];
                        grid_.prepare_point(i, px_[i], py_[i]);
                      }
                    });
  if (resolve && std::find(contact_flags_.begin(), contact_flags_.end(), 1) != contact_flags_.end()) {
    // The grid still holds the positions before the move: at most max_speed * h stale.
    double stale = 0.0;
    for (std::size_t i = 0; i < n; ++i) stale = std::max(stale, max_speed_[i] * h);
    std::copy(px_.begin(), px_.end(), pre_x_.begin());
    std::copy(py_.begin(), py_.end(), pre_y_.begin());
    const OverlapResolutionResult r =
        resolve_disc_overlaps(px_.data(), py_.data(), radius_.data(), n, contact_flags_.data(), grid_, stale,
                              obstacles_, OverlapResolutionOptions{}, overlap_scratch_);
    // The velocity is what the agent actually did (as in position-based dynamics), so the next
    // step's reciprocal constraints start from the blocked motion, not from the intended one.
    const double inv_h = 1.0 / h;
    for (std::size_t i = 0; i < n; ++i) {
      vx_[i] += (px_[i] - pre_x_[i]) * inv_h;
      vy_[i] += (py_[i] - pre_y_[i]) * inv_h;
    }
    ++overlap_resolutions_;
    overlap_contacts_ += static_cast<long long>(r.contacts);
    grid_.rebuild(px_.data(), py_.data(), n);  // the projection moved agents after prepare_point
  } else {
    grid_.finish_rebuild(px_.data(), py_.data(), n);
  }
  ++substep_count_;
}

void CrowdSimulation::step() {
  const double h = dt_ / substeps_;
  for (int s = 0; s < substeps_; ++s) substep(h);
  time_ += dt_;
}

}  // namespace crowdlab
