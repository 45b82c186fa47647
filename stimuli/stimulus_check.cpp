#include "stimuli/stimulus_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab::stimuli {
namespace {

constexpr int kPoints = kJointCount + 1;  // the joints and the top of the head
using BodyPoints = std::array<Vec3, kPoints>;

/// Height of the head joint above the feet in the rest pose (the chain's offsets; the rest pose is
/// upright), so the top of the head is height_m - this above the head joint, along the head bone.
double rest_head_height_m(const BodyShape& shape) {
  double y = 0.0;
  for (int j = kHead; j >= 0; j = kJointParent[static_cast<size_t>(j)])
    y += shape.joint_offsets_m[static_cast<size_t>(j)].y();
  return y;
}

BodyPoints body_points(const CharacterAnimation& c, int frame, double head_top_m) {
  const BoneTransforms bones = forward_kinematics(c.shape, c.frames[static_cast<size_t>(frame)]);
  BodyPoints p;
  for (int j = 0; j < kJointCount; ++j) p[static_cast<size_t>(j)] = bones[static_cast<size_t>(j)].translation;
  p[kJointCount] = bones[kHead].apply(Vec3(0.0, head_top_m, 0.0));
  return p;
}

/// A camera's world -> pixel map with the matrices multiplied once (Camera::project's convention).
struct Projector {
  Eigen::Matrix4d pv;
  double width, height;
  explicit Projector(const Camera& c) : pv(c.projection() * c.view()), width(c.width), height(c.height) {}
  std::optional<Eigen::Vector2d> operator()(const Vec3& world) const {
    const Eigen::Vector4d clip = pv * world.homogeneous();
    if (clip.w() <= 1e-9) return std::nullopt;
    return Eigen::Vector2d((clip.x() / clip.w() + 1.0) * 0.5 * width,
                           (1.0 - clip.y() / clip.w()) * 0.5 * height);
  }
};

using ScreenPoints = std::array<std::optional<Eigen::Vector2d>, kPoints>;

double median(std::vector<double> v) {
  if (v.empty()) return -1.0;
  const size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(mid), v.end());
  return v[mid];
}

/// Mean displacement between two frames' screen points of every character (both in front of the camera).
double screen_step(const std::vector<ScreenPoints>& a, const std::vector<ScreenPoints>& b) {
  double sum = 0.0;
  long n = 0;
  for (size_t c = 0; c < a.size(); ++c)
    for (int k = 0; k < kPoints; ++k)
      if (a[c][static_cast<size_t>(k)] && b[c][static_cast<size_t>(k)]) {
        sum += (*a[c][static_cast<size_t>(k)] - *b[c][static_cast<size_t>(k)]).norm();
        ++n;
      }
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

/// On-screen motion of the still world between two cameras: the mean displacement of five ground points
/// around camera a's target (the target's foot point and 2 m to each side), seen by a and by b. Zero
/// for a camera that does not move; a camera that jumps (a following camera at the loop) shows here.
double background_step(const Camera& a, const Camera& b) {
  const Vec3 centre(a.target.x(), 0.0, a.target.z());
  const Projector pa(a), pb(b);
  double sum = 0.0;
  int n = 0;
  for (const Vec3& d : {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(-2, 0, 0), Vec3(0, 0, 2), Vec3(0, 0, -2)}) {
    const auto qa = pa(centre + d), qb = pb(centre + d);
    if (qa && qb) {
      sum += (*qa - *qb).norm();
      ++n;
    }
  }
  return n > 0 ? sum / n : 0.0;
}

/// seam / typical step, capped at 1e6; 1 when neither moves.
double step_ratio(double seam, double typical) {
  if (typical > 1e-9) return std::min(seam / typical, 1e6);
  return seam > 1e-9 ? 1e6 : 1.0;
}

}  // namespace

