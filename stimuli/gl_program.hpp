#pragma once
// A linked GLSL program (RAII) with cached uniform locations. Requires a current GL context.
#include <string>
#include <unordered_map>

namespace crowdlab::stimuli {

class GlProgram {
 public:
  /// Compiles and links; throws RuntimeError with the driver's info log on failure.
  GlProgram(const char* vertex_source, const char* fragment_source, const std::string& name);
  ~GlProgram();
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  unsigned id() const { return id_; }
  /// Location of a uniform (-1 when the driver optimised it away, which GL treats as a no-op).
  int uniform(const char* name);

 private:
  unsigned id_ = 0;
  std::unordered_map<std::string, int> locations_;
};

}  // namespace crowdlab::stimuli
