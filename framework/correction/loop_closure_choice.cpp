#include "framework/correction/loop_closure_choice.hpp"

#include <algorithm>
#include <utility>

#include "framework/core/crowd_penetration_depth.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/penetration_depth.hpp"
#include "framework/correction/blend_keeping_planted_feet.hpp"

namespace crowdlab {
namespace {

/// The frames the descent's candidates may change, [0, min(start_window, first)) and [first, N), as one
/// span per candidate (the frames between, if any, are the unclosed clip's on every candidate).
std::vector<FrameSpan> descent_spans(size_t candidates, int frames, int first, int start_window) {
  return std::vector<FrameSpan>(candidates, {std::min(start_window, first) > 0 ? 0 : first, frames});
}

/// The descent: every character on candidate 0, each too deep moved on (after the last of the first
/// `rungs`: unclosed, index closures.size()), all at once, until none is too deep. Terminates, since
/// `unclosed` alone keeps every character within the limit.
std::vector<size_t> descend(const std::vector<const CrowdAnimation*>& closures, size_t rungs,
                            const CrowdAnimation& unclosed, int first, int start_window, double limit_m,
                            const std::vector<std::vector<bool>>& allowed) {
  const int frames = unclosed.frame_count();
  const size_t open = closures.size();
  // The first candidate from r on, among the first `rungs`, that the character may take; else unclosed.
  auto next_allowed = [&](size_t c, size_t r) {
    while (r < rungs && !allowed[r][c]) ++r;
    return r < rungs ? r : open;
  };
  CrowdAnimation mixed = unclosed;
  std::vector<size_t> rung(mixed.characters.size(), 0);
  for (size_t c = 0; c < rung.size(); ++c) {
    rung[c] = next_allowed(c, 0);
    if (rung[c] < open) mixed.characters[c].frames = closures[rung[c]]->characters[c].frames;
  }
  for (bool moved = true; moved;) {
    moved = false;
    std::vector<double> depth = deepest_per_character(mixed, first, frames);
    const int start = std::min(start_window, first);
    if (start > 0) {
      const std::vector<double> at_start = deepest_per_character(mixed, 0, start);
      for (size_t c = 0; c < depth.size(); ++c) depth[c] = std::max(depth[c], at_start[c]);
    }
    for (size_t c = 0; c < rung.size(); ++c) {
      if (rung[c] == open || depth[c] <= limit_m) continue;
      rung[c] = next_allowed(c, rung[c] + 1);
      mixed.characters[c].frames = (rung[c] < open ? closures[rung[c]] : &unclosed)->characters[c].frames;
      moved = true;
    }
  }
  return rung;
}

/// Mean joint distance (m) between a character's last and first frames: its share of the seam.
double seam_m(const CharacterAnimation& c) {
  const auto last = joint_positions(c.shape, c.frames.back()),
             first = joint_positions(c.shape, c.frames.front());
  double sum = 0.0;
  for (size_t j = 0; j < last.size(); ++j) sum += (last[j] - first[j]).norm();
  return sum / static_cast<double>(last.size());
}

/// The join (header, step 2), on every character with rung[c] == closures.size().
class Join {
 public:
  /// spans[r]: the frames candidate r changes (the unclosed clip is kept whole). Capsules only of the
  /// characters that may be on a candidate: those the descent left open, or put on it.
  Join(const std::vector<const CrowdAnimation*>& closures, const CrowdAnimation& unclosed,
       std::vector<FrameSpan> spans, double limit_m, const std::vector<std::vector<bool>>& allowed,
       const std::vector<size_t>& rung)
      : open_(closures.size()),
        n_(unclosed.characters.size()),
        limit_m_(limit_m),
        allowed_(allowed),
        spans_(std::move(spans)) {
    spans_.push_back({0, unclosed.frame_count()});
    capsules_.assign(open_ + 1, std::vector<std::vector<WorldCapsules>>(n_));
    for (size_t r = 0; r <= open_; ++r) {
      const CrowdAnimation& a = r < open_ ? *closures[r] : unclosed;
      for (size_t c = 0; c < n_; ++c)
        for (int f = spans_[r].begin; f < spans_[r].end && (r == open_ || rung[c] == open_ || rung[c] == r);
             ++f)
          capsules_[r][c].push_back(
              world_capsules(a.characters[c].shape, a.characters[c].frames[static_cast<size_t>(f)]));
    }
  }

