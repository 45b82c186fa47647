#pragma once
// Seed 000 Figure 4 as files: the corrected root position of the shoved character against time, one
// curve per damping d, with its target. Used by `crowdlab experiment damping` and `crowdlab reproduce
// gomez2024`.
#include <filesystem>
#include <vector>

#include "framework/correction/damping_experiment.hpp"

namespace crowdlab::cli {

/// Writes dir/damping.csv (damping,time_s,position_m,target_m), dir/damping_summary.csv
/// (damping,rms_deviation_m,max_deviation_m) and dir/damping.png|svg (position vs time; the target
/// dashed; the peak of the shove, t = 3.5 s, dotted).
void write_damping_figure(const std::vector<DampingRun>& runs, const std::filesystem::path& dir);

}  // namespace crowdlab::cli
