#pragma once
// StimulusManifest: what the stimuli stage produced, as the study and analysis stages read it.
// Stored as DIR/manifest.csv with columns:
//   id,<factor columns...>,file,duration_s,frames,width,height,sha256,overlap_l,v_i_m,collisions,practice
// (factor columns in spec order; metric columns empty when not computed).
#include <map>
#include <string>
#include <vector>

namespace crowdlab {

struct StimulusEntry {
  std::string id;                              ///< condition id (+ "_" + viewpoint when rendered per view)
  std::map<std::string, std::string> factors;  ///< factor name -> level text
  std::string file;                            ///< path relative to the manifest's folder
  double duration_s = 0.0;
  int frames = 0;
  int width = 0;
  int height = 0;
  std::string sha256;
  double mean_overlap_l = -1.0;  ///< per-character mean overlap volume, litres (-1 = unknown)
  double v_i_m = -1.0;           ///< seed 001 Eq. 1, metres (-1 = unknown)
  int collisions = -1;           ///< colliding character pairs over the clip (-1 = unknown)
  bool practice = false;
};

struct StimulusManifest {
  std::vector<std::string> factor_names;  ///< column order
  std::vector<StimulusEntry> entries;
};

/// Writes / reads DIR/manifest.csv. read_manifest() throws InputError naming file, row and column.
void write_manifest(const StimulusManifest& manifest, const std::string& csv_path);
StimulusManifest read_manifest(const std::string& csv_path);

}  // namespace crowdlab
