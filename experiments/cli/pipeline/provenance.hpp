#pragma once
// Provenance and incremental re-runs for `crowdlab run`.
//
// Every output file OUT gets a sidecar OUT.prov.json recording what made it:
//   {"stage", "input_hash", "crowdlab_version", "spec_hash", "seed", "libraries", "created_utc"}
// A stage's input_hash is the SHA-256 of its parameters (canonical JSON), the hashes of its upstream
// outputs and the crowdlab version. A stage re-runs only when its output is missing or its recorded
// input_hash differs, like a build system. Sidecars are per file, so shards running in parallel never
// write the same file; `run --collect` merges them into DIR/provenance.json.
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace crowdlab::cli {

struct ProvenanceContext {
  std::string spec_hash;
  std::uint64_t seed = 0;
};

/// SHA-256 over the stage name, its parameters (canonical JSON dump) and its upstream hashes.
std::string stage_input_hash(const std::string& stage, const nlohmann::json& params,
                             const std::vector<std::string>& upstream_hashes);

/// True when `output` exists and its sidecar records exactly `input_hash`.
bool output_up_to_date(const std::filesystem::path& output, const std::string& input_hash);

/// Writes `output`.prov.json after `output` has been written completely.
void record_provenance(const std::filesystem::path& output, const std::string& stage,
                       const std::string& input_hash, const ProvenanceContext& context);

/// The recorded input hash of an output ("" when it has no sidecar).
std::string recorded_hash(const std::filesystem::path& output);

/// Versions of the libraries crowdlab was built against (Eigen, yaml-cpp, libav*, OpenCV, ...).
nlohmann::json library_versions();

/// Writes a file atomically: to a temporary name in the same folder, fsync, then rename.
void write_file_atomic(const std::filesystem::path& path, const std::string& contents);

}  // namespace crowdlab::cli
