#include "framework/pipeline/stage_runner.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"

namespace crowdlab {
namespace {

/// "from A, B and 2 more files": what a failed stage read, so that its error names the inputs and not
/// only the output it was making (issue 33: a bad asset was reported as "stage 'animation'
/// (.../baseline.glb): ...").
std::string inputs_text(const Stage& stage) {
  constexpr size_t kNamed = 3;
  if (stage.inputs.empty()) return "";
  std::string text = " from ";
  for (size_t i = 0; i < std::min(kNamed, stage.inputs.size()); ++i)
    text += (i ? ", " : "") + stage.inputs[i].string();
  if (stage.inputs.size() > kNamed)
    text += " and " + std::to_string(stage.inputs.size() - kNamed) + " more files";
  return text;
}

}  // namespace

std::string Stage::input_hash() const {
  std::vector<std::string> hashes = upstream;
  for (const std::filesystem::path& input : inputs) {
    if (!std::filesystem::exists(input))
      throw RuntimeError("stage '" + name + "': its input " + input.string() + " is missing");
    hashes.push_back(input.filename().string() + ":" + sha256_file_hex(input.string()));
  }
  return stage_input_hash(name, code_version, recipe, hashes);
}

StageRunner::StageRunner(ProvenanceContext context, bool force)
    : context_(std::move(context)), force_(force) {}

bool StageRunner::run(const Stage& stage) {
  if (stage.outputs.empty()) throw RuntimeError("stage '" + stage.name + "' declares no output");
  const std::string hash = stage.input_hash();
  std::vector<const StageOutput*> stale;
  for (const StageOutput& out : stage.outputs)
    if (force_ || !output_up_to_date(out.path, hash)) stale.push_back(&out);
  if (stale.empty()) {
    ++skipped_;
    spdlog::debug("stage {}: up to date ({})", stage.name, stage.outputs.front().path.string());
    if (stage.load) stage.load();
    return false;
  }
  // The stage counts as run when its main output is remade; remaking only a derived output (a clip's
  // JSON sidecar) keeps it counted as up to date, as `crowdlab run` has always reported it.
  (stale.front() == &stage.outputs.front() ? run_ : skipped_)++;
  spdlog::debug("stage {}: running ({})", stage.name, stale.front()->path.string());
  const StageOutput* current = stale.front();
  try {
    if (stage.compute) stage.compute();
    for (const StageOutput* out : stale) {
      current = out;
      write_output_via_temporary(out->path, out->write);
      record_provenance(out->path, stage.name, hash, context_);
    }
    // Downstream stages consume what is on disk, as they would after a resume (stage.hpp).
    if (stage.load) stage.load();
  } catch (const InputError&) {
    spdlog::error("stage '{}' failed on bad input while making {}", stage.name, current->path.string());
    throw;
  } catch (const std::exception& e) {
    throw RuntimeError("stage '" + stage.name + "' (making " + current->path.string() + inputs_text(stage) +
                       "): " + e.what());
  }
  return true;
}

}  // namespace crowdlab
