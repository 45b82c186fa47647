// ORCA line-segment obstacles (van den Berg et al. 2011, Sec. 5.1): the half-plane on analytic
// cases, walls never crossed, collision-free passage through a doorway and along a corridor.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "framework/crowd/orca_model.hpp"
#include "framework/crowd/orca_obstacle_line.hpp"
#include "tests/crowd/crowd_test_helpers.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_orca_obstacles {

using namespace crowdlab;

namespace {

/// True when v violates the half-plane (v on the right of the directed line).
bool violates(const orca::Line& L, double vx, double vy) {
  return orca::det(L.dx, L.dy, L.px - vx, L.py - vy) > 1e-12;
}

/// Does any point of the motion p(t) = p + v t, t in [0, tau], come closer than r to segment [a, b]?
bool collides_within(const Vec2& p, const Vec2& v, double r, const Vec2& a, const Vec2& b, double tau) {
  for (int k = 0; k <= 4000; ++k) {
    const double t = tau * k / 4000.0;
    const Vec2 q = p + t * v;
    const Vec2 ab = b - a;
    const double s = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    if ((q - (a + s * ab)).norm() < r - 1e-9) return true;
  }
  return false;
}

/// Segment [p, q] crosses segment [a, b] (proper intersection).
bool crosses(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b) {
  auto side = [](const Vec2& o, const Vec2& u, const Vec2& x) {
    return (u.x() - o.x()) * (x.y() - o.y()) - (u.y() - o.y()) * (x.x() - o.x());
  };
  return side(a, b, p) * side(a, b, q) < 0.0 && side(p, q, a) * side(p, q, b) < 0.0;
}

double distance_to_segment(const Vec2& q, const ObstacleSegment& s) {
  const Vec2 ab = s.b - s.a;
  const double t = std::clamp((q - s.a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (q - (s.a + t * ab)).norm();
}

}  // namespace

TEST_CASE("orca obstacles: the wall half-plane is the cut-off line (d - r) / tau",
          "[crowd][orca][obstacle]") {
  // Agent at the origin, wall y = 2 from x = -5 to 5, heading straight at it.
  const double r = 0.25, tau = 2.0;
  orca::ObstacleAgent agent{0.0, 0.0, 0.0, 1.5, r, 1.5};
  orca::Line L;
  REQUIRE(orca::obstacle_line(-5.0, 2.0, 5.0, 2.0, agent, 1.0 / tau, 0.1, nullptr, 0, L));
  // Permitted: v.y <= (2 - r) / tau everywhere along the line.
  const double limit = (2.0 - r) / tau;
  for (double vx : {-1.0, 0.0, 0.7}) {
    CHECK_FALSE(violates(L, vx, limit - 1e-6));
    CHECK(violates(L, vx, limit + 1e-6));
  }
  // Both orientations of the segment give the same half-plane (a wall blocks on both sides).
  orca::Line R;
  REQUIRE(orca::obstacle_line(5.0, 2.0, -5.0, 2.0, agent, 1.0 / tau, 0.1, nullptr, 0, R));
  CHECK(R.dx == Approx(L.dx));
  CHECK(R.dy == Approx(L.dy));
  CHECK(orca::det(L.dx, L.dy, R.px - L.px, R.py - L.py) == Approx(0.0).margin(1e-12));
}

TEST_CASE("orca obstacles: half-planes exclude every colliding velocity, admit passing the end",
          "[crowd][orca][obstacle]") {
  // For many agent positions, segments and current velocities: every velocity on the permitted
  // side is collision-free for tau (the half-plane is a subset of the complement of VO_tau).
  const double r = 0.25, tau = 2.0;
  const Vec2 a(-1.0, 1.0), b(1.5, 1.4);
  int lines = 0, admitted_past_end = 0;
  for (double px : {-3.0, -1.2, 0.0, 1.0, 2.4}) {
    for (double py : {-1.5, -0.2, 0.6, 2.5, 3.5}) {
      const Vec2 p(px, py);
      if (distance_to_segment(p, {a, b}) <= r + 0.01) continue;
      for (double ang = 0.0; ang < 6.28; ang += 0.7) {
        orca::ObstacleAgent agent{px, py, 1.2 * std::cos(ang), 1.2 * std::sin(ang), r, 1.5};
        orca::Line L;
        if (!orca::obstacle_line(a.x(), a.y(), b.x(), b.y(), agent, 1.0 / tau, 0.1, nullptr, 0, L)) continue;
        ++lines;
        for (double vx = -1.5; vx <= 1.5; vx += 0.25) {
          for (double vy = -1.5; vy <= 1.5; vy += 0.25) {
            if (violates(L, vx, vy)) continue;
            INFO("p " << px << "," << py << " v " << vx << "," << vy);
            CHECK_FALSE(collides_within(p, Vec2(vx, vy), r, a, b, tau));
          }
        }
        // The exact obstacle admits some velocity aimed past an end point that the closest-point
        // half-plane (the conservative session-1 rule) would forbid.
        const Vec2 aim = (b + Vec2(0.6, 0.0) - p).normalized();
        const Vec2 c = a + std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0) * (b - a);
        const Vec2 n = (p - c).normalized();
        const double d = (p - c).norm();
        const Vec2 v = 1.0 * aim;
        if (!violates(L, v.x(), v.y()) && v.dot(n) < -(d - r) / tau) ++admitted_past_end;
      }
    }
  }
  CHECK(lines > 50);
  CHECK(admitted_past_end > 0);
}

TEST_CASE("orca obstacles: agents pass a doorway without crossing a wall or overlapping",
          "[crowd][orca][obstacle]") {
  // A wall along x = 0 with a 1.4 m doorway at |y| < 0.7; 12 agents left of it head for goals on
  // the right (mirror positions).
  const std::vector<ObstacleSegment> walls = {{Vec2(0.0, -12.0), Vec2(0.0, -0.7)},
                                              {Vec2(0.0, 0.7), Vec2(0.0, 12.0)}};
  std::vector<AgentInit> agents;
  for (int row = 0; row < 4; ++row) {
    for (int col = 0; col < 3; ++col) {
      AgentInit g;
      g.position = {-2.0 - 1.0 * col, -1.5 + 1.0 * row};
      g.goal = {2.0 + 1.0 * col, -1.5 + 1.0 * row};
      g.radius_m = 0.25;
      g.preferred_speed_mps = 1.3;
      g.max_speed_mps = 1.5;
      agents.push_back(g);
    }
  }
  OrcaParams params;
  params.resolve_overlaps = GENERATE(false, true);
  INFO("overlap-free mode " << params.resolve_overlaps);
  CrowdSimulation sim(std::make_shared<OrcaModel>(params), agents, walls, 0.1);
  sim.set_preferred_velocity_jitter(0.01, 3);
  double worst_overlap = -1.0, closest_wall = 1e9;
  std::vector<Vec2> before(sim.size());
  // ORCA is local: each agent first heads for the doorway, then for its goal once through.
  for (std::size_t i = 0; i < sim.size(); ++i) sim.set_goal(i, Vec2(0.0, agents[i].position.y() * 0.05));
  bool arrived = false;
  for (int s = 0; s < 1200 && !arrived; ++s) {
    for (std::size_t i = 0; i < sim.size(); ++i) {
      before[i] = sim.position(i);
      if (sim.position(i).x() > -0.3) sim.set_goal(i, agents[i].goal);
    }
    sim.step();
    arrived = true;
    for (std::size_t i = 0; i < sim.size(); ++i) {
      for (const ObstacleSegment& w : walls) {
        CHECK_FALSE(crosses(before[i], sim.position(i), w.a, w.b));
        closest_wall = std::min(closest_wall, distance_to_segment(sim.position(i), w));
      }
      arrived = arrived && (sim.position(i) - agents[i].goal).norm() < 0.1;
    }
    worst_overlap = std::max(worst_overlap, test::deepest_overlap(sim));
  }
  INFO("closest wall " << closest_wall << " deepest overlap " << worst_overlap << " t " << sim.time_s());
  CHECK(arrived);
  CHECK(closest_wall >= 0.25 - 1e-3);
  CHECK(worst_overlap <= 1e-3);
}

TEST_CASE("orca obstacles: a dense corridor flow stays inside its walls", "[crowd][orca][obstacle]") {
  // 2 m wide corridor, 40 agents walking +y, some started against the walls' ends.
  const std::vector<ObstacleSegment> walls = {{Vec2(-1.0, -6.0), Vec2(-1.0, 30.0)},
                                              {Vec2(1.0, -6.0), Vec2(1.0, 30.0)}};
  std::vector<AgentInit> agents;
  for (int k = 0; k < 40; ++k) {
    AgentInit g;
    g.position = {-0.7 + 0.467 * (k % 4), -5.0 + 0.55 * (k / 4)};
    g.goal = {(k % 2 ? 0.5 : -0.5), 40.0};
    g.radius_m = 0.2;
    g.preferred_speed_mps = 1.2 + 0.02 * (k % 5);
    g.max_speed_mps = 1.5;
    agents.push_back(g);
  }
  CrowdSimulation sim(std::make_shared<OrcaModel>(OrcaParams{}), agents, walls, 0.1);
  double closest_wall = 1e9, worst_overlap = -1.0;
  for (int s = 0; s < 150; ++s) {
    sim.step();
    for (std::size_t i = 0; i < sim.size(); ++i) {
      CHECK(std::fabs(sim.position(i).x()) < 1.0);
      for (const ObstacleSegment& w : walls)
        closest_wall = std::min(closest_wall, distance_to_segment(sim.position(i), w));
    }
    worst_overlap = std::max(worst_overlap, test::deepest_overlap(sim));
  }
  CHECK(closest_wall >= 0.2 - 1e-3);
  CHECK(worst_overlap <= 1e-3);
  for (std::size_t i = 0; i < sim.size(); ++i) CHECK(sim.position(i).y() > 5.0);
}

}  // namespace test_orca_obstacles
