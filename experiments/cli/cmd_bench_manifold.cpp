// `crowdlab bench manifold`: median ms per step of a surface crowd (seed 002 §4): wall-clock time, and
// the thread CPU time of the calling thread (the whole step with --threads 1; on a shared machine the
// wall time also counts the time other processes hold the core).
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "experiments/cli/bench_group.hpp"
#include "experiments/cli/command_table.hpp"
#include "experiments/cli/timing.hpp"
#include "framework/core/progress.hpp"
#include "framework/surface/surface_crowd.hpp"
#include "framework/surface/surface_scenes.hpp"

namespace crowdlab::cli::cmd_bench_manifold {
namespace {

struct Options {
  int agents = 1000;
  std::string mesh = "blobby";
  std::string model = "social";
  std::string relevant = "visibility";
  bool face_up = false;
  int steps = 200;
  int threads = 1;
  bool json = false;
};

void run(const Options& o) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(o.threads));
  // The blob grows with the crowd (about 4 m^2 of surface per agent, radius sqrt(N / pi) m) so the
  // density, and with it the work per agent, stays fixed as N grows; its resolution stays >= 100k triangles.
  auto mesh = std::make_shared<const SurfaceMesh>(
      o.mesh == "blobby" ? make_blobby_surface(100000, std::max(8.0, std::sqrt(o.agents / M_PI)))
                         : make_surface_scene(o.mesh));
  SurfaceCrowdParams params;
  params.avoidance = parse_surface_avoidance(o.model, "--model");
  params.relevant = parse_relevant_mode(o.relevant, "--relevant");
  params.smooth_body_up = !o.face_up;
  const SurfaceCrowdModel model = make_surface_crowd_model(mesh, params, 8, 1);
  SurfaceCrowdState state = spawn_surface_agents(model, o.agents, 1);
  for (int k = 0; k < 10; ++k) step_surface_crowd(model, state);  // warm-up: caches, first allocation
  std::vector<double> ms, cpu_ms;                                 // wall-clock and thread CPU time per step
  {
    Progress progress("bench manifold", static_cast<size_t>(o.steps));
    for (int k = 0; k < o.steps; ++k) {
      double cpu = 0;
      ms.push_back(time_ms([&] { cpu = thread_cpu_ms([&] { step_surface_crowd(model, state); }); }));
      cpu_ms.push_back(cpu);
      progress.advance();
    }
  }
  const double med = median_of(ms);
  if (o.json) {
    nlohmann::json j{{"ms_per_step_median", med},
                     {"ms_per_step_mean", mean_of(ms)},
                     {"steps_per_s", 1000.0 / med},
                     {"cpu_ms_per_step_median", median_of(cpu_ms)},
                     {"cpu_steps_per_s", 1000.0 / median_of(cpu_ms)},
                     {"agents", o.agents},
                     {"triangles", mesh->face_count()},
                     {"mesh", o.mesh},
                     {"model", o.model},
                     {"relevant", o.relevant},
                     {"body_up", o.face_up ? "face" : "smooth"},
                     {"threads", o.threads},
                     {"steps", o.steps}};
    std::printf("%s\n", j.dump().c_str());
  } else {
    std::printf("manifold crowd (%s, %s Relevant): %d agents on '%s' (%d triangles), %d thread(s)\n",
                o.model.c_str(), o.relevant.c_str(), o.agents, o.mesh.c_str(), mesh->face_count(), o.threads);
    std::printf("  median %.3f ms/step (%.0f steps/s), mean %.3f ms over %d steps\n", med, 1000.0 / med,
                mean_of(ms), o.steps);
    std::printf(
        "  thread CPU time: median %.3f ms/step (%.0f steps/s; wall time also counts other processes)\n",
        median_of(cpu_ms), 1000.0 / median_of(cpu_ms));
  }
}

}  // namespace

void add_bench_manifold_command(Command& root) {
  auto opts = std::make_shared<Options>();
  auto* cmd = bench_group(root)->add_subcommand("manifold", "Surface crowd: median ms per simulation step");
  cmd->add_option("--agents", opts->agents, "Number of agents")
      ->check(check::range(1, 1000000))
      ->capture_default_str();
  cmd->add_option(
         "--mesh", opts->mesh,
         "Scene name (building, floor_ceiling, floor_wall, mobius, torus, tree, blobby) or .obj/.gltf/.glb")
      ->capture_default_str();
  cmd->add_option("--model", opts->model, "Obstacle avoidance in the tangent plane")
      ->check(check::is_member({"social", "orca"}))
      ->capture_default_str();
  cmd->add_option("--relevant", opts->relevant, "Relevant function (relevance.hpp)")
      ->check(check::is_member({"visibility", "visibility_mesh", "euclidean", "surface"}))
      ->capture_default_str();
  cmd->add_flag("--face-up", opts->face_up, "Bodies along each face's normal instead of the smoothed up");
  cmd->add_option("--steps", opts->steps, "Timed steps")
      ->check(check::range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--threads", opts->threads, "Worker threads")
      ->check(check::range(1, 256))
      ->capture_default_str();
  cmd->add_flag("--json", opts->json, "Print one JSON object");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace crowdlab::cli::cmd_bench_manifold
