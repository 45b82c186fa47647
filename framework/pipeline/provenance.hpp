#pragma once
// Provenance and incremental re-runs for the run pipeline (`crowdlab run`, stage_runner.hpp).
//
// Every output file OUT gets a sidecar OUT.prov.json recording what made it:
//   {"stage", "input_hash", "output_sha256", "crowdlab_version", "spec_hash", "seed", "libraries",
//    "created_utc"}
// A stage's input_hash is the SHA-256 of its recipe (canonical bytes of every value it reads, stage.hpp),
// the version of its code, the hashes of its upstream stages and input files, and the crowdlab version. A
// stage re-runs only when its output is missing, its recorded input_hash differs (like a build system), or
// the output's SHA-256 differs from the recorded output_sha256 (a truncated or altered file, issue 21;
// sidecars without the field are redone once). Integrity: every output is written to a temporary name in its
// folder and renamed into place only when complete (write_output_via_temporary), and its sidecar is written
// after it, so a run killed at any point leaves either the old output with its old sidecar, or a new output
// whose hash no sidecar vouches for: both are redone or kept correctly by the next run. Sidecars are per
// file, so shards running in parallel never write the same file; `run --collect` merges them into
// DIR/provenance.json.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "framework/core/write_file.hpp"  // write_output_via_temporary, write_text_file

namespace crowdlab {

/// Versions of the libraries the framework was built against (crowdlab, Eigen); the composing program
/// adds its own (the CLI: libav*, OpenCV) to ProvenanceContext::libraries.
nlohmann::json framework_library_versions();

struct ProvenanceContext {
  std::string spec_hash;
  std::uint64_t seed = 0;
  nlohmann::json libraries = framework_library_versions();  ///< recorded in every sidecar
};

/// SHA-256 over the stage name, the version of its code, its recipe (canonical bytes, stage.hpp), its
/// upstream hashes and crowdlab's version.
std::string stage_input_hash(const std::string& stage, const std::string& code_version,
                             const std::string& recipe, const std::vector<std::string>& upstream_hashes);

/// True when `output` exists, its sidecar records exactly `input_hash`, and the file's SHA-256 is the
/// sidecar's output_sha256.
bool output_up_to_date(const std::filesystem::path& output, const std::string& input_hash);

/// Writes `output`.prov.json (with the SHA-256 of `output`) after `output` has been written completely.
void record_provenance(const std::filesystem::path& output, const std::string& stage,
                       const std::string& input_hash, const ProvenanceContext& context);

/// The recorded input hash of an output ("" when it has no sidecar).
std::string recorded_hash(const std::filesystem::path& output);

/// A provenance sidecar (OUTPUT.prov.json) read as untrusted JSON (framework/io/untrusted_json.hpp: at most
/// 64 levels deep and 16 MiB; a FIFO or device refused before opening). Throws InputError naming the
/// file and the byte.
nlohmann::json read_provenance_record(const std::filesystem::path& path);

}  // namespace crowdlab
