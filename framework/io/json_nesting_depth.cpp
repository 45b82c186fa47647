#include "framework/io/json_nesting_depth.hpp"

namespace crowdlab {
namespace {

struct NestingScan {
  std::size_t deepest = 0;
  std::size_t exceeded_at = std::string_view::npos;  ///< where depth first passed stop_at
};

NestingScan scan_nesting(std::string_view json, std::size_t stop_at) {
  NestingScan scan;
  std::size_t depth = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (in_string) {
      if (c == '\\')
        ++i;  // the escaped character cannot end the string
      else if (c == '"')
        in_string = false;
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > scan.deepest) scan.deepest = depth;
      if (scan.deepest > stop_at) {
        scan.exceeded_at = i;
        return scan;
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return scan;
}

}  // namespace

std::size_t json_nesting_depth(std::string_view json, std::size_t stop_at) {
  return scan_nesting(json, stop_at).deepest;
}

std::size_t json_nesting_exceeded_at(std::string_view json, std::size_t limit) {
  return scan_nesting(json, limit).exceeded_at;
}

}  // namespace crowdlab
