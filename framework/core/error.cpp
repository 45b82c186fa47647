#include "framework/core/error.hpp"

#include "framework/core/printable_excerpt.hpp"

namespace crowdlab {

std::string SourceLocation::prefix() const {
  // Built with append() rather than operator+ chains: GCC 12 at -O3 reports false array-bounds /
  // stringop-overflow warnings for the latter (GCC bugs 105329, 105651).
  std::string out;
  if (!file.empty()) {
    out.append(file);
    if (line > 0) {
      out.append(":").append(std::to_string(line));
      if (column > 0) out.append(":").append(std::to_string(column));
    }
    out.append(": ");
  }
  if (!key.empty()) out.append(key).append(": ");
  return out;
}

// Every message goes through message_excerpt(): values quoted from a user's file are cut and their
// control bytes escaped, whichever call site built the message (issue 33).
InputError::InputError(const std::string& message) : std::runtime_error(message_excerpt(message)) {}

InputError::InputError(SourceLocation where, const std::string& message)
    : std::runtime_error(message_excerpt(where.prefix() + message)), where_(std::move(where)) {}

}  // namespace crowdlab