  /// Why unclosed character c stays so (explain_open_characters).
  OpenCharacterReason explain(size_t c, const std::vector<size_t>& rung) const {
    OpenCharacterReason why{c, 0, open_, {}};
    double best_deepest = 0.0;
    for (size_t r = 0; r < open_; ++r) {
      if (!allowed_[r][c]) {
        ++why.excluded;
        continue;
      }
      std::vector<std::pair<size_t, double>> met;
      double deepest = 0.0;
      for (size_t o = 0; o < n_; ++o) {
        const double d = o == c ? 0.0 : depth_m(c, r, o, rung[o]);
        if (d <= limit_m_) continue;
        met.emplace_back(o, d);
        deepest = std::max(deepest, d);
      }
      if (why.best == open_ || met.size() < why.met.size() ||
          (met.size() == why.met.size() && deepest < best_deepest)) {
        why.best = r;
        why.met = std::move(met);
        best_deepest = deepest;
      }
    }
    return why;
  }

  /// Closes what it can of the unclosed characters, largest seam first.
  void run(const CrowdAnimation& unclosed, std::vector<size_t>& rung) const {
    std::vector<std::pair<double, size_t>> order;
    for (size_t c = 0; c < n_; ++c)
      if (rung[c] == open_) order.emplace_back(-seam_m(unclosed.characters[c]), c);
    std::sort(order.begin(), order.end());
    for (const auto& entry : order)
      for (size_t r = 0; r < open_ && rung[entry.second] == open_; ++r) try_close(entry.second, r, rung);
  }

 private:
  /// Character c's capsules on candidate r at frame f (the unclosed clip's outside r's span).
  const WorldCapsules& at(size_t c, size_t r, int f) const {
    const FrameSpan& s = spans_[r];
    return f >= s.begin && f < s.end ? capsules_[r][c][static_cast<size_t>(f - s.begin)]
                                     : capsules_[open_][c][static_cast<size_t>(f)];
  }

  /// Deepest penetration (m) of character c on candidate rc and o on ro over the frames either changes
  /// (c is on a candidate, rc < open_; elsewhere both are the unclosed clip, within the limit).
  double depth_m(size_t c, size_t rc, size_t o, size_t ro) const {
    int begin = spans_[rc].begin, end = spans_[rc].end;
    if (ro < open_) begin = std::min(begin, spans_[ro].begin), end = std::max(end, spans_[ro].end);
    double d = 0.0;
    for (int f = begin; f < end; ++f) d = std::max(d, max_penetration_depth(at(c, rc, f), at(o, ro, f)));
    return d;
  }

  /// c on candidate r, with the unclosed characters it meets too deeply there; kept if all of them are
  /// then within the limit against everyone.
  void try_close(size_t c, size_t r, std::vector<size_t>& rung) const {
    if (!allowed_[r][c]) return;
    std::vector<size_t> group = {c};
    for (size_t o = 0; o < n_; ++o) {
      if (o == c || depth_m(c, r, o, rung[o]) <= limit_m_) continue;
      if (rung[o] != open_ || !allowed_[r][o] || group.size() == kMaxJoinedCharacters) return;
      group.push_back(o);
    }
    for (size_t g : group) rung[g] = r;
    for (size_t g : group)
      for (size_t o = 0; o < n_; ++o)
        if (o != g && depth_m(g, r, o, rung[o]) > limit_m_) {
          for (size_t h : group) rung[h] = open_;
          return;
        }
  }

