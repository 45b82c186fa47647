// The generic stage runner (framework/pipeline/stage_runner.hpp) and the framework's run pipeline
// (run_experiment.hpp), tested directly, without the binary: up-to-date skip, recompute when a
// parameter or an upstream hash changes or an output is missing or altered, provenance written after
// the output, only stale outputs rewritten, and a failure named by its stage and output.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/pipeline/run_experiment.hpp"
#include "framework/pipeline/stage_runner.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_stage_runner {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

/// A stage with one text output per name, counting what it computes, writes and loads.
struct CountingStage {
  explicit CountingStage(fs::path folder) : dir(std::move(folder)) {}
  fs::path dir;
  std::string text = "v1";
  std::vector<std::string> upstream;
  int computed = 0, loaded = 0;
  std::map<std::string, int> written;

  Stage stage(const std::vector<std::string>& names = {"out.txt"}) {
    Stage s;
    s.name = "counting";
    s.recipe = canonical_bytes(text);
    s.upstream = upstream;
    for (const std::string& name : names)
      s.outputs.push_back({dir / name, [this, name](const fs::path& tmp) {
                             ++written[name];
                             write_text_file(tmp, text + ":" + name);
                           }});
    s.compute = [this] { ++computed; };
    s.load = [this] { ++loaded; };
    return s;
  }
};

