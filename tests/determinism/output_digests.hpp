#pragma once
// Content digests of crowdlab's outputs for the pinned-output-hash test (test_pinned_output_hash.cpp):
// each digest covers what an output says, never how or where or when it was written, so it is equal
// across runs, thread counts, output folders and crowdlab versions exactly when the content is.
//   crowd files (.glb)   the decoded CrowdAnimation (the file holds crowdlab's version as generator)
//   frames (PNG)         the decoded pixels (PNG bytes depend on the zlib build)
//   responses.csv        every column but the wall-clock `timestamp`
//   JSON                 the parsed document, re-serialised (sorted keys, shortest round-trip numbers)
//   text (report.md)     with the absolute paths it names replaced by placeholders
// Every digest is SHA-256 as lowercase hex (framework/core/sha256.hpp).
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab::test {

/// Digest of every value of a crowd: metadata, bodies (shape, capsules, mesh), poses, environment.
std::string crowd_animation_digest(const CrowdAnimation& crowd);

/// Digest of the decoded pixels of every `*.png` in `folder`, in file-name order (with sizes and
/// channel counts). Throws when a file cannot be decoded or the folder has none.
std::string png_frames_digest(const std::filesystem::path& folder);

/// Digest of a CSV file without the named column (when present).
std::string csv_digest_without_column(const std::filesystem::path& file, const std::string& column);

/// Digest of a JSON file's parsed content.
std::string json_digest(const std::filesystem::path& file);

/// Digest of a text file after replacing every occurrence of each `from` by its `to`, pair by pair in
/// the given order (list a path before any path that is a prefix of it).
std::string text_digest(const std::filesystem::path& file,
                        const std::vector<std::pair<std::string, std::string>>& placeholders);

}  // namespace crowdlab::test