StimulusCheck measure_stimulus_geometry(const CrowdAnimation& crowd, const Viewpoint& view, int frames) {
  if (frames < 1 || frames > crowd.frame_count())
    throw InputError("stimulus check: " + std::to_string(frames) + " frames asked of a crowd of " +
                     std::to_string(crowd.frame_count()));
  std::vector<double> head_top(crowd.characters.size());
  for (size_t c = 0; c < crowd.characters.size(); ++c) {
    const BodyShape& s = crowd.characters[c].shape;
    head_top[c] = std::max(0.0, s.params.height_m - rest_head_height_m(s));
  }
  auto project_frame = [&](int f, const Projector& cam) {
    std::vector<ScreenPoints> out(crowd.characters.size());
    for (size_t c = 0; c < crowd.characters.size(); ++c) {
      const BodyPoints p = body_points(crowd.characters[c], f, head_top[c]);
      for (int k = 0; k < kPoints; ++k) out[c][static_cast<size_t>(k)] = cam(p[static_cast<size_t>(k)]);
    }
    return out;
  };
  StimulusCheck check;
  std::vector<double> heights, steps, background_steps;
  double in_frame_min = 1.0;
  std::vector<ScreenPoints> first, previous;
  for (int f = 0; f < frames; ++f) {
    const Camera camera = view.at(f);
    const std::vector<ScreenPoints> now = project_frame(f, Projector(camera));
    int inside = 0;
    for (const ScreenPoints& pts : now) {
      bool in = true;
      double y0 = 1e30, y1 = -1e30;
      for (const auto& p : pts) {
        in = in && p && p->x() >= 0.0 && p->x() <= camera.width && p->y() >= 0.0 && p->y() <= camera.height;
        if (p) y0 = std::min(y0, p->y()), y1 = std::max(y1, p->y());
      }
      if (!in) continue;
      ++inside;
      heights.push_back(y1 - y0);
    }
    if (!now.empty())
      in_frame_min = std::min(in_frame_min, static_cast<double>(inside) / static_cast<double>(now.size()));
    if (f > 0) {
      steps.push_back(screen_step(previous, now));
      background_steps.push_back(background_step(view.at(f - 1), camera));
    }
    if (f == 0) first = now;
    previous = now;
  }
  check.crowd_in_frame_min = crowd.characters.empty() ? -1.0 : in_frame_min;
  check.character_height_px = median(heights);
  // The seam: the last frame, then the first again (each seen by its own camera). The bodies' ratio,
  // or the still world's when the camera moves and jumps back further than it moves per frame.
  if (frames >= 3) {
    check.seam_step_ratio = step_ratio(screen_step(previous, first), median(steps));
    if (view.moves())
      check.seam_step_ratio =
          std::max(check.seam_step_ratio,
                   step_ratio(background_step(view.at(frames - 1), view.at(0)), median(background_steps)));
  }
  return check;
}

void add_overlap_measures(StimulusCheck& check, const std::vector<double>& overlap_fractions) {
  if (overlap_fractions.empty()) return;
  double with = 0.0, sum = 0.0;
  for (double x : overlap_fractions) {
    with += x > 0.0 ? 1.0 : 0.0;
    sum += x;
  }
  const double n = static_cast<double>(overlap_fractions.size());
  check.overlap_frame_share = with / n;
  check.overlap_pixel_fraction = sum / n;
}

std::vector<std::string> stimulus_check_failures(const StimulusCheck& c, const StimulusCheckSpec& limits,
                                                 const ClipRole& role) {
  std::vector<std::string> out;
  if (c.crowd_in_frame_min >= 0.0 && c.crowd_in_frame_min < limits.crowd_in_frame_min)
    out.push_back(
        fmt::format("crowd in frame {:.3f} < {:.3f}", c.crowd_in_frame_min, limits.crowd_in_frame_min));
  const double scale = role.image_height / 1080.0;
  const double height_min = scale * (role.viewpoint == ViewpointId::V4 ? limits.overhead_height_px_min
                                                                       : limits.character_height_px_min);
  if (c.character_height_px >= 0.0 && c.character_height_px < height_min)
    out.push_back(fmt::format("character height {:.0f} px < {:.0f} px", c.character_height_px, height_min));
  if (role.loops && c.seam_step_ratio >= 0.0 && c.seam_step_ratio > limits.seam_step_ratio_max)
    out.push_back(fmt::format("loop seam {:.2f}x > {:.2f}x the median frame step", c.seam_step_ratio,
                              limits.seam_step_ratio_max));
  if (role.baseline && limits.baseline_overlap_frames_min > 0.0 && c.overlap_frame_share >= 0.0 &&
      c.overlap_frame_share < limits.baseline_overlap_frames_min)
    out.push_back(fmt::format("baseline overlap in {:.2f} of frames < {:.2f}", c.overlap_frame_share,
                              limits.baseline_overlap_frames_min));
  return out;
}

nlohmann::json stimulus_check_json(const StimulusCheck& c) {
  auto value = [](double v) { return v >= 0.0 ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"crowd_in_frame_min", value(c.crowd_in_frame_min)},
          {"character_height_px", value(c.character_height_px)},
          {"overlap_frame_share", value(c.overlap_frame_share)},
          {"overlap_pixel_fraction", value(c.overlap_pixel_fraction)},
          {"seam_step_ratio", value(c.seam_step_ratio)}};
}

StimulusCheck stimulus_check_from_json(const nlohmann::json& j) {
  auto read = [&](const char* key) {
    const auto it = j.find(key);
    return it != j.end() && it->is_number() ? it->get<double>() : -1.0;
  };
  StimulusCheck c;
  c.crowd_in_frame_min = read("crowd_in_frame_min");
  c.character_height_px = read("character_height_px");
  c.overlap_frame_share = read("overlap_frame_share");
  c.overlap_pixel_fraction = read("overlap_pixel_fraction");
  c.seam_step_ratio = read("seam_step_ratio");
  return c;
}

}  // namespace crowdlab::stimuli
