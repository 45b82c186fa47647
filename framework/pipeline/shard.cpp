#include "framework/pipeline/shard.hpp"

#include <charconv>

#include "framework/core/error.hpp"

namespace crowdlab {

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  Shard s;
  auto parse = [](std::string_view v, int& out) {
    auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
    return ec == std::errc() && p == v.data() + v.size();
  };
  if (slash == std::string::npos || !parse(std::string_view(text).substr(0, slash), s.index) ||
      !parse(std::string_view(text).substr(slash + 1), s.count) || s.count < 1 || s.index < 1 ||
      s.index > s.count)
    throw InputError(SourceLocation{"", 0, 0, "--shard"},
                     "expected K/N with 1 <= K <= N, got '" + text + "'");
  return s;
}

}  // namespace crowdlab
