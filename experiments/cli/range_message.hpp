#pragma once
// CLI11's range check prints its limits with std::to_string: PositiveNumber's limits are the smallest and
// largest doubles, so `--max-levels 0` printed "Value 0 not in range 0.000000 to 1797693134862315708...",
// 300 digits (issue 33), and Range(1e-12, 0.5) printed its lower limit as 0.000000. One rewrite, applied to
// every validation error in main(), states the limits as a person would.
#include <optional>
#include <string>

namespace crowdlab::cli {

/// For "<option>: Value V not in range A to B": "<option>: must be a positive number, got V" (A is the
/// smallest positive double), "<option>: must be at least A, got V" (B is the largest double), or
/// "<option>: must be between A and B, got V" with A and B in shortest form. nullopt for other messages.
std::optional<std::string> readable_range_message(const std::string& message);

}  // namespace crowdlab::cli
