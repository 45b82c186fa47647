// `crowdlab experiment manifold-compare`: seed 002's comparison of Relevant functions (visibility-aware
// vs Euclidean vs surface distance) on the floor-ceiling slab (Fig. 5), the two-storey building and
// the floor-wall corner, for both ObstacleAvoidance models (social forces, ORCA), reporting collision
// percentages and false positives/negatives, and the median collision rate of the visibility-aware
// Relevant per model beside seed 002's 0.05 % (social forces) and 0.009 % (RVO).
//
// Collision percentage (surface_measures.hpp): 100 x agent-frames whose three-sphere body overlaps a
// reachable agent's / agent-frames. Seed 002 §4 reports "collision percentages" and their "median
// collision rates" (.05 % and .009 %, crowds of 1,000 agents) without a formula, a denominator, a time
// step or a density; per agent-frame is our reading, the median is taken over every scene and run of a
// Relevant mode. The visibility_mesh Relevant (our refinement, relevance.hpp) is measured beside the
// seed's disk test; --face-up measures bodies that snap to each face normal (the pre-fix behaviour).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "experiments/cli/command_estimates.hpp"
#include "experiments/cli/command_table.hpp"
#include "experiments/cli/experiment_group.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "experiments/cli/timing.hpp"
#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "framework/core/seed.hpp"
#include "framework/surface/surface_measures.hpp"
#include "framework/surface/surface_scenes.hpp"

namespace crowdlab::cli::cmd_experiment_manifold {
namespace {

struct Options {
  std::string out = "manifold-compare";
  int agents = 200;
  int steps = 300;
  int runs = 3;
  std::uint64_t seed = 2024;
  bool face_up = false;
};

void run(const Options& o) {
  namespace fs = std::filesystem;
  const std::vector<std::string> scenes = {"floor_ceiling", "building", "floor_wall"};
  const std::vector<RelevantMode> modes = {RelevantMode::kVisibility, RelevantMode::kVisibilityMesh,
                                           RelevantMode::kEuclidean, RelevantMode::kSurface};
  const std::vector<SurfaceAvoidance> models = {SurfaceAvoidance::kSocialForces, SurfaceAvoidance::kOrca};
  const size_t all_runs = scenes.size() * models.size() * modes.size() * static_cast<size_t>(o.runs);
  announce_estimate("manifold-compare",
                    manifold_compare_estimate(static_cast<double>(all_runs), o.agents, o.steps));
  fs::create_directories(o.out);
  std::ofstream csv(fs::path(o.out) / "manifold_compare.csv");
  csv << csv_line({"scene", "model", "relevant", "run", "agents", "steps", "collision_percent",
                   "false_positives_per_agent_step", "false_negatives_per_agent_step"});
  // Counted in steps, not runs: one run of --agents 100000 takes minutes (issue 33).
  Progress progress("manifold-compare", all_runs * static_cast<size_t>(o.steps));
  std::printf("%-14s %-7s %-15s %14s %12s %12s\n", "scene", "model", "relevant", "collisions %",
              "FP/agent-step", "FN/agent-step");
  // (relevant mode, model) -> collision % of every run
  std::map<std::pair<std::string, std::string>, std::vector<double>> rates;
  for (const auto& scene : scenes) {
    auto mesh = std::make_shared<const SurfaceMesh>(make_surface_scene(scene));
    const TriangleBvh bvh(*mesh);
    for (SurfaceAvoidance model_kind : models)
      for (RelevantMode mode : modes) {
        std::vector<double> coll, fp, fn;
        for (int r = 0; r < o.runs; ++r) {
          SurfaceCrowdParams p;
          p.relevant = mode;
          p.avoidance = model_kind;
          p.smooth_body_up = !o.face_up;
          const std::uint64_t seed = derive_seed(o.seed, scene + "/" + std::to_string(r));
          const SurfaceCrowdModel model = make_surface_crowd_model(mesh, p, 6, seed);
          SurfaceCrowdState state = spawn_surface_agents(model, o.agents, seed);
          SurfaceCrowdMeasures m;
          for (int k = 0; k < o.steps; ++k) {
            step_surface_crowd(model, state);
            accumulate_surface_measures(model, state, bvh, m);
            progress.advance();
          }
          const double per = 1.0 / static_cast<double>(m.agent_frames);
          coll.push_back(m.collision_percent());
          fp.push_back(static_cast<double>(m.false_positives) * per);
          fn.push_back(static_cast<double>(m.false_negatives) * per);
          rates[{relevant_mode_name(mode), surface_avoidance_name(model_kind)}].push_back(coll.back());
          csv << csv_line({scene, surface_avoidance_name(model_kind), relevant_mode_name(mode),
                           std::to_string(r), std::to_string(o.agents), std::to_string(o.steps),
                           csv_number(coll.back()), csv_number(fp.back()), csv_number(fn.back())});
        }
        std::printf("%-14s %-7s %-15s %14.4f %12.4f %12.4f   (medians of %d runs)\n", scene.c_str(),
                    surface_avoidance_name(model_kind), relevant_mode_name(mode), median_of(coll),
                    median_of(fp), median_of(fn), o.runs);
      }
  }
  for (RelevantMode mode : modes)
    std::printf(
        "median collision rate, %s Relevant, all scenes and runs: social forces %.4f %%, ORCA %.4f %%\n",
        relevant_mode_name(mode), median_of(rates[{relevant_mode_name(mode), "social"}]),
        median_of(rates[{relevant_mode_name(mode), "orca"}]));
  std::printf("seed 002 reports median collision rates of 0.05 %% (social forces) and 0.009 %% (RVO).\n");
  std::printf("wrote %s\n", (fs::path(o.out) / "manifold_compare.csv").string().c_str());
}

}  // namespace

void add_experiment_manifold_command(Command& root) {
  auto opts = std::make_shared<Options>();
  auto* cmd = experiment_group(root)->add_subcommand(
      "manifold-compare",
      "Seed 002: Relevant functions compared on floor-ceiling, building and floor-wall scenes");
  cmd->add_option("--out", opts->out, "Output folder")->capture_default_str();
  cmd->add_option("--agents", opts->agents, "Agents per run")
      ->check(check::range(2, 100000))
      ->capture_default_str();
  cmd->add_option("--steps", opts->steps, "Steps per run")
      ->check(check::range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--runs", opts->runs, "Runs (seeds) per scene and mode")
      ->check(check::range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--seed", opts->seed, "Seed")->capture_default_str();
  cmd->add_flag("--face-up", opts->face_up,
                "Bodies stand along each face's normal (snapping at creases) instead of the smoothed up");
  cmd->callback([opts] {
    const OutputFolderLock lock(opts->out);  // one process per folder (output_folder_lock.hpp)
    run(*opts);
  });
}

}  // namespace crowdlab::cli::cmd_experiment_manifold
