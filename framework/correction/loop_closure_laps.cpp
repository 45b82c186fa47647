#include "framework/correction/loop_closure_laps.hpp"

#include <algorithm>

#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

void frame_targets(const CrowdAnimation& crowd, int f, std::vector<Pose>& targets) {
  for (size_t c = 0; c < targets.size(); ++c) targets[c] = crowd.characters[c].frames[static_cast<size_t>(f)];
}

NextLap::NextLap(Corrector after_clip, const CrowdAnimation& input, int window, Progress* progress)
    : corrector_(std::move(after_clip)),
      input_(&input),
      window_(window),
      progress_(progress),
      poses_(input.characters.size()) {}

std::vector<std::vector<Pose>> NextLap::first(int frames) {
  std::vector<Pose> targets(poses_.size());
  const int before_window = input_->frame_count() - window_ - 1;
  for (int f = stepped(); f < frames; ++f) {
    frame_targets(*input_, f, targets);
    const std::vector<Pose> corrected = corrector_.step(targets);
    for (size_t c = 0; c < poses_.size(); ++c) poses_[c].push_back(corrected[c]);
    if (window_ > 0 && f == before_window) before_window_ = corrector_;
    const StepStats& st = corrector_.last_stats();
    contacts_ += st.contacts();
    iterations_ += st.cg_iterations;
    if (st.rejected) ++rejected_;
    if (!st.converged) ++unconverged_;
    if (progress_) progress_->advance();
  }
  std::vector<std::vector<Pose>> lap = poses_;
  for (std::vector<Pose>& p : lap) p.resize(static_cast<size_t>(frames));
  return lap;
}

RecordedLap NextLap::record() && {
  const int frames = input_->frame_count();
  first(frames);
  CrowdAnimation clip = *input_;
  for (size_t c = 0; c < clip.characters.size(); ++c) clip.characters[c].frames = std::move(poses_[c]);
  return RecordedLap{std::move(clip),
                     std::move(before_window_),
                     std::move(corrector_),
                     rejected_,
                     unconverged_,
                     frames > 0 ? contacts_ / frames : 0.0,
                     frames > 0 ? iterations_ / frames : 0.0};
}

namespace {

/// The mean distance (m) of every joint of every character between frames a and b.
double mean_joint_step_m(const std::vector<std::vector<std::vector<Vec3>>>& joints, size_t a, size_t b) {
  double sum = 0.0;
  size_t count = 0;
  for (const auto& character : joints)
    for (size_t j = 0; j < character[a].size(); ++j, ++count)
      sum += (character[a][j] - character[b][j]).norm();
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

}  // namespace

double world_seam_step_ratio(const CrowdAnimation& clip) {
  const auto frames = static_cast<size_t>(clip.frame_count());
  if (frames < 3 || clip.characters.empty()) return 0.0;
  std::vector<std::vector<std::vector<Vec3>>> joints;  // joints[c][f][j]
  for (const CharacterAnimation& c : clip.characters) {
    auto& per_frame = joints.emplace_back();
    for (const Pose& p : c.frames) {
      const auto positions = joint_positions(c.shape, p);
      per_frame.emplace_back(positions.begin(), positions.end());
    }
  }
  std::vector<double> steps;
  for (size_t f = 1; f < frames; ++f) steps.push_back(mean_joint_step_m(joints, f - 1, f));
  const auto middle = steps.begin() + static_cast<long>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  return *middle > 0.0 ? mean_joint_step_m(joints, frames - 1, 0) / *middle : 0.0;
}

bool keep_extra_lap(const ClosedLap& kept, const ClosedLap& extra, double depth_floor_m) {
  return extra.seam_step_ratio < kept.seam_step_ratio &&
         extra.deepest_m <= std::max(kept.deepest_m, depth_floor_m);
}

}  // namespace crowdlab
