#include "framework/surface/surface_crowd.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <unordered_map>

#include "framework/core/bucket_sort.hpp"
#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"
#include "framework/surface/geodesic_distance.hpp"
#include "framework/surface/smooth_surface_up.hpp"
#include "framework/surface/surface_avoidance.hpp"
#include "framework/surface/tangent_orca.hpp"

namespace crowdlab {
namespace {

void check(bool ok, const std::string& name, const std::string& range) {
  if (!ok) throw InputError(SourceLocation{"", 0, 0, name}, "must be " + range);
}

int random_face(const std::vector<double>& cumulative_area, Rng& rng) {
  const double r = uniform01(rng) * cumulative_area.back();
  return static_cast<int>(std::upper_bound(cumulative_area.begin(), cumulative_area.end(), r) -
                          cumulative_area.begin());
}

Vec3 random_point_in_face(const SurfaceMesh& mesh, int f, Rng& rng) {
  double u = uniform01(rng), v = uniform01(rng);
  if (u + v > 1) {
    u = 1 - u;
    v = 1 - v;
  }
  return mesh.corner(f, 0) + u * (mesh.corner(f, 1) - mesh.corner(f, 0)) +
         v * (mesh.corner(f, 2) - mesh.corner(f, 0));
}

std::vector<double> cumulative_areas(const SurfaceMesh& mesh) {
  std::vector<double> c(static_cast<size_t>(mesh.face_count()));
  double acc = 0;
  for (int f = 0; f < mesh.face_count(); ++f) {
    acc += 0.5 * (mesh.corner(f, 1) - mesh.corner(f, 0)).cross(mesh.corner(f, 2) - mesh.corner(f, 0)).norm();
    c[static_cast<size_t>(f)] = acc;
  }
  return c;
}

std::uint32_t cell_hash(const Eigen::Vector3i& c) {
  return static_cast<std::uint32_t>(c.x() * 73856093) ^ static_cast<std::uint32_t>(c.y() * 19349663) ^
         static_cast<std::uint32_t>(c.z() * 83492791);
}

Eigen::Vector3i cell_of(const Vec3& p, double cell) {
  return Eigen::Vector3i(static_cast<int>(std::floor(p.x() / cell)),
                         static_cast<int>(std::floor(p.y() / cell)),
                         static_cast<int>(std::floor(p.z() / cell)));
}

}  // namespace

SurfaceAvoidance parse_surface_avoidance(const std::string& text, const std::string& key) {
  if (text == "social") return SurfaceAvoidance::kSocialForces;
  if (text == "orca") return SurfaceAvoidance::kOrca;
  throw InputError(SourceLocation{"", 0, 0, key}, "must be 'social' or 'orca', not '" + text + "'");
}

const char* surface_avoidance_name(SurfaceAvoidance a) {
  return a == SurfaceAvoidance::kOrca ? "orca" : "social";
}

Vec3 body_up(const SurfaceCrowdModel& model, const SurfacePoint& p) {
  return model.params.smooth_body_up ? smooth_surface_up(*model.mesh, p) : p.up(*model.mesh);
}

Vec3 body_center(const SurfaceCrowdModel& model, const SurfacePoint& p) {
  return p.position_m + body_up(model, p) * (model.params.body.height_m / 2);
}

SurfaceCrowdModel make_surface_crowd_model(std::shared_ptr<const SurfaceMesh> mesh,
                                           const SurfaceCrowdParams& p, int goal_count, std::uint64_t seed) {
  check(p.neighbor_distance_m > 0 && p.neighbor_distance_m <= 10, "neighbor_distance_m", "in (0, 10] m");
  check(p.max_neighbors >= 1 && p.max_neighbors <= 32, "max_neighbors", "in [1, 32]");
  check(p.preferred_speed_mps > 0 && p.preferred_speed_mps <= 3, "preferred_speed_mps", "in (0, 3] m/s");
  check(p.max_speed_mps >= p.preferred_speed_mps, "max_speed_mps", ">= preferred_speed_mps");
  check(p.dt_s > 0 && p.dt_s <= 0.2, "dt_s", "in (0, 0.2] s");
  check(p.body.sphere_radius_m > 0 && 2 * p.body.sphere_radius_m <= p.body.height_m, "sphere_radius_m",
        "positive and at most half the agent height");
  check(p.body.sphere_spacing_m >= 0 && p.body.sphere_spacing_m <= p.body.height_m, "sphere_spacing_m",
        "in [0, agent height] (0 = span feet to head)");
  check(p.orca_margin_m >= 0 && p.orca_margin_m <= 1, "orca_margin_m", "in [0, 1] m");
  check(p.orca_time_horizon_s > 0 && p.orca_time_horizon_s <= 10, "orca_time_horizon_s", "in (0, 10] s");
  check(goal_count >= 1, "goal_count", ">= 1");
  SurfaceCrowdModel m;
  m.mesh = std::move(mesh);
  m.params = p;
  if (p.relevant == RelevantMode::kVisibilityMesh) m.bvh = std::make_shared<const TriangleBvh>(*m.mesh);
  Rng rng(derive_seed(seed, "surface-goals"));
  const auto cumulative = cumulative_areas(*m.mesh);
  for (int g = 0; g < goal_count; ++g) {
    const int f = random_face(cumulative, rng);
    m.goal_vertices.push_back(m.mesh->triangles[static_cast<size_t>(f)][0]);
    m.goal_fields.push_back(geodesic_distance_field(*m.mesh, {m.goal_vertices.back()}));
  }
  return m;
}

SurfaceCrowdState spawn_surface_agents(const SurfaceCrowdModel& model, int n, std::uint64_t seed) {
  if (n < 1) throw InputError(SourceLocation{"", 0, 0, "agents"}, "must be >= 1");
  const SurfaceMesh& mesh = *model.mesh;
  Rng rng(derive_seed(seed, "surface-spawn"));
  const auto cumulative = cumulative_areas(mesh);
  SurfaceCrowdState s;
  const double min_gap = 2.0 * model.params.body.sphere_radius_m;
  // Grid cell: two stacks within 5 cm of touching have body centres at most height + 5 cm apart
  // (spheres at the ends of each stack), so the 27 cells around a centre hold every possible contact
  // (a smaller cell missed stacks on perpendicular surfaces: heads touching, centres 1.3 m apart).
  const double cell = model.params.body.height_m + 0.05;
  std::unordered_multimap<std::uint32_t, int> occupied;
  long attempts = 0;
  while (static_cast<int>(s.points.size()) < n) {
    if (++attempts > 200L * n + 10000)
      throw InputError(SourceLocation{"", 0, 0, "agents"}, std::to_string(n) +
                                                               " agents do not fit on this surface at " +
                                                               std::to_string(min_gap) + " m spacing");
    SurfacePoint p;
    p.face = random_face(cumulative, rng);
    p.position_m = random_point_in_face(mesh, p.face, rng);
    const Vec3 c = body_center(model, p);
    const Eigen::Vector3i key = cell_of(c, cell);
    bool free = true;
    for (int dx = -1; dx <= 1 && free; ++dx)
      for (int dy = -1; dy <= 1 && free; ++dy)
        for (int dz = -1; dz <= 1 && free; ++dz) {
          auto range = occupied.equal_range(cell_hash(key + Eigen::Vector3i(dx, dy, dz)));
          for (auto it = range.first; it != range.second && free; ++it) {
            const SurfacePoint& q = s.points[static_cast<size_t>(it->second)];
            if (stacked_clearance(p.position_m, body_up(model, p), q.position_m, body_up(model, q),
                                  model.params.body) < 0.05)
              free = false;
          }
        }
    if (!free) continue;
    occupied.emplace(cell_hash(key), static_cast<int>(s.points.size()));
    s.points.push_back(p);
    s.velocity_mps.push_back(Vec3::Zero());
    s.goal.push_back(static_cast<int>(uniform_index(rng, model.goal_fields.size())));
  }
  return s;
}

namespace {

/// Stage 1: bins body centres (counting sort into a power-of-two hash table of cells as large as the
/// neighbour distance) and copies the agents in slot order. Returns the table's index mask.
std::uint32_t bin_agents(const SurfaceCrowdModel& model, SurfaceCrowdState& s) {
  const SurfaceCrowdParams& p = model.params;
  const size_t N = s.points.size();
  size_t slots = 1;
  while (slots < 2 * N) slots <<= 1;
  const std::uint32_t mask = static_cast<std::uint32_t>(slots - 1);
  s.center_m.resize(N);
  s.up.resize(N);
  for (size_t i = 0; i < N; ++i) {
    s.up[i] = body_up(model, s.points[i]);
    s.center_m[i] = s.points[i].position_m + s.up[i] * (p.body.height_m / 2);
  }
  s.cell_slot.resize(N);
  s.slot_start.resize(slots + 1);
  s.slot_agents.resize(N);
  for (size_t i = 0; i < N; ++i)
    s.cell_slot[i] = cell_hash(cell_of(s.center_m[i], p.neighbor_distance_m)) & mask;
  bucket_sort(s.cell_slot.data(), N, s.slot_start,
              [&](size_t i, std::uint32_t slot) { s.slot_agents[slot] = static_cast<std::uint32_t>(i); });
  // Copies in slot order, so that scanning a cell reads contiguous memory (at 10,000 agents the
  // scattered reads of the agent arrays, not the arithmetic, dominated the step).
  s.sorted.resize(N);
  for (size_t k = 0; k < N; ++k) {
    const size_t j = s.slot_agents[k];
    s.sorted[k] =
        SurfaceCrowdState::SortedAgent{s.center_m[j], s.points[j].position_m, s.up[j], static_cast<int>(j)};
  }
  if (p.relevant == RelevantMode::kSurface) {
    s.face_agents.assign(static_cast<size_t>(model.mesh->face_count()), {});
    for (size_t i = 0; i < N; ++i)
      s.face_agents[static_cast<size_t>(s.points[i].face)].push_back(static_cast<int>(i));
  }
  return mask;
}

/// Per-task scratch of the relevant stage (reused across agents: no allocation once grown).
struct RelevantScratch {
  std::vector<std::pair<double, int>> candidates;  ///< (clearance m, agent)
  std::vector<int> reached_faces;
};

/// kSurface: the agents on the faces within the neighbour distance of a's face, by a bounded Dijkstra
/// over the face graph (centroid distances).
void surface_candidates(const SurfaceCrowdModel& model, const SurfaceCrowdState& s, size_t i,
                        RelevantScratch& scratch) {
  const SurfaceMesh& mesh = *model.mesh;
  const SurfaceCrowdParams& p = model.params;
  const SurfacePoint& a = s.points[i];
  std::vector<int>& reached_faces = scratch.reached_faces;
  reached_faces.clear();
  std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, std::greater<>> q;
  q.emplace(0.0, a.face);
  while (!q.empty()) {
    auto [d, f] = q.top();
    q.pop();
    if (std::find(reached_faces.begin(), reached_faces.end(), f) != reached_faces.end()) continue;
    reached_faces.push_back(f);
    for (int e = 0; e < 3; ++e) {
      const int g = mesh.neighbors[static_cast<size_t>(f)][static_cast<size_t>(e)];
      if (g < 0) continue;
      const double nd = d + (mesh.centroid(g) - mesh.centroid(f)).norm();
      if (nd <= p.neighbor_distance_m) q.emplace(nd, g);
    }
  }
  for (int f : reached_faces)
    for (int j : s.face_agents[static_cast<size_t>(f)]) {
      if (static_cast<size_t>(j) == i) continue;
      const size_t js = static_cast<size_t>(j);
      scratch.candidates.emplace_back(
          stacked_clearance(a.position_m, s.up[i], s.points[js].position_m, s.up[js], p.body), j);
    }
}

/// The other modes: the agents of the 27 cells around a's body centre within the neighbour distance,
/// filtered by visibility for kVisibility and kVisibilityMesh.
void grid_candidates(const SurfaceCrowdModel& model, const SurfaceCrowdState& s, size_t i, std::uint32_t mask,
                     RelevantScratch& scratch) {
  const SurfaceCrowdParams& p = model.params;
  const SurfacePoint& a = s.points[i];
  const Vec3 up_a = s.up[i], center_a = s.center_m[i];
  const double radius2 = p.neighbor_distance_m * p.neighbor_distance_m;
  auto consider = [&](size_t k) {  // k: position in slot order
    const SurfaceCrowdState::SortedAgent& o = s.sorted[k];
    if (static_cast<size_t>(o.index) == i) return;
    const double d2 = (o.center_m - center_a).squaredNorm();
    if (d2 > radius2) return;
    // Seed 002 §3 gives each agent one normal, used both for the disk at its feet and for stacking
    // its spheres (o_up): here the body's up. (Disks in the face planes under tilted bodies were
    // measured too, docs/surfaces.md: fewer false negatives on the thin slab, more at the building's
    // convex ramp crests; the mesh test has neither.)
    if (p.relevant == RelevantMode::kVisibility &&
        !mutually_visible(a.position_m, up_a, o.feet_m, o.up, o.feet_m + o.up * p.body.height_m))
      return;
    if (p.relevant == RelevantMode::kVisibilityMesh &&
        !mutually_visible_near_feet(a.position_m, up_a, o.feet_m, o.feet_m + o.up * p.body.height_m,
                                    *model.bvh))
      return;
    scratch.candidates.emplace_back(stacked_clearance(a.position_m, up_a, o.feet_m, o.up, p.body), o.index);
  };
  const Eigen::Vector3i c = cell_of(center_a, p.neighbor_distance_m);
  std::uint32_t visited[27];
  int nv = 0;
  for (int dx = -1; dx <= 1; ++dx)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dz = -1; dz <= 1; ++dz) {
        const std::uint32_t slot = cell_hash(c + Eigen::Vector3i(dx, dy, dz)) & mask;
        if (std::find(visited, visited + nv, slot) != visited + nv) continue;
        visited[nv++] = slot;
        for (std::uint32_t k = s.slot_start[slot]; k < s.slot_start[slot + 1]; ++k) consider(k);
      }
}

/// Stage 2: agent i's relevant neighbours, the max_neighbors candidates of least body clearance, into
/// s.neighbors[i * K ..]. Returns how many were kept.
size_t find_relevant(const SurfaceCrowdModel& model, SurfaceCrowdState& s, size_t i, std::uint32_t mask,
                     RelevantScratch& scratch) {
  const size_t K = static_cast<size_t>(model.params.max_neighbors);
  scratch.candidates.clear();
  if (model.params.relevant == RelevantMode::kSurface)
    surface_candidates(model, s, i, scratch);
  else
    grid_candidates(model, s, i, mask, scratch);
  auto& candidates = scratch.candidates;
  const size_t keep = std::min(K, candidates.size());
  std::partial_sort(candidates.begin(), candidates.begin() + static_cast<long>(keep), candidates.end());
  s.neighbor_count[i] = static_cast<int>(keep);
  for (size_t k = 0; k < keep; ++k) s.neighbors[i * K + k] = candidates[k].second;
  return keep;
}

/// Stage 3: the goal direction from the geodesic field (a new goal once within goal_reached_m), the
/// avoidance's velocity in the tangent plane, clamped to max_speed_mps, into s.next_velocity/next_goal.
void steer(const SurfaceCrowdModel& model, SurfaceCrowdState& s, size_t i, size_t keep,
           const SurfaceAvoidanceModel& avoidance) {
  const SurfaceMesh& mesh = *model.mesh;
  const SurfaceCrowdParams& p = model.params;
  const SurfacePoint& a = s.points[i];
  int goal = s.goal[i];
  const auto& field = model.goal_fields[static_cast<size_t>(goal)];
  const double to_goal = interpolate_field(mesh, field, a.face, a.position_m);
  if (!(to_goal > p.goal_reached_m)) {
    Rng rng(derive_seed(static_cast<std::uint64_t>(s.step_index), "goal" + std::to_string(i)));
    goal = static_cast<int>(uniform_index(rng, model.goal_fields.size()));
  }
  Vec3 dir = descent_direction(mesh, model.goal_fields[static_cast<size_t>(goal)], a.face);
  const Vec3 v_pref = dir * p.preferred_speed_mps;
  Vec3 v = to_tangent(mesh, a.face, avoidance.velocity(model, s, i, keep, v_pref));
  const double speed = v.norm();
  if (speed > p.max_speed_mps) v *= p.max_speed_mps / speed;
  s.next_velocity[i] = v;
  s.next_goal[i] = goal;
}

/// Stage 4: every agent moves along the surface with its new velocity (independently; parallel-safe).
void move_agents(const SurfaceCrowdModel& model, SurfaceCrowdState& s) {
  const size_t N = s.points.size();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, N, 128), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t i = range.begin(); i != range.end(); ++i) {
      Vec3 v = s.next_velocity[i];
      move_on_surface(*model.mesh, s.points[i], v * model.params.dt_s, v);
      s.velocity_mps[i] = v;
      s.goal[i] = s.next_goal[i];
    }
  });
}

}  // namespace

void step_surface_crowd(const SurfaceCrowdModel& model, SurfaceCrowdState& s) {
  const size_t N = s.points.size();
  s.neighbors.resize(N * static_cast<size_t>(model.params.max_neighbors));
  s.neighbor_count.resize(N);
  s.next_velocity.resize(N);
  s.next_goal.resize(N);
  const std::uint32_t mask = bin_agents(model, s);
  const SurfaceAvoidanceModel& avoidance = surface_avoidance_model(model.params.avoidance);
  // Stages 2 + 3 per agent, from the old state only. Agents in slot order: neighbours in space are
  // processed together and share cached mesh and agent data. Each writes only its own slots, so the
  // order does not change any result.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, N, 64), [&](const tbb::blocked_range<size_t>& range) {
    RelevantScratch scratch;
    for (size_t r = range.begin(); r != range.end(); ++r) {
      const size_t i = s.slot_agents[r];
      const size_t keep = find_relevant(model, s, i, mask, scratch);
      steer(model, s, i, keep, avoidance);
    }
  });
  move_agents(model, s);
  ++s.step_index;
}

}  // namespace crowdlab
