#include "stimuli/viewpoint.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kBodyMarginM = 0.4;  // half a shoulder width plus arm reach around each root
constexpr double kFrameFill = 0.92;   // 8 % margin inside the image

struct Preset {
  double azimuth_deg, elevation_deg, fov_deg;
};

struct CrowdFrame {
  Vec3 lo, hi;                     ///< bounding box (metres)
  Vec3 front = Vec3::UnitZ();      ///< unit, horizontal
  Vec3 walk_axis = Vec3::UnitX();  ///< principal horizontal direction of root motion (unit)
};

Vec3 horizontal(const Vec3& v) {
  return Vec3(v.x(), 0.0, v.z());
}

CrowdFrame crowd_frame(const CrowdAnimation& crowd) {
  CrowdFrame cf;
  cf.lo = Vec3::Constant(1e30);
  cf.hi = Vec3::Constant(-1e30);
  Vec3 forward_sum = Vec3::Zero();
  double tallest = 0.0;
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const CharacterAnimation& c : crowd.characters) {
    tallest = std::max(tallest, c.shape.params.height_m);
    if (c.frames.empty()) continue;
    const Vec3 first = c.frames.front().root_position_m;
    for (const Pose& p : c.frames) {
      cf.lo = cf.lo.cwiseMin(p.root_position_m);
      cf.hi = cf.hi.cwiseMax(p.root_position_m);
      forward_sum += horizontal(p.local_rotations[kPelvis] * Vec3::UnitZ());
      const Eigen::Vector2d d(p.root_position_m.x() - first.x(), p.root_position_m.z() - first.z());
      scatter += d * d.transpose();
    }
  }
  if (cf.lo.x() > cf.hi.x()) throw InputError("viewpoint: the crowd has no frames to frame");
  cf.lo = Vec3(cf.lo.x() - kBodyMarginM, 0.0, cf.lo.z() - kBodyMarginM);
  cf.hi = Vec3(cf.hi.x() + kBodyMarginM, std::max(tallest, 1.0) + 0.05, cf.hi.z() + kBodyMarginM);
  const double frames = static_cast<double>(crowd.frame_count() * crowd.characters.size());
  if (frames > 0 && forward_sum.norm() / frames >= 0.25) cf.front = forward_sum.normalized();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(scatter);
  if (eig.info() == Eigen::Success && eig.eigenvalues()(1) > 1e-9) {
    const Eigen::Vector2d a = eig.eigenvectors().col(1);
    cf.walk_axis = Vec3(a.x(), 0.0, a.y()).normalized();
  }
  return cf;
}

/// Camera looking at the box centre from the direction (azimuth about +Y from `front`, elevation),
/// at the distance that puts all eight box corners inside the frame.
Camera fit_box(const Vec3& lo, const Vec3& hi, const Vec3& front, const Preset& preset, int width,
               int height) {
  const Vec3 target = 0.5 * (lo + hi);
  const double az = preset.azimuth_deg * kDeg, el = preset.elevation_deg * kDeg;
  const Vec3 side = Vec3::UnitY().cross(front).normalized();  // front x up... any horizontal perpendicular
  const Vec3 horiz = std::cos(az) * front + std::sin(az) * side;
  const Vec3 to_eye = (std::cos(el) * horiz + std::sin(el) * Vec3::UnitY()).normalized();
  const Vec3 f = -to_eye;
  const Vec3 up_hint = std::abs(f.y()) > 0.999 ? Vec3::UnitZ() : Vec3::UnitY();
  const Vec3 r = f.cross(up_hint).normalized();
  const Vec3 u = r.cross(f);
  const double ty = std::tan(0.5 * preset.fov_deg * kDeg) * kFrameFill;
  const double tx = ty * width / height;
  double d = 1.0, near_depth = 1e30, far_depth = 0.0;
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
    const Vec3 q = corner - target;
    d = std::max({d, std::abs(q.dot(r)) / tx - q.dot(f), std::abs(q.dot(u)) / ty - q.dot(f)});
  }
  for (int c = 0; c < 8; ++c) {
    const Vec3 corner((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
    const double depth = d + (corner - target).dot(f);
    near_depth = std::min(near_depth, depth);
    far_depth = std::max(far_depth, depth);
  }
  Camera cam;
  cam.eye = target + to_eye * d;
  cam.target = target;
  cam.fov_y_deg = preset.fov_deg;
  cam.near_m = std::clamp(0.5 * near_depth, 0.1, 5.0);
  cam.far_m = far_depth + 150.0;
  cam.width = width;
  cam.height = height;
  return cam;
}

const std::map<std::string, Preset>& presets() {
  static const std::map<std::string, Preset> table = {
      {"V1", {0.0, 6.0, 40.0}},  {"V2", {0.0, 30.0, 40.0}},    {"V3", {45.0, 15.0, 40.0}},
      {"V4", {0.0, 80.0, 40.0}}, {"pair", {45.0, 30.0, 35.0}}, {"tracking", {30.0, 25.0, 45.0}},
  };
  return table;
}

}  // namespace

