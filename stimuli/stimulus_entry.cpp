#include "stimuli/stimulus_entry.hpp"

#include "framework/core/sha256.hpp"

namespace crowdlab::stimuli {

StimulusEntry make_stimulus_entry(const std::string& id, const std::map<std::string, std::string>& factors,
                                  const std::string& mp4_path, const std::string& file_in_manifest,
                                  const RenderResult& result) {
  StimulusEntry e;
  e.id = id;
  e.factors = factors;
  e.file = file_in_manifest;
  e.duration_s = result.duration_s;
  e.frames = result.frames;
  e.width = result.width;
  e.height = result.height;
  e.sha256 = sha256_file_hex(mp4_path);
  return e;
}

}  // namespace crowdlab::stimuli
