#include "framework/core/error.hpp"

namespace crowdlab {

std::string SourceLocation::prefix() const {
  std::string out;
  if (!file.empty()) {
    out += file;
    if (line > 0) {
      out += ":" + std::to_string(line);
      if (column > 0) out += ":" + std::to_string(column);
    }
    out += ": ";
  }
  if (!key.empty()) out += key + ": ";
  return out;
}

InputError::InputError(const std::string& message) : std::runtime_error(message) {}

InputError::InputError(SourceLocation where, const std::string& message)
    : std::runtime_error(where.prefix() + message), where_(std::move(where)) {}

}  // namespace crowdlab
