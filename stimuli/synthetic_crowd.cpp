#include "stimuli/synthetic_crowd.hpp"

#include <cmath>
#include <numbers>

#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab::stimuli {

CrowdAnimation make_synthetic_crowd(const SyntheticCrowdOptions& o) {
  if (o.characters < 1 || o.frames < 1 || !(o.fps > 0) || !(o.spacing_m > 0))
    throw InputError("synthetic crowd: characters, frames, fps and spacing must be positive");
  CrowdAnimation crowd;
  crowd.meta.fps = o.fps;
  crowd.meta.seed = o.seed;
  crowd.meta.scenario = "synthetic";
  crowd.meta.condition_id = "synthetic";
  const int columns =
      o.columns > 0 ? o.columns : static_cast<int>(std::ceil(std::sqrt(static_cast<double>(o.characters))));
  const double two_pi = 2.0 * std::numbers::pi;
  for (int i = 0; i < o.characters; ++i) {
    Rng rng(derive_seed(o.seed, "character/" + std::to_string(i)));
    BodyParams params;
    params.sex = i % 2 == 0 ? Sex::kFemale : Sex::kMale;
    params.height_m =
        std::clamp((params.sex == Sex::kFemale ? 1.63 : 1.76) + 0.07 * standard_normal(rng), 1.45, 2.0);
    params.girth = std::clamp(1.0 + 0.08 * standard_normal(rng), 0.8, 1.3);
    CharacterAnimation c;
    char name[16];
    std::snprintf(name, sizeof name, "c%03d", i);
    c.name = name;
    c.shape = make_procedural_body(params);
    c.palette = i;
    const double row = i / columns, col = i % columns;
    const double x = (col - 0.5 * (columns - 1)) * o.spacing_m + 0.08 * o.spacing_m * (uniform01(rng) - 0.5);
    const double z = -row * o.spacing_m + 0.08 * o.spacing_m * (uniform01(rng) - 0.5);
    const double heading = 0.25 * (uniform01(rng) - 0.5);
    const double phase = two_pi * uniform01(rng);
    const int cycles = 1 + static_cast<int>(uniform_index(rng, 2));
    for (int f = 0; f < o.frames; ++f) {
      const double t = two_pi * cycles * f / o.frames + phase;  // periodic over the clip
      Pose p = Pose::rest(c.shape);
      p.root_position_m = Vec3(x, c.shape.pelvis_height_m() + 0.01 * std::sin(2 * t), z);
      p.local_rotations[kPelvis] = Quat(Eigen::AngleAxisd(heading + 0.08 * std::sin(t), Vec3::UnitY()));
      p.local_rotations[kSpine2] = Quat(Eigen::AngleAxisd(0.05 * std::sin(t), Vec3::UnitZ()));
      p.local_rotations[kHead] = Quat(Eigen::AngleAxisd(0.2 * std::sin(t + 1.0), Vec3::UnitY()));
      p.local_rotations[kLeftShoulder] = Quat(Eigen::AngleAxisd(-1.25 + 0.1 * std::sin(t), Vec3::UnitZ()) *
                                              Eigen::AngleAxisd(0.15 * std::sin(t), Vec3::UnitY()));
      p.local_rotations[kRightShoulder] = Quat(Eigen::AngleAxisd(1.25 - 0.1 * std::sin(t), Vec3::UnitZ()) *
                                               Eigen::AngleAxisd(0.15 * std::sin(t), Vec3::UnitY()));
      p.local_rotations[kLeftElbow] = Quat(Eigen::AngleAxisd(0.3 + 0.2 * std::sin(t), Vec3::UnitY()));
      p.local_rotations[kRightElbow] = Quat(Eigen::AngleAxisd(-0.3 - 0.2 * std::sin(t), Vec3::UnitY()));
      p.local_rotations[kLeftHip] = Quat(Eigen::AngleAxisd(0.05 * std::sin(t), Vec3::UnitX()));
      p.local_rotations[kRightHip] = Quat(Eigen::AngleAxisd(-0.05 * std::sin(t), Vec3::UnitX()));
      if (o.walk_speed_mps > 0.0) {  // stride ~ 0.7 m per step at 1.2 m/s
        const double time_s = f / o.fps;
        const double gait = two_pi * o.walk_speed_mps / 1.4 * time_s + phase;
        p.root_position_m.z() += o.walk_speed_mps * time_s;
        p.root_position_m.y() = c.shape.pelvis_height_m() - 0.02 + 0.015 * std::cos(2 * gait);
        p.local_rotations[kPelvis] =
            Quat(Eigen::AngleAxisd(heading * 0.2 + 0.06 * std::sin(gait), Vec3::UnitY()));
        p.local_rotations[kLeftHip] = Quat(Eigen::AngleAxisd(-0.4 * std::sin(gait), Vec3::UnitX()));
        p.local_rotations[kRightHip] = Quat(Eigen::AngleAxisd(0.4 * std::sin(gait), Vec3::UnitX()));
        p.local_rotations[kLeftKnee] =
            Quat(Eigen::AngleAxisd(0.5 * std::max(0.0, std::cos(gait)), Vec3::UnitX()));
        p.local_rotations[kRightKnee] =
            Quat(Eigen::AngleAxisd(0.5 * std::max(0.0, -std::cos(gait)), Vec3::UnitX()));
        p.local_rotations[kLeftShoulder] = Quat(Eigen::AngleAxisd(-1.3, Vec3::UnitZ()) *
                                                Eigen::AngleAxisd(0.35 * std::sin(gait), Vec3::UnitX()));
        p.local_rotations[kRightShoulder] = Quat(Eigen::AngleAxisd(1.3, Vec3::UnitZ()) *
                                                 Eigen::AngleAxisd(-0.35 * std::sin(gait), Vec3::UnitX()));
      }
      c.frames.push_back(p);
    }
    crowd.characters.push_back(std::move(c));
  }
  if (o.corridor_walls) {
    const double half_width = 0.5 * columns * o.spacing_m + 0.5;
    const double rows = std::ceil(static_cast<double>(o.characters) / columns);
    const double z_lo = -rows * o.spacing_m - 2.0, z_hi = o.walk_speed_mps * o.frames / o.fps + 3.0;
    for (int side : {-1, 1}) {
      Box wall;
      wall.center_m = Vec3(side * (half_width + 0.1), 1.25, 0.5 * (z_lo + z_hi));
      wall.half_extents_m = Vec3(0.1, 1.25, 0.5 * (z_hi - z_lo));
      crowd.environment.boxes.push_back(wall);
    }
  }
  if (o.stage) {
    Box stage;
    const double width = columns * o.spacing_m + 2.0;
    stage.center_m = Vec3(0.0, 0.25, 0.5 * o.spacing_m + 2.5);
    stage.half_extents_m = Vec3(0.5 * width, 0.25, 0.75);
    crowd.environment.boxes.push_back(stage);
  }
  return crowd;
}

}  // namespace crowdlab::stimuli
