#include "stimuli/viewpoint.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "framework/core/error.hpp"

namespace crowdlab::stimuli {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kFrameFill = 0.92;  // the binding image dimension keeps a 4 % margin on each side

Vec3 horizontal(const Vec3& v) {
  return Vec3(v.x(), 0.0, v.z());
}

struct Preset {
  double azimuth_deg, elevation_deg, fov_deg;
};

/// Camera axes for a view from the direction (azimuth about +Y from `front`, elevation above the
/// horizontal): to_eye points from the target to the eye; r, u, f are right, up and forward.
struct ViewAxes {
  Vec3 to_eye, r, u, f;
};

ViewAxes view_axes(const Vec3& front, const Preset& preset) {
  const double az = preset.azimuth_deg * kDeg, el = preset.elevation_deg * kDeg;
  const Vec3 side = Vec3::UnitY().cross(front).normalized();  // any horizontal perpendicular
  const Vec3 horiz = std::cos(az) * front + std::sin(az) * side;
  ViewAxes a;
  a.to_eye = (std::cos(el) * horiz + std::sin(el) * Vec3::UnitY()).normalized();
  a.f = -a.to_eye;
  const Vec3 up_hint = std::abs(a.f.y()) > 0.999 ? Vec3::UnitZ() : Vec3::UnitY();  // as Camera::view()
  a.r = a.f.cross(up_hint).normalized();
  a.u = a.r.cross(a.f);
  return a;
}

/// The projected box of `corners` seen from target + to_eye * d: centre offset and half extents in
/// normalised image coordinates ([-1, 1] spans the image).
struct Projection {
  double cx = 0, cy = 0, half_x = 0, half_y = 0;
};

Projection project_box(const std::array<Vec3, 8>& corners, const Vec3& target, double d, const ViewAxes& a,
                       double tan_x, double tan_y) {
  double x0 = 1e30, x1 = -1e30, y0 = 1e30, y1 = -1e30;
  for (const Vec3& c : corners) {
    const Vec3 q = c - (target + a.to_eye * d);
    const double depth = q.dot(a.f);
    const double x = q.dot(a.r) / (depth * tan_x), y = q.dot(a.u) / (depth * tan_y);
    x0 = std::min(x0, x);
    x1 = std::max(x1, x);
    y0 = std::min(y0, y);
    y1 = std::max(y1, y);
  }
  return {0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (x1 - x0), 0.5 * (y1 - y0)};
}

/// Camera looking along `a` at the box [lo, hi] so that the box projects centred and fills kFrameFill of
/// the image width or height, whichever binds (see the framing rule in viewpoint.hpp).
Camera fit_box(const Vec3& lo, const Vec3& hi, const ViewAxes& a, double fov_deg, int width, int height) {
  std::array<Vec3, 8> corners;
  for (int c = 0; c < 8; ++c)
    corners[static_cast<size_t>(c)] =
        Vec3((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
  const double tan_y = std::tan(0.5 * fov_deg * kDeg), tan_x = tan_y * width / height;
  Vec3 target = 0.5 * (lo + hi);
  double d = 1.0;
  // Alternate: the distance that gives the fill (bisection: the projection shrinks as d grows once
  // every corner is in front of the eye), then move the target so the projected box is centred.
  for (int iteration = 0; iteration < 30; ++iteration) {
    double nearest = 1e30;  // smallest d that keeps every corner 5 cm in front of the eye
    for (const Vec3& c : corners) nearest = std::min(nearest, (c - target).dot(a.to_eye));
    double d_lo = std::max(nearest, 0.0) + 0.05, d_hi = d_lo + 1.0;
    auto fill = [&](double dist) {
      const Projection p = project_box(corners, target, dist, a, tan_x, tan_y);
      return std::max(p.half_x, p.half_y);
    };
    while (fill(d_hi) > kFrameFill) d_hi *= 2.0;
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (d_lo + d_hi);
      (fill(mid) > kFrameFill ? d_lo : d_hi) = mid;
    }
    d = d_hi;
    const Projection p = project_box(corners, target, d, a, tan_x, tan_y);
    if (std::abs(p.cx) < 1e-6 && std::abs(p.cy) < 1e-6) break;
    target += a.r * (p.cx * tan_x * d) + a.u * (p.cy * tan_y * d);
  }
  double near_depth = 1e30, far_depth = 0.0;
  for (const Vec3& c : corners) {
    const double depth = (c - target).dot(a.f) + d;
    near_depth = std::min(near_depth, depth);
    far_depth = std::max(far_depth, depth);
  }
  Camera cam;
  cam.eye = target + a.to_eye * d;
  cam.target = target;
  cam.fov_y_deg = fov_deg;
  cam.near_m = std::clamp(0.5 * near_depth, 0.02, 5.0);
  cam.far_m = far_depth + 150.0;
  cam.width = width;
  cam.height = height;
  return cam;
}

/// The catalogue's preset (framework/core/viewpoint_catalogue.hpp) as this file's Preset.
Preset preset_of(ViewpointId id) {
  const ViewpointPreset& p = viewpoint_preset(id);
  return Preset{p.azimuth_deg, p.elevation_deg, p.fov_deg};
}

}  // namespace

Viewpoint::Viewpoint(ViewpointId id, const CrowdAnimation& crowd, int width, int height,
                     const ViewpointOverrides& overrides)
    : Viewpoint(id, crowd_extent(character_tracks(crowd), crowd.meta.fps), width, height, overrides) {}

Viewpoint Viewpoint::placed(std::string name, const CameraPlacement& placement, int width, int height) {
  Viewpoint v;
  v.name_ = std::move(name);
  v.place(placement, width, height);
  return v;
}

void Viewpoint::place(const CameraPlacement& v, int width, int height) {
  if (width <= 0 || height <= 0) throw InputError("viewpoint: image size must be positive");
  if (const std::string problem = camera_placement_problem(v); !problem.empty())
    throw std::logic_error("viewpoint " + name_ + ": an unchecked camera placement (" + problem + ")");
  fixed_.eye = Vec3(v[0], v[1], v[2]);
  fixed_.target = Vec3(v[3], v[4], v[5]);
  fixed_.fov_y_deg = v[6];
  fixed_.near_m = 0.1;
  fixed_.far_m = (fixed_.eye - fixed_.target).norm() + 200.0;
  fixed_.width = width;
  fixed_.height = height;
}

Viewpoint::Viewpoint(ViewpointId id, const CrowdExtent& extent, int width, int height,
                     const ViewpointOverrides& overrides)
    : name_(viewpoint_name(id)) {
  if (width <= 0 || height <= 0) throw InputError("viewpoint: image size must be positive");
  if (const auto placed_at = overrides.find(id); placed_at != overrides.end()) {
    place(placed_at->second, width, height);
    return;
  }
  const Preset preset = preset_of(id);
  if (id == ViewpointId::pair) {
    // Look across the walking axis so the two paths run diagonally through the image.
    const Vec3 across = Vec3::UnitY().cross(extent.walk_axis).normalized();
    fixed_ = fit_box(extent.lo_m, extent.hi_m, view_axes(across, preset), preset.fov_deg, width, height);
  } else if (id == ViewpointId::tracking) {
    tracking_ = true;
    const std::vector<Vec3>& feet = extent.focal_feet_m;
    const int n = static_cast<int>(feet.size());
    const int half_window = std::max(1, static_cast<int>(std::lround(0.5 * extent.fps)));
    focal_path_.resize(feet.size());
    for (int f = 0; f < n; ++f) {
      Vec3 sum = Vec3::Zero();
      const int a = std::max(0, f - half_window), b = std::min(n - 1, f + half_window);
      for (int g = a; g <= b; ++g) sum += feet[static_cast<size_t>(g)];
      focal_path_[static_cast<size_t>(f)] = sum / (b - a + 1);
    }
    Vec3 travel = horizontal(feet.back() - feet.front());
    if (travel.norm() < 0.5) travel = extent.focal_forward;
    const double distance_m = 6.0;  // behind-above the focal character
    tracking_offset_ = view_axes(-travel.normalized(), preset).to_eye * distance_m;
    fixed_.fov_y_deg = preset.fov_deg;
    fixed_.near_m = 0.3;
    fixed_.far_m = 200.0;
    fixed_.width = width;
    fixed_.height = height;
  } else if (!extent.follow_path_m.empty()) {
    // A travelling crowd: frame its box relative to the follow path, then ride along that path.
    fixed_ = fit_box(extent.follow_lo_m, extent.follow_hi_m, view_axes(extent.front, preset), preset.fov_deg,
                     width, height);
    if (id == ViewpointId::V4) {
      // From overhead, turned a quarter about the vertical when that frames the crowd closer: seen from
      // its front, a corridor's crowd (long along its walk) ran along the image's short side and left
      // two thirds of a 16:9 frame to the floor (issue 28, session 24: walkers 56-70 px at 1080p). A crowd
      // that stays put keeps seed 000's orientation (the concert's stage at the top of the image).
      Preset turned = preset;
      turned.azimuth_deg += 90.0;
      const Camera side = fit_box(extent.follow_lo_m, extent.follow_hi_m, view_axes(extent.front, turned),
                                  preset.fov_deg, width, height);
      if ((side.eye - side.target).norm() < (fixed_.eye - fixed_.target).norm()) fixed_ = side;
    }
    follow_path_ = extent.follow_path_m;
  } else {
    fixed_ =
        fit_box(extent.lo_m, extent.hi_m, view_axes(extent.front, preset), preset.fov_deg, width, height);
  }
}

Camera Viewpoint::at(int frame) const {
  if (!follow_path_.empty()) {
    Camera cam = fixed_;
    const Vec3& offset =
        follow_path_[static_cast<size_t>(std::clamp(frame, 0, static_cast<int>(follow_path_.size()) - 1))];
    cam.eye += offset;
    cam.target += offset;
    return cam;
  }
  if (!tracking_) return fixed_;
  Camera cam = fixed_;
  const size_t f = static_cast<size_t>(std::clamp(frame, 0, static_cast<int>(focal_path_.size()) - 1));
  cam.target = focal_path_[f] + Vec3(0.0, 0.9, 0.0);  // about the pelvis
  cam.eye = cam.target + tracking_offset_;
  return cam;
}

}  // namespace crowdlab::stimuli