nlohmann::json sidecar_of(const fs::path& output) {
  std::ifstream in(output.string() + ".prov.json");
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("stage runner: runs once, then skips and loads while nothing changed") {
  CountingStage c{scratch_dir("stage_runner_skip")};
  StageRunner runner(ProvenanceContext{"spec-hash", 7}, false);
  CHECK(runner.run(c.stage()));
  CHECK(slurp(c.dir / "out.txt") == "v1:out.txt");
  CHECK(c.computed == 1);
  CHECK(c.loaded == 1);  // read back after writing: downstream consumes what is on disk
  CHECK_FALSE(runner.run(c.stage()));
  CHECK(c.computed == 1);
  CHECK(c.loaded == 2);
  CHECK(runner.stages_run() == 1);
  CHECK(runner.stages_skipped() == 1);
  // A new runner over the same folder (the next `crowdlab run`) skips too.
  StageRunner next(ProvenanceContext{"spec-hash", 7}, false);
  CHECK_FALSE(next.run(c.stage()));
  // ... unless forced.
  StageRunner forced(ProvenanceContext{"spec-hash", 7}, true);
  CHECK(forced.run(c.stage()));
  CHECK(c.computed == 2);
}

TEST_CASE("stage runner: the result is read back from the outputs after they are written") {
  // The stage's in-memory result is replaced by what its file holds, as a resumed run would load it
  // (issue 21: a crowd corrected from the in-memory baseline differed from one corrected after a resume).
  const fs::path dir = scratch_dir("stage_runner_read_back");
  std::string result;
  Stage s;
  s.name = "lossy";
  s.outputs.push_back(
      {dir / "out.txt", [&](const fs::path& tmp) { write_text_file(tmp, result.substr(0, 4)); }});
  s.compute = [&] { result = "0.123456789"; };
  s.load = [&] { result = slurp(dir / "out.txt"); };
  StageRunner runner(ProvenanceContext{}, false);
  REQUIRE(runner.run(s));
  CHECK(result == "0.12");
}

TEST_CASE("stage runner: an input file recomputed with other bytes redoes the stage that reads it") {
  // Issue 21: a crowd file deleted and recomputed kept its stale metrics and clip, whose input hash
  // covered only the upstream stage's parameters, not the bytes they read.
  CountingStage up{scratch_dir("stage_runner_input_file")};
  CountingStage down{up.dir};
  StageRunner runner(ProvenanceContext{}, false);
  const auto downstream = [&] {
    Stage s = down.stage({"down.txt"});
    s.inputs = {up.dir / "up.txt"};
    return s;
  };
  REQUIRE(runner.run(up.stage({"up.txt"})));
  REQUIRE(runner.run(downstream()));
  CHECK_FALSE(runner.run(downstream()));
  // Recomputed with the same bytes: downstream stays up to date.
  fs::remove(up.dir / "up.txt");
  REQUIRE(runner.run(up.stage({"up.txt"})));
  CHECK_FALSE(runner.run(downstream()));
  // Recomputed with other bytes under the same parameters (what new assets or another library do).
  fs::remove(up.dir / "up.txt");
  const auto params = up.stage({"up.txt"}).input_hash();
  Stage changed = up.stage({"up.txt"});
  changed.outputs[0].write = [](const fs::path& tmp) { write_text_file(tmp, "other bytes"); };
  REQUIRE(changed.input_hash() == params);
  REQUIRE(runner.run(changed));
  CHECK(runner.run(downstream()));
  CHECK(down.computed == 2);
  // A missing input is an error naming it, never a silent skip.
  fs::remove(up.dir / "up.txt");
  CHECK_THROWS_WITH(runner.run(downstream()), Catch::Contains("up.txt") && Catch::Contains("missing"));
}

TEST_CASE("stage runner: a changed parameter or upstream hash recomputes") {
  CountingStage c{scratch_dir("stage_runner_inputs")};
  StageRunner runner(ProvenanceContext{}, false);
  REQUIRE(runner.run(c.stage()));
  c.text = "v2";
  CHECK(runner.run(c.stage()));
  CHECK(slurp(c.dir / "out.txt") == "v2:out.txt");
  CHECK_FALSE(runner.run(c.stage()));
  c.upstream = {"an upstream stage changed"};
  CHECK(runner.run(c.stage()));
  CHECK(sidecar_of(c.dir / "out.txt")["input_hash"] == c.stage().input_hash());
  CHECK(c.computed == 3);
}

TEST_CASE("stage runner: a missing or altered output is remade, its up-to-date sibling is not") {
  CountingStage c{scratch_dir("stage_runner_outputs")};
  StageRunner runner(ProvenanceContext{}, false);
  REQUIRE(runner.run(c.stage({"a.txt", "b.txt"})));
  fs::remove(c.dir / "a.txt");
  CHECK(runner.run(c.stage({"a.txt", "b.txt"})));
  CHECK(c.written["a.txt"] == 2);
  CHECK(c.written["b.txt"] == 1);
  {
    std::ofstream(c.dir / "b.txt", std::ios::app) << "x";  // altered after its sidecar was written
  }
  CHECK(runner.run(c.stage({"a.txt", "b.txt"})));
  CHECK(c.written["a.txt"] == 2);
  CHECK(c.written["b.txt"] == 2);
  // Runs: the first, and the one that remade the main output a.txt; remaking only b.txt is not one.
  CHECK(runner.stages_run() == 2);
  CHECK(runner.stages_skipped() == 1);
  CHECK(slurp(c.dir / "b.txt") == "v1:b.txt");
  // A lost sidecar makes its output stale as well.
  fs::remove(c.dir / "a.txt.prov.json");
  CHECK(runner.run(c.stage({"a.txt", "b.txt"})));
  CHECK(c.written["a.txt"] == 3);
}

TEST_CASE("stage runner: provenance is written after the output and records its hash") {
  CountingStage c{scratch_dir("stage_runner_provenance")};
  StageRunner runner(ProvenanceContext{"spec-hash", 42}, false);
  Stage s = c.stage();
  // While the output is being written, no sidecar vouches for it yet.
  auto write = s.outputs[0].write;
  s.outputs[0].write = [&](const fs::path& tmp) {
    CHECK_FALSE(fs::exists(c.dir / "out.txt.prov.json"));
    write(tmp);
  };
  REQUIRE(runner.run(s));
  const nlohmann::json prov = sidecar_of(c.dir / "out.txt");
  CHECK(prov["stage"] == "counting");
  CHECK(prov["spec_hash"] == "spec-hash");
  CHECK(prov["seed"] == 42);
  CHECK(prov["output_sha256"] == sha256_file_hex((c.dir / "out.txt").string()));
  CHECK(prov["libraries"].contains("eigen"));
}

TEST_CASE("stage runner: a failure names the stage and the output, and leaves no output") {
  CountingStage c{scratch_dir("stage_runner_failure")};
  StageRunner runner(ProvenanceContext{}, false);
  Stage s = c.stage({"a.txt", "b.txt"});
  s.outputs[1].write = [](const fs::path& tmp) {
    write_text_file(tmp, "half");
    throw std::runtime_error("disk on fire");
  };
  try {
    runner.run(s);
    FAIL("no error");
  } catch (const RuntimeError& e) {
    CHECK_THAT(e.what(), Catch::Contains("stage 'counting'") && Catch::Contains("b.txt") &&
                             Catch::Contains("disk on fire"));
  }
  CHECK(fs::exists(c.dir / "a.txt.prov.json"));  // the output made before the failure is kept
  CHECK_FALSE(fs::exists(c.dir / "b.txt"));
  CHECK_FALSE(fs::exists(c.dir / "b.txt.prov.json"));
  // The files it read are named too (issue 33: a bad asset was reported by the output alone).
  write_text_file(c.dir / "rig.json", "{}");
  s.inputs = {c.dir / "rig.json"};
  CHECK_THROWS_WITH(runner.run(s), Catch::Contains("from " + (c.dir / "rig.json").string()));
  // Bad input passes on as InputError (exit 2), not as a runtime failure.
  s.outputs[1].write = [](const fs::path&) { throw InputError("bad.yaml: key: broken"); };
  CHECK_THROWS_AS(runner.run(s), InputError);
}

TEST_CASE("run_experiment without presentation stages: crowd, animation, correction and metrics") {
  const fs::path out = scratch_dir("stage_runner_experiment");
  const ExperimentSpec spec = load_experiment_spec(tiny_spec());
  RunOptions options;
  options.out_dir = out;
  options.only = "density-2.5_viewpoint-V4_method-ours_rep-1";
  RunSummary first = run_experiment(spec, options);
  CHECK(first.conditions == 1);
  // crowd, animation, correction and the corrected crowd's metrics.
  CHECK(first.stages_run == 4);
  CHECK(first.stages_skipped == 0);
  const fs::path group = out / "crowds/density-2.5_rep-1";
  for (const char* file : {"trajectories.csv", "baseline.glb", "ours.glb", "ours.metrics.json"}) {
    INFO(file);
    CHECK(fs::exists(group / file));
    CHECK(fs::exists(group / (std::string(file) + ".prov.json")));
  }
  CHECK_FALSE(fs::exists(group / "baseline.metrics.json"));
  const StimulusManifest m = read_manifest(first.manifest.string());
  REQUIRE(m.entries.size() == 1);
  CHECK(m.entries[0].file.empty());
  CHECK(m.entries[0].frames == 15);
  CHECK(m.entries[0].mean_overlap_l >= 0.0);
  // Nothing changed: every stage is up to date (the crowd stage is checked, not remade).
  RunSummary second = run_experiment(spec, options);
  CHECK(second.stages_run == 0);
  CHECK(second.stages_skipped == 4);
  // An altered corrected crowd is remade; its metrics, whose input hash is unchanged, are not.
  fs::resize_file(group / "ours.glb", fs::file_size(group / "ours.glb") - 4);
  RunSummary third = run_experiment(spec, options);
  CHECK(third.stages_run == 1);
}

}  // namespace test_stage_runner
