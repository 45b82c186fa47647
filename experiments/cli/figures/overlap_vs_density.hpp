#pragma once
// Seed 000 Figure 3 as files: the per-character mean overlap volume against density, baseline and
// corrected, per scenario. Used by `crowdlab experiment overlap-vs-density` and `crowdlab reproduce
// gomez2024` (which compute the rows differently but must write the same CSV and plots).
#include <filesystem>
#include <string>
#include <vector>

namespace crowdlab::cli {

struct OverlapRow {
  std::string scenario;  ///< stationary | corridor
  int characters = 0;
  double density = 0;         ///< characters per m^2 (the factor level)
  std::string method;         ///< baseline | ours
  double mean_overlap_l = 0;  ///< litres per character, mean over characters and frames
};

/// Writes dir/overlap_vs_density.csv (scenario,characters,density,method,mean_overlap_l, one row per
/// scenario x density x method in the given order) and dir/overlap_vs_density_<scenario>.png|svg.
void write_overlap_vs_density(const std::vector<OverlapRow>& rows, const std::filesystem::path& dir);

/// The baseline / ours value of one scenario and density; NaN when absent.
double overlap_of(const std::vector<OverlapRow>& rows, const std::string& scenario, double density,
                  const std::string& method);

}  // namespace crowdlab::cli
