#include "framework/correction/loop_closure_excerpt.hpp"

#include <algorithm>

namespace crowdlab {

ClosureExcerpt ClosureExcerpt::of(int frames, int head_frames, int tail_frames, int margin) {
  const int head = head_frames + margin, tail_begin = frames - tail_frames - margin;
  return head < tail_begin ? ClosureExcerpt{frames, head, tail_begin}
                           : ClosureExcerpt{frames, frames, frames};
}

CrowdAnimation ClosureExcerpt::cut(const CrowdAnimation& clip) const {
  CrowdAnimation excerpt;
  excerpt.environment = clip.environment;
  excerpt.meta = clip.meta;
  excerpt.characters.reserve(clip.characters.size());
  for (const CharacterAnimation& c : clip.characters) {
    CharacterAnimation& e = excerpt.characters.emplace_back(c);  // one character's frames at a time
    e.frames.erase(e.frames.begin() + head, e.frames.begin() + tail_begin);
  }
  return excerpt;
}

void ClosureExcerpt::put_back(const CharacterAnimation& excerpt, CharacterAnimation& clip) const {
  std::copy(excerpt.frames.begin(), excerpt.frames.begin() + head, clip.frames.begin());
  std::copy(excerpt.frames.begin() + head, excerpt.frames.end(), clip.frames.begin() + tail_begin);
}

}  // namespace crowdlab
