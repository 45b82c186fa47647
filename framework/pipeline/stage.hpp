#pragma once
// One stage of the run pipeline, described as data (issue 22): what it is called, its recipe (the plain
// struct of every value its computation reads, issue 30), what it reads (the input hashes of the stages
// upstream, its input files), the files it makes and how, and how to read its result back when those
// files are up to date. StageRunner (stage_runner.hpp)
// runs every stage the same way; provenance.hpp defines the input hash and the sidecars.
//
// A stage's result usually lives in memory too (a CrowdAnimation, a metrics JSON): `compute` makes it
// when some output is stale, each output's `write` writes it to a file, and `load` reads it back from the
// files: instead of computing when every output is up to date, and after writing when it computed. So
// the stages downstream always consume exactly what is on disk (a float32 crowd file, say), whether the
// run computed the result or resumed from it: an interrupted run reproduces an uninterrupted one
// (issue 21). Stages that only write files leave compute/load empty.
//
// The input hash covers the recipe through canonical_bytes() (framework/core/canonical_bytes.hpp), which
// serialises every field of the recipe struct: a value the computation reads is a recipe field, so it
// is hashed without being listed, and a value that is not a field (the YAML text, a protocol's wording)
// cannot redo the stage. Each recipe names its stage and the version of that stage's code
// (Recipe::kStage, Recipe::kCodeVersion); stage_for(recipe) fills the three.
//
// What a stage reads is part of its input hash twice over: `upstream` names the recipes of the stages
// upstream (their input hashes), and `inputs` names the files it reads, whose SHA-256 is hashed in when
// the stage runs. So an upstream output that was deleted and recomputed with different bytes (new
// body-model assets, another library version) redoes everything downstream of it (issue 21).
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "framework/core/canonical_bytes.hpp"

namespace crowdlab {

struct StageOutput {
  std::filesystem::path path;  ///< the final file (written via a temporary in its folder)
  /// Writes the complete file at `tmp` (same folder and extension as `path`).
  std::function<void(const std::filesystem::path& tmp)> write;
};

struct Stage {
  std::string name;          ///< "crowd", "animation", ...: recorded in the sidecars
  std::string code_version;  ///< bumped when the stage's code changes its output (Recipe::kCodeVersion)
  std::string recipe;        ///< canonical_bytes() of the stage's recipe: every value its computation reads
  std::vector<std::string> upstream;          ///< input hashes of the stages whose results this one reads
  std::vector<std::filesystem::path> inputs;  ///< files this stage reads: they must exist when it runs
  std::vector<StageOutput> outputs;           ///< at least one; the first is the main one (see StageRunner)
  std::function<void()> compute;              ///< optional: makes the result before any output is written
  std::function<void()> load;  ///< optional: reads the result from the outputs (skipped or just written)

  /// stage_input_hash(name, code_version, recipe, upstream + the SHA-256 of every input file): what
  /// the outputs' sidecars must record to be up to date. Throws RuntimeError when an input file is
  /// missing.
  std::string input_hash() const;
};

/// A stage named and versioned by its recipe type, hashing `recipe` (every field of it).
template <class Recipe>
Stage stage_for(const Recipe& recipe) {
  Stage s;
  s.name = std::string(Recipe::kStage);
  s.code_version = std::string(Recipe::kCodeVersion);
  s.recipe = canonical_bytes(recipe);
  return s;
}

}  // namespace crowdlab
