#pragma once
// Typed errors, mapped to exit codes once, in the CLI's main():
//   InputError   -> exit 2 (bad spec, bad file, bad arguments: the user must change something)
//   RuntimeError -> exit 1 (a stage failed while running on valid input)
// Both carry a SourceLocation so messages read "file:line:column: key.path: message".
#include <stdexcept>
#include <string>

namespace crowdlab {

/// Where in an input file a problem was found. line/column are 1-based; 0 means unknown.
struct SourceLocation {
  std::string file;
  int line = 0;
  int column = 0;
  std::string key;  ///< dotted key path (YAML) or node/field name (glTF, BVH, CSV column)

  /// "file:line:column: key: " with absent parts omitted.
  std::string prefix() const;
};

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message);
  InputError(SourceLocation where, const std::string& message);
  const SourceLocation& where() const { return where_; }

 private:
  SourceLocation where_;
};

class RuntimeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace crowdlab
