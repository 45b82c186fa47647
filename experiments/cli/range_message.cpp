#include "experiments/cli/range_message.hpp"

#include <cstdio>
#include <cstdlib>
#include <limits>
#include <regex>

namespace crowdlab::cli {

namespace {

/// Shortest text that reads back as `v` (at most 17 significant digits).
std::string shortest(double v) {
  char buf[32];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(buf, sizeof buf, "%.*g", digits, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

}  // namespace

std::optional<std::string> readable_range_message(const std::string& message) {
  static const std::regex kRange(R"(^(.*)Value (.*) not in range (\S+) to (\S+)\s*$)");
  std::smatch m;
  if (!std::regex_match(message, m, kRange)) return std::nullopt;
  const std::string option = m[1], value = m[2];
  const double lo = std::strtod(m[3].str().c_str(), nullptr), hi = std::strtod(m[4].str().c_str(), nullptr);
  const bool unbounded = hi >= std::numeric_limits<double>::max() * 0.999;
  // std::to_string printed the lower limit with 6 decimals: the smallest positive double (PositiveNumber)
  // and 1e-12 read as 0.000000, like a limit of 0 itself.
  const bool tiny_lower = lo == 0.0 && m[3].str().find('.') != std::string::npos;
  char* end = nullptr;
  const double got = std::strtod(value.c_str(), &end);
  const bool got_zero = end != value.c_str() && *end == '\0' && got == 0.0;
  std::string rule;
  if (tiny_lower && unbounded)
    rule = got_zero ? "must be a positive number" : "must not be negative";
  else if (tiny_lower)
    rule = std::string(got_zero ? "must be greater than 0" : "must not be negative") + " and at most " +
           shortest(hi);
  else if (unbounded)
    rule = "must be at least " + shortest(lo);
  else
    rule = "must be between " + shortest(lo) + " and " + shortest(hi);
  return option + rule + ", got '" + value + "'";
}

}  // namespace crowdlab::cli
