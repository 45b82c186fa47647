#pragma once
// `crowdlab run SPEC --out DIR --collect`: merges the per-shard manifests (manifest.shard-K-of-N.csv)
// into DIR/manifest.csv and every provenance sidecar into DIR/provenance.json, after checking that
// every condition of the spec (practice included) appears exactly once. Throws RuntimeError naming
// the missing or duplicated condition ids.
#include <filesystem>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::cli {

struct CollectSummary {
  int shards = 0;
  int entries = 0;
  int provenance_records = 0;
};

CollectSummary collect_shards(const ExperimentSpec& spec, const std::filesystem::path& out_dir);

}  // namespace crowdlab::cli
