#pragma once
// The one generic runner of pipeline stages (stage.hpp), used for every stage of `crowdlab run`:
//   up-to-date check  every output exists, its sidecar records the stage's input hash (with the hashes
//                     of its input files) and the file's
//                     SHA-256 (provenance.hpp); then the stage is skipped and `load` reads its result
//   recompute         otherwise (or with `force`): `compute`, then every stale output is written via a
//                     temporary and renamed into place, and its sidecar is written after it; then
//                     `load` reads the result back from the files, so that what the stages downstream
//                     consume never depends on whether this run computed or resumed (stage.hpp)
//   progress          counts of stages run (main output, outputs.front(), remade) and skipped (main
//                     output up to date, even when a derived output was remade), a debug line per stage
//   error context     a failure names the stage and the output it was making: RuntimeError and other
//                     exceptions are rethrown as RuntimeError "stage 'NAME' (PATH): reason"; InputError
//                     passes on unchanged (it already names the file, line and key) after a log line.
// Outputs that are still up to date are not rewritten when a sibling output is stale (e.g. a clip's
// sidecar JSON is remade without re-encoding the clip).
#include "framework/pipeline/provenance.hpp"
#include "framework/pipeline/stage.hpp"

namespace crowdlab {

class StageRunner {
 public:
  /// force: treat every output as stale.
  StageRunner(ProvenanceContext context, bool force);

  /// Runs or skips `stage`; returns true when it ran (some output was stale).
  bool run(const Stage& stage);

  int stages_run() const { return run_; }
  int stages_skipped() const { return skipped_; }
  const ProvenanceContext& context() const { return context_; }

 private:
  ProvenanceContext context_;
  bool force_ = false;
  int run_ = 0;
  int skipped_ = 0;
};

}  // namespace crowdlab
