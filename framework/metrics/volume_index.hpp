#pragma once
// V_i of seed 001 §3.1.3, Eq. 1: the mean cube root of the interpenetration volume over the frames
// of a clip where it is non-zero:
//   V_i = (1 / n_i) * sum_f cbrt(v_i(f)),  n_i = #{f : v_i(f) != 0}
// Input: v(f) per frame (m^3, >= 0). Output: metres (the cube root of m^3); 0 when n_i = 0 (the
// paper leaves that case undefined; a clip without collision has no interpenetration).
// Throws InputError for negative or non-finite entries (naming the frame).
#include <span>

namespace crowdlab {

double mean_cube_root_volume(std::span<const double> volume_per_frame_m3);

}  // namespace crowdlab