  size_t open_, n_;
  double limit_m_;
  const std::vector<std::vector<bool>>& allowed_;
  std::vector<FrameSpan> spans_;  ///< per candidate, then the unclosed clip's (every frame)
  std::vector<std::vector<std::vector<WorldCapsules>>> capsules_;  ///< [candidate][character][span frame]
};

/// The crowd with every character's frames in reverse order.
CrowdAnimation reversed(CrowdAnimation crowd) {
  for (CharacterAnimation& c : crowd.characters) std::reverse(c.frames.begin(), c.frames.end());
  return crowd;
}

}  // namespace

std::vector<double> deepest_per_character(const CrowdAnimation& crowd, int first, int last) {
  std::vector<double> depth(crowd.characters.size(), 0.0);
  std::vector<WorldCapsules> bodies(crowd.characters.size());
  for (int f = first; f < last; ++f) {
    for (size_t c = 0; c < bodies.size(); ++c)
      bodies[c] =
          world_capsules(crowd.characters[c].shape, crowd.characters[c].frames[static_cast<size_t>(f)]);
    const std::vector<double> now = deepest_penetration_per_body(bodies);
    for (size_t c = 0; c < bodies.size(); ++c) depth[c] = std::max(depth[c], now[c]);
  }
  return depth;
}

std::vector<size_t> descend_closures(const std::vector<const CrowdAnimation*>& closures, size_t descent_rungs,
                                     const CrowdAnimation& unclosed, int first, int start_window,
                                     double limit_m, const std::vector<std::vector<bool>>& allowed) {
  return descend(closures, std::min(descent_rungs, closures.size()), unclosed, first, start_window, limit_m,
                 allowed);
}

void join_closures(const std::vector<const CrowdAnimation*>& closures, const CrowdAnimation& unclosed,
                   double limit_m, const std::vector<std::vector<bool>>& allowed,
                   const std::vector<FrameSpan>& spans, std::vector<size_t>& rung) {
  Join(closures, unclosed, spans, limit_m, allowed, rung).run(unclosed, rung);
}

std::vector<OpenCharacterReason> explain_open_characters(const std::vector<const CrowdAnimation*>& closures,
                                                         const CrowdAnimation& unclosed, double limit_m,
                                                         const std::vector<std::vector<bool>>& allowed,
                                                         const std::vector<FrameSpan>& spans,
                                                         const std::vector<size_t>& rung) {
  const Join join(closures, unclosed, spans, limit_m, allowed, rung);
  std::vector<OpenCharacterReason> reasons;
  for (size_t c = 0; c < rung.size(); ++c)
    if (rung[c] == closures.size()) reasons.push_back(join.explain(c, rung));
  return reasons;
}

std::vector<size_t> choose_closures(const std::vector<const CrowdAnimation*>& closures, size_t descent_rungs,
                                    const CrowdAnimation& unclosed, int first, int start_window,
                                    double limit_m, const std::vector<std::vector<bool>>& allowed,
                                    const std::vector<FrameSpan>& spans) {
  std::vector<size_t> rung =
      descend_closures(closures, descent_rungs, unclosed, first, start_window, limit_m, allowed);
  join_closures(
      closures, unclosed, limit_m, allowed,
      spans.empty() ? descent_spans(closures.size(), unclosed.frame_count(), first, start_window) : spans,
      rung);
  return rung;
}

CrowdAnimation mix_closures(const std::vector<const CrowdAnimation*>& closures,
                            const CrowdAnimation& unclosed, const std::vector<size_t>& choice) {
  CrowdAnimation mixed = unclosed;
  for (size_t c = 0; c < mixed.characters.size(); ++c)
    if (choice[c] < closures.size()) mixed.characters[c].frames = closures[choice[c]]->characters[c].frames;
  return mixed;
}

CrowdAnimation start_from_next_lap(const CrowdAnimation& input,
                                   const std::vector<std::vector<Pose>>& next_start,
                                   const CorrectorParams& params, const CrowdAnimation& clip) {
  // Reversed in time, the clip's last W frames are its first W backwards, and next_start (reversed) is
  // what they blend into, its first pose on the reversed clip's last frame.
  std::vector<std::vector<Pose>> targets = next_start;
  for (std::vector<Pose>& t : targets) std::reverse(t.begin(), t.end());
  CrowdAnimation backwards = reversed(clip);
  blend_keeping_planted_feet(reversed(input), targets, static_cast<int>(targets.front().size()), params,
                             backwards);
  return reversed(std::move(backwards));
}

CrowdAnimation close_joints(const CrowdAnimation& clip, const std::vector<std::vector<Pose>>& lap_end,
                            std::span<const Joint> joints) {
  CrowdAnimation closed = clip;
  const int window = static_cast<int>(lap_end.front().size());
  for (size_t c = 0; c < closed.characters.size(); ++c)
    for (int k = 0, first = static_cast<int>(closed.characters[c].frames.size()) - window;
         first >= 0 && k < window; ++k) {
      const double w = raised_cosine(k + 1, window);
      auto& rotations = closed.characters[c].frames[static_cast<size_t>(first + k)].local_rotations;
      const auto& lap = lap_end[c][static_cast<size_t>(k)].local_rotations;
      for (Joint j : joints) {
        const auto i = static_cast<size_t>(j);
        rotations[i] = rotations[i].slerp(w, lap[i]).normalized();
      }
    }
  return closed;
}

CrowdAnimation cut_joints_from_next_lap(const CrowdAnimation& clip,
                                        const std::vector<std::vector<Pose>>& next_lap,
                                        std::span<const Joint> joints, int cut, int window) {
  CrowdAnimation mixed = clip;
  for (size_t c = 0; c < mixed.characters.size(); ++c)
    for (int f = 0; !mixed.characters[c].frames.empty() && f < cut + window; ++f) {
      // The clip's weight: 0 before the cut, rising over the window (1 only after it).
      const double w = f < cut ? 0.0 : raised_cosine(f - cut + 1, window + 1);
      auto& rotations = mixed.characters[c].frames[static_cast<size_t>(f)].local_rotations;
      const auto& next = next_lap[c][static_cast<size_t>(f)].local_rotations;
      for (Joint j : joints) {
        const auto i = static_cast<size_t>(j);
        rotations[i] = next[i].slerp(w, rotations[i]).normalized();
      }
    }
  return mixed;
}

}  // namespace crowdlab
