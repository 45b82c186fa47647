#include "experiments/cli/pipeline/collect.hpp"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "experiments/cli/pipeline/library_versions.hpp"
#include "framework/core/error.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/pipeline/provenance.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::cli {
namespace fs = std::filesystem;

namespace {
/// "manifest.shard-K-of-N.csv", as run_experiment() names a shard's manifest.
bool is_shard_manifest(const std::string& name) {
  return name.starts_with("manifest.shard-") && name.ends_with(".csv") &&
         name.find("-of-") != std::string::npos;
}
}  // namespace

CollectSummary collect_shards(const ExperimentSpec& spec, const fs::path& dir) {
  if (!fs::is_directory(dir)) throw InputError(dir.string() + ": no such output folder");
  CollectSummary s;
  StimulusManifest merged;
  std::map<std::string, int> seen;
  std::vector<fs::path> shard_files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (is_shard_manifest(entry.path().filename().string())) shard_files.push_back(entry.path());
  std::sort(shard_files.begin(), shard_files.end());
  if (shard_files.empty() && fs::exists(dir / "manifest.csv")) shard_files.push_back(dir / "manifest.csv");
  if (shard_files.empty()) throw RuntimeError(dir.string() + ": no manifest or shard manifests to collect");
  for (const fs::path& file : shard_files) {
    StimulusManifest m = read_manifest(file.string());
    if (merged.factor_names.empty()) merged.factor_names = m.factor_names;
    for (StimulusEntry& e : m.entries) {
      ++seen[e.id];
      merged.entries.push_back(std::move(e));
    }
    ++s.shards;
  }
  std::vector<Condition> expected = enumerate_practice_conditions(spec);
  for (Condition& c : enumerate_conditions(spec)) expected.push_back(std::move(c));
  std::string missing, duplicated;
  for (const Condition& c : expected) {
    const int n = seen.count(c.id) ? seen[c.id] : 0;
    if (n == 0) missing += " " + c.id;
    if (n > 1) duplicated += " " + c.id;
  }
  for (const auto& [id, n] : seen) {
    bool known = false;
    for (const Condition& c : expected) known = known || c.id == id;
    if (!known) duplicated += " " + id + "(unknown)";
  }
  if (!missing.empty() || !duplicated.empty())
    throw RuntimeError("collect " + dir.string() + ": " +
                       (missing.empty() ? "" : "missing conditions:" + missing + "; ") +
                       (duplicated.empty() ? "" : "duplicated or unknown:" + duplicated));
  // Enumeration order, whatever the shard order was.
  std::map<std::string, size_t> rank;
  for (size_t i = 0; i < expected.size(); ++i) rank[expected[i].id] = i;
  std::sort(merged.entries.begin(), merged.entries.end(),
            [&](const StimulusEntry& a, const StimulusEntry& b) { return rank[a.id] < rank[b.id]; });
  write_manifest(merged, (dir / "manifest.csv").string());
  s.entries = static_cast<int>(merged.entries.size());

  nlohmann::json prov;
  prov["spec_hash"] = spec.source_hash;
  prov["seed"] = spec.seed;
  prov["libraries"] = library_versions();
  prov["outputs"] = nlohmann::json::object();
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    const std::string name = entry.path().string();
    if (!name.ends_with(".prov.json")) continue;
    try {
      prov["outputs"][fs::relative(name.substr(0, name.size() - 10), dir).string()] =
          read_provenance_record(entry.path());
      ++s.provenance_records;
    } catch (const InputError& e) {
      throw RuntimeError(std::string(e.what()) + " (a corrupt provenance record: re-run that shard)");
    }
  }
  write_file_atomic(dir / "provenance.json", prov.dump(2) + "\n");
  return s;
}

}  // namespace crowdlab::cli
