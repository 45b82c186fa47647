#include "study_ui/verify_stimuli.hpp"

#include <filesystem>
#include <map>

#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"

namespace crowdlab::study {

std::string stimulus_path(const std::string& stimuli_dir, const StimulusEntry& entry) {
  const std::filesystem::path p(entry.file);
  return (p.is_absolute() ? p : std::filesystem::path(stimuli_dir) / p).lexically_normal().string();
}

std::vector<std::string> find_stimulus_problems(const StimulusManifest& manifest,
                                                const std::string& stimuli_dir) {
  std::vector<std::string> problems;
  std::map<std::string, std::string> hash_of;  // path -> sha256 (hash each file once)
  for (const StimulusEntry& e : manifest.entries) {
    const std::string path = stimulus_path(stimuli_dir, e);
    std::error_code ec;
    if (e.file.empty()) {
      problems.push_back(e.id + ": no file named in the manifest");
      continue;
    }
    if (!std::filesystem::is_regular_file(path, ec)) {
      problems.push_back(e.id + ": " + path + ": missing");
      continue;
    }
    if (std::filesystem::file_size(path, ec) == 0 || ec) {
      problems.push_back(e.id + ": " + path + ": empty or unreadable");
      continue;
    }
    if (e.sha256.empty()) continue;
    auto it = hash_of.find(path);
    if (it == hash_of.end()) {
      try {
        it = hash_of.emplace(path, sha256_file_hex(path)).first;
      } catch (const std::exception& ex) {
        problems.push_back(e.id + ": " + ex.what());
        continue;
      }
    }
    if (it->second != e.sha256)
      problems.push_back(e.id + ": " + path + ": sha256 mismatch (manifest " + e.sha256 + ", file " +
                         it->second + "): corrupted or replaced");
  }
  return problems;
}

void verify_stimuli(const StimulusManifest& manifest, const std::string& stimuli_dir) {
  const auto problems = find_stimulus_problems(manifest, stimuli_dir);
  if (problems.empty()) return;
  std::string msg = std::to_string(problems.size()) + " stimulus file problem(s) in " + stimuli_dir +
                    "; the session was not started:";
  for (const auto& p : problems) msg += "\n  " + p;
  throw InputError(msg);
}

}  // namespace crowdlab::study
