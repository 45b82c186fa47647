#include "stimuli/crowd_extent.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <string>

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {
namespace {

Vec3 horizontal(const Vec3& v) {
  return Vec3(v.x(), 0.0, v.z());
}

/// Grows [lo, hi] by the axis-aligned box of the disc of radius r centred at p, orthogonal to unit u.
void add_disc(const Vec3& p, const Vec3& u, double r, Vec3& lo, Vec3& hi) {
  const Vec3 half(r * std::sqrt(std::max(0.0, 1.0 - u.x() * u.x())),
                  r * std::sqrt(std::max(0.0, 1.0 - u.y() * u.y())),
                  r * std::sqrt(std::max(0.0, 1.0 - u.z() * u.z())));
  lo = lo.cwiseMin(p - half);
  hi = hi.cwiseMax(p + half);
}

void check_heights(size_t agents, const std::vector<double>& heights_m) {
  if (heights_m.size() != agents)
    throw InputError("crowd extent: " + std::to_string(heights_m.size()) + " body heights for " +
                     std::to_string(agents) + " characters");
}

/// The follow path and relative box of a travelling crowd (see crowd_extent.hpp); nothing otherwise.
void add_follow_path(const std::vector<CharacterTrack>& tracks, CrowdExtent& e) {
  const size_t frames = tracks.front().feet_m.size();
  std::vector<Vec3> centroid(frames, Vec3::Zero());
  for (const CharacterTrack& t : tracks)
    for (size_t f = 0; f < frames; ++f) centroid[f] += horizontal(t.feet_m[f]);
  for (Vec3& c : centroid) c /= static_cast<double>(tracks.size());
  if ((centroid.back() - centroid.front()).norm() <= kFollowTravelM) return;
  // Symmetric window, shrinking at the ends: the path starts and ends on the centroid itself and has no
  // lag (a one-sided window would slow the camera down in the first and last second).
  const long n = static_cast<long>(frames);
  const long half = std::max(1L, std::lround(e.fps));
  e.follow_path_m.resize(frames);
  for (long f = 0; f < n; ++f) {
    const long h = std::min({half, f, n - 1 - f});
    Vec3 sum = Vec3::Zero();
    for (long g = f - h; g <= f + h; ++g) sum += centroid[static_cast<size_t>(g)];
    e.follow_path_m[static_cast<size_t>(f)] = sum / static_cast<double>(2 * h + 1);
  }
  e.follow_lo_m = Vec3::Constant(1e30);
  e.follow_hi_m = Vec3::Constant(-1e30);
  for (const CharacterTrack& t : tracks)
    for (size_t f = 0; f < frames; ++f) {
      const Vec3 up = t.up.empty() ? Vec3::UnitY() : t.up[f];
      const Vec3 feet = t.feet_m[f] - e.follow_path_m[f];
      add_disc(feet, up, kBodyRadiusM, e.follow_lo_m, e.follow_hi_m);
      add_disc(feet + t.height_m * up, up, kBodyRadiusM, e.follow_lo_m, e.follow_hi_m);
    }
}

}  // namespace

CrowdExtent crowd_extent(const std::vector<CharacterTrack>& tracks, double fps) {
  if (tracks.empty() || tracks.front().feet_m.empty())
    throw InputError("viewpoint: the crowd has no frames to frame");
  const size_t frames = tracks.front().feet_m.size();
  CrowdExtent e;
  e.fps = fps;
  e.lo_m = Vec3::Constant(1e30);
  e.hi_m = Vec3::Constant(-1e30);
  Vec3 forward_sum = Vec3::Zero();
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const CharacterTrack& t : tracks) {
    if (t.feet_m.size() != frames || t.forward.size() != frames || (!t.up.empty() && t.up.size() != frames))
      throw InputError("crowd extent: every character needs the same number of frames");
    for (size_t f = 0; f < frames; ++f) {
      const Vec3 up = t.up.empty() ? Vec3::UnitY() : t.up[f];
      add_disc(t.feet_m[f], up, kBodyRadiusM, e.lo_m, e.hi_m);
      add_disc(t.feet_m[f] + t.height_m * up, up, kBodyRadiusM, e.lo_m, e.hi_m);
      forward_sum += horizontal(t.forward[f]);
      const Vec3 d = t.feet_m[f] - t.feet_m.front();
      const Eigen::Vector2d d2(d.x(), d.z());
      scatter += d2 * d2.transpose();
    }
  }
  if (forward_sum.norm() / static_cast<double>(frames * tracks.size()) >= 0.25)
    e.front = forward_sum.normalized();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  if (eig.info() == Eigen::Success && eig.eigenvalues()(1) > 1e-9) {
    const Eigen::Vector2d a = eig.eigenvectors().col(1);
    e.walk_axis = Vec3(a.x(), 0.0, a.y()).normalized();
  }
  add_follow_path(tracks, e);
  e.focal_feet_m = tracks.front().feet_m;
  const Vec3 focal_forward = horizontal(tracks.front().forward.front());
  if (focal_forward.norm() > 1e-6) e.focal_forward = focal_forward.normalized();
  return e;
}

std::vector<CharacterTrack> character_tracks(const CrowdTrajectories& trajectories,
                                             const std::vector<double>& heights_m) {
  check_heights(trajectories.agents.size(), heights_m);
  std::vector<CharacterTrack> tracks(trajectories.agents.size());
  for (size_t a = 0; a < tracks.size(); ++a) {
    const AgentTrajectory& agent = trajectories.agents[a];
    CharacterTrack& t = tracks[a];
    t.height_m = heights_m[a];
    for (size_t f = 0; f < agent.position_m.size(); ++f) {
      t.feet_m.emplace_back(agent.position_m[f].x(), 0.0, agent.position_m[f].y());
      const double h = f < agent.heading_rad.size() ? agent.heading_rad[f] : 0.0;
      t.forward.emplace_back(std::sin(h), 0.0, std::cos(h));  // 0 faces +Z, pi/2 faces +X
    }
  }
  return tracks;
}

std::vector<CharacterTrack> character_tracks(const SurfaceTrajectories& surface,
                                             const std::vector<double>& heights_m) {
  check_heights(surface.agents.size(), heights_m);
  std::vector<CharacterTrack> tracks(surface.agents.size());
  for (size_t a = 0; a < tracks.size(); ++a) {
    tracks[a].feet_m = surface.agents[a].feet_m;
    tracks[a].up = surface.agents[a].up;
    tracks[a].forward = surface.agents[a].forward;
    tracks[a].height_m = heights_m[a];
  }
  return tracks;
}

std::vector<CharacterTrack> character_tracks(const CrowdAnimation& crowd) {
  std::vector<CharacterTrack> tracks;
  for (const CharacterAnimation& c : crowd.characters) {
    if (c.frames.empty()) continue;
    CharacterTrack t;
    t.height_m = c.shape.params.height_m;
    for (const Pose& p : c.frames) {
      t.feet_m.push_back(p.root_position_m - Vec3(0.0, c.shape.pelvis_height_m(), 0.0));
      t.forward.push_back(p.local_rotations[kPelvis] * Vec3::UnitZ());
    }
    tracks.push_back(std::move(t));
  }
  return tracks;
}

std::vector<double> body_heights_m(const CrowdAnimation& crowd) {
  std::vector<double> heights;
  for (const CharacterAnimation& c : crowd.characters) heights.push_back(c.shape.params.height_m);
  return heights;
}

}  // namespace crowdlab::stimuli
