#include "framework/io/write_root_trajectories_csv.hpp"

#include <string>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/write_file.hpp"

namespace crowdlab {

void write_root_trajectories_csv(const CrowdAnimation& crowd, const std::string& path) {
  validate_crowd(crowd, path);
  std::string out = csv_line({"character", "frame", "time_s", "x", "z", "heading_rad"});
  for (const CharacterAnimation& ch : crowd.characters)
    for (size_t f = 0; f < ch.frames.size(); ++f) {
      const Pose& p = ch.frames[f];
      out += csv_line({ch.name, std::to_string(f), csv_number(static_cast<double>(f) / crowd.meta.fps),
                       csv_number(p.root_position_m.x()), csv_number(p.root_position_m.z()),
                       csv_number(p.heading_rad())});
    }
  write_text_file(path, out);  // names the file and the OS's reason on failure
}

}  // namespace crowdlab
