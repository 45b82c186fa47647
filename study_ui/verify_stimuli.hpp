#pragma once
// verify_stimuli: checks every stimulus a session will show BEFORE the session starts, so that a
// missing or corrupted file never interrupts a participant mid-study.
// For each manifest entry: the file exists, is a regular non-empty file, and its SHA-256 equals the
// manifest's sha256 column (when the column is filled). Files are hashed once each.
#include <string>
#include <vector>

#include "framework/core/stimulus_manifest.hpp"

namespace crowdlab::study {

/// Absolute path of an entry's file (manifest paths are relative to the manifest's folder).
std::string stimulus_path(const std::string& stimuli_dir, const StimulusEntry& entry);

/// Returns one message per problem ("<id>: <file>: missing" / "empty" / "sha256 mismatch ...").
std::vector<std::string> find_stimulus_problems(const StimulusManifest& manifest,
                                                const std::string& stimuli_dir);

/// Throws InputError listing every problem (exit code 2), or returns when all files are intact.
void verify_stimuli(const StimulusManifest& manifest, const std::string& stimuli_dir);

}  // namespace crowdlab::study