const std::vector<std::string>& viewpoint_names() {
  static const std::vector<std::string> names = {"V1", "V2", "V3", "V4", "pair", "tracking"};
  return names;
}

Viewpoint::Viewpoint(const std::string& name, const CrowdAnimation& crowd, int width, int height,
                     const ViewpointOverrides& overrides)
    : name_(name) {
  if (width <= 0 || height <= 0) throw InputError("viewpoint: image size must be positive");
  const auto preset_it = presets().find(name);
  const auto override_it = overrides.find(name);
  if (preset_it == presets().end() && override_it == overrides.end()) {
    std::string known;
    for (const auto& n : viewpoint_names()) known += (known.empty() ? "" : ", ") + n;
    throw InputError("unknown viewpoint '" + name + "' (known: " + known +
                     ", or one named in render.viewpoint_overrides)");
  }
  if (override_it != overrides.end()) {
    const std::vector<double>& v = override_it->second;
    const std::string where = "render.viewpoint_overrides." + name;
    if (v.size() != 7)
      throw InputError(where + ": expected [px,py,pz,tx,ty,tz,fov_deg] (7 numbers), got " +
                       std::to_string(v.size()));
    for (double x : v)
      if (!std::isfinite(x)) throw InputError(where + ": values must be finite");
    if (!(v[6] > 1.0 && v[6] < 170.0)) throw InputError(where + ": fov_deg must be in (1, 170)");
    fixed_.eye = Vec3(v[0], v[1], v[2]);
    fixed_.target = Vec3(v[3], v[4], v[5]);
    if ((fixed_.eye - fixed_.target).norm() < 1e-6)
      throw InputError(where + ": camera position equals target");
    fixed_.fov_y_deg = v[6];
    fixed_.near_m = 0.1;
    fixed_.far_m = (fixed_.eye - fixed_.target).norm() + 200.0;
    fixed_.width = width;
    fixed_.height = height;
    return;
  }
  const CrowdFrame cf = crowd_frame(crowd);
  const Preset& preset = preset_it->second;
  if (name == "pair") {
    // Look across the walking axis so the two paths run diagonally through the image.
    const Vec3 across = Vec3::UnitY().cross(cf.walk_axis).normalized();
    fixed_ = fit_box(cf.lo, cf.hi, across, preset, width, height);
  } else if (name == "tracking") {
    tracking_ = true;
    size_t focal = 0;
    for (size_t i = 0; i < crowd.characters.size(); ++i)
      if (crowd.characters[i].name == "c000") focal = i;
    const std::vector<Pose>& frames = crowd.characters.at(focal).frames;
    const int n = static_cast<int>(frames.size());
    const int half_window = std::max(1, static_cast<int>(std::lround(0.5 * crowd.meta.fps)));
    focal_path_.resize(frames.size());
    for (int f = 0; f < n; ++f) {
      Vec3 sum = Vec3::Zero();
      const int a = std::max(0, f - half_window), b = std::min(n - 1, f + half_window);
      for (int g = a; g <= b; ++g) sum += frames[static_cast<size_t>(g)].root_position_m;
      focal_path_[static_cast<size_t>(f)] = sum / (b - a + 1);
    }
    Vec3 travel = horizontal(frames.back().root_position_m - frames.front().root_position_m);
    if (travel.norm() < 0.5) travel = horizontal(frames.front().local_rotations[kPelvis] * Vec3::UnitZ());
    const Vec3 behind = -travel.normalized();
    const Vec3 lo(-0.5, 0.0, -0.5), hi(0.5, 1.9, 0.5);
    fixed_ = fit_box(lo, hi, behind, preset, width, height);
    const double distance = 6.0;  // metres behind-above the focal character
    const Vec3 dir = (fixed_.eye - fixed_.target).normalized();
    tracking_offset_ = dir * distance;
    fixed_.near_m = 0.3;
    fixed_.far_m = 200.0;
  } else {
    fixed_ = fit_box(cf.lo, cf.hi, cf.front, preset, width, height);
  }
}

Camera Viewpoint::at(int frame) const {
  if (!tracking_) return fixed_;
  Camera cam = fixed_;
  const size_t f = static_cast<size_t>(std::clamp(frame, 0, static_cast<int>(focal_path_.size()) - 1));
  cam.target = Vec3(focal_path_[f].x(), 0.9, focal_path_[f].z());
  cam.eye = cam.target + tracking_offset_;
  return cam;
}

}  // namespace crowdlab::stimuli
