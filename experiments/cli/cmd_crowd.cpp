// `crowdlab crowd SPEC.yaml --condition ID --csv out.csv`: one condition's 2D crowd trajectories
// (framework/crowd/generate_scenario.hpp; a manifold scenario writes its 3D surface trajectories,
// framework/core/surface_trajectories.hpp), plus optional measures, and `--collision-table` for the
// seed 001 Table 2 style collision counts over a spec's scenario x density x repetition cells.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "experiments/cli/command_table.hpp"
#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/progress.hpp"
#include "framework/core/trajectories.hpp"
#include "framework/crowd/collision_table.hpp"
#include "framework/crowd/count_spec_collisions.hpp"
#include "framework/crowd/disc_collision_events.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/crowd/interpersonal_distance_histogram.hpp"
#include "framework/crowd/pair_closest_approaches.hpp"
#include "framework/pipeline/provenance.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "framework/surface/generate_manifold_scenario.hpp"

namespace crowdlab::cli::cmd_crowd {
namespace {

struct Args {
  std::string spec, condition, csv, measures_dir, collision_table;
  double pair_distance_m = 2.0;
  bool list = false;
};

/// Creates the parent folder, then writes atomically with the CLI's one file writer.
void write_file(const std::filesystem::path& path, const std::string& text) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  write_file_atomic(path, text);
}

const Condition& find_condition(const std::vector<Condition>& conditions, const std::string& id) {
  for (const Condition& c : conditions)
    if (c.id == id) return c;
  std::string known;
  for (std::size_t k = 0; k < conditions.size() && k < 5; ++k) known += (k ? ", " : "") + conditions[k].id;
  throw InputError("--condition: no condition '" + id + "' in the spec (e.g. " + known +
                   "; `crowdlab crowd SPEC --list` lists them)");
}

void run_collision_table(const ExperimentSpec& spec, const std::vector<Condition>& conditions,
                         const Args& a) {
  const auto counts = count_spec_collisions(spec, conditions);
  const auto cells = collision_table(counts);
  write_file(a.collision_table, collision_table_csv(cells));
  std::printf("%s", collision_table_markdown(cells).c_str());
  spdlog::info("wrote {} ({} cells from {} trajectory sets)", a.collision_table, cells.size(), counts.size());
}

void run(const Args& a) {
  const ExperimentSpec spec = load_experiment_spec(a.spec);
  const std::vector<Condition> conditions = enumerate_conditions(spec);
  if (a.list) {
    for (const Condition& c : conditions) std::printf("%s\n", c.id.c_str());
    return;
  }
  if (!a.collision_table.empty()) {
    run_collision_table(spec, conditions, a);
    if (a.condition.empty()) return;
  }
  if (a.condition.empty())
    throw InputError("crowd: --condition ID is required (or --list / --collision-table)");
  if (a.csv.empty() && a.measures_dir.empty())
    throw InputError("crowd: give --csv FILE and/or --measures DIR");
  const Condition& condition = find_condition(conditions, a.condition);
  if (condition.params.scenario == ScenarioKind::manifold) {
    // Surface crowds (seed 002): the 3D trajectories; the 2D disc measures do not apply to them.
    if (!a.measures_dir.empty())
      throw InputError(
          "crowd: --measures is for 2D scenarios; for surface crowds use `crowdlab experiment "
          "manifold-compare`");
    const ManifoldScenario m = generate_manifold_scenario(spec, condition);
    write_file(a.csv, surface_trajectories_csv(m.surface, spec.fps));
    return;
  }
  const ScenarioResult r = generate_scenario(spec, condition);
  if (!a.csv.empty()) write_file(a.csv, trajectories_csv(r.trajectories));
  nlohmann::json summary = {{"condition", condition.id},
                            {"scenario", kind_name(r.scenario)},
                            {"characters", r.trajectories.agents.size()},
                            {"frames", r.trajectories.frame_count()},
                            {"fps", r.trajectories.fps},
                            {"area_m2", r.area_m2},
                            {"achieved_density_per_m2", r.achieved_density_per_m2},
                            {"min_spacing_m", r.min_spacing_m}};
  if (!a.measures_dir.empty()) {
    const std::filesystem::path dir(a.measures_dir);
    const auto events = disc_collision_events(r.trajectories);
    write_file(dir / "collisions.csv", disc_collision_events_csv(events, r.trajectories.fps));
    write_file(dir / "pairs.csv",
               pair_closest_approaches_csv(pair_closest_approaches(r.trajectories, a.pair_distance_m),
                                           r.trajectories.fps));
    const DistanceHistogram h = interpersonal_distance_histogram(r.trajectories, 0.05, a.pair_distance_m);
    write_file(dir / "distances.csv", distance_histogram_csv(h));
    summary["collisions"] = events.size();
    summary["mean_interpersonal_distance_m"] = h.mean_m;
    write_file(dir / "summary.json", summary.dump(2) + "\n");
  }
  std::printf("%s\n", summary.dump().c_str());
}

}  // namespace

void add_crowd_command(Command& root) {
  auto args = std::make_shared<Args>();
  Command* cmd = root.add_subcommand(
      "crowd",
      "Generate one condition's 2D crowd trajectories (placement + navigation) and its crowd measures");
  cmd->add_option("spec", args->spec, "Experiment spec (YAML)")->required()->check(check::existing_file());
  cmd->add_option("--condition", args->condition, "Condition id (see --list)");
  cmd->add_option("--csv", args->csv,
                  "Write character,frame,time_s,x,z,heading_rad,group,radius_m rows here");
  cmd->add_option(
      "--measures", args->measures_dir,
      "Write collisions.csv, pairs.csv (ttca/dtca per frame and pair), distances.csv (histogram) and "
      "summary.json into this folder");
  cmd->add_option("--pair-distance", args->pair_distance_m,
                  "Pairs closer than this (m) enter pairs.csv/distances.csv")
      ->capture_default_str();
  cmd->add_option(
      "--collision-table", args->collision_table,
      "Generate every scenario x density x repetition and write mean/sd collision counts (seed 001 "
      "Table 2) to this CSV");
  cmd->add_flag("--list", args->list, "List the spec's condition ids");
  cmd->callback([args] { run(*args); });
}

}  // namespace crowdlab::cli::cmd_crowd
