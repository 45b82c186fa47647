#include "framework/pipeline/provenance.hpp"

#include <Eigen/Core>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>

#include "crowdlab_version.hpp"
#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"
#include "framework/io/untrusted_json.hpp"

namespace crowdlab {
namespace fs = std::filesystem;

std::string stage_input_hash(const std::string& stage, const std::string& code_version,
                             const std::string& recipe, const std::vector<std::string>& upstream_hashes) {
  // The recipe is raw bytes (not UTF-8): it is hashed on its own and only its digest enters the JSON.
  nlohmann::json j;
  j["stage"] = stage;
  j["code_version"] = code_version;
  j["recipe_sha256"] = sha256_hex(recipe);
  j["upstream"] = upstream_hashes;
  j["crowdlab_version"] = CROWDLAB_VERSION;
  return sha256_hex(j.dump());
}

static fs::path sidecar(const fs::path& output) {
  return fs::path(output.string() + ".prov.json");
}

/// The sidecar of `output` as JSON (null when missing or torn: killed mid-write means "not up to date").
nlohmann::json read_provenance_record(const fs::path& path) {
  JsonLimits limits;
  limits.max_bytes = 16u << 20;  // a sidecar is a few hundred bytes
  return read_untrusted_json(path, "provenance record", limits);
}

/// A sidecar nested deep, huge or a FIFO is "not up to date" too, never a crash or a hang; rewriting it
/// then refuses what is not a regular file.
static nlohmann::json read_sidecar(const fs::path& output) {
  if (!fs::exists(fs::symlink_status(sidecar(output)))) return nullptr;
  try {
    return read_provenance_record(sidecar(output));
  } catch (const InputError&) {
    return nullptr;
  }
}

/// A text field of a sidecar, "" when it is missing or not text: json's value() threw a bare type_error
/// ("type must be string, but is number") out of `crowdlab run` for `"input_hash": 5` (issue 33).
static std::string text_field(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : "";
}

std::string recorded_hash(const fs::path& output) {
  const nlohmann::json j = read_sidecar(output);
  return j.is_object() ? text_field(j, "input_hash") : "";
}

bool output_up_to_date(const fs::path& output, const std::string& input_hash) {
  if (!fs::exists(output)) return false;
  const nlohmann::json j = read_sidecar(output);
  return j.is_object() && text_field(j, "input_hash") == input_hash &&
         text_field(j, "output_sha256") == sha256_file_hex(output.string());
}

nlohmann::json framework_library_versions() {
  nlohmann::json j;
  j["crowdlab"] = CROWDLAB_VERSION;
  j["eigen"] = std::to_string(EIGEN_WORLD_VERSION) + "." + std::to_string(EIGEN_MAJOR_VERSION) + "." +
               std::to_string(EIGEN_MINOR_VERSION);
  return j;
}

void record_provenance(const fs::path& output, const std::string& stage, const std::string& input_hash,
                       const ProvenanceContext& context) {
  nlohmann::json j;
  j["stage"] = stage;
  j["output"] = output.filename().string();
  j["input_hash"] = input_hash;
  j["output_sha256"] = sha256_file_hex(output.string());
  j["crowdlab_version"] = CROWDLAB_VERSION;
  j["spec_hash"] = context.spec_hash;
  j["seed"] = context.seed;
  j["libraries"] = context.libraries;
  const std::time_t now = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  j["created_utc"] = buf;
  write_file_atomic(sidecar(output), j.dump(2) + "\n");
}

}  // namespace crowdlab
