#include "experiments/cli/pipeline/job_script_text.hpp"

#include "framework/core/control_characters.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::cli {
namespace {

bool is_slurm_safe(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' || c == '_' ||
         c == '-';
}

}  // namespace

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string make_recipe_quote(const std::string& s) {
  std::string out;
  for (char c : shell_quote(s)) out += c == '$' ? std::string("$$") : std::string(1, c);
  return out;
}

std::string slurm_directive_word(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (is_slurm_safe(c))
      out += c;
    else if (out.empty() || out.back() != '_')
      out += '_';
  }
  return out;
}

std::string comment_text(const std::string& s) {
  std::string out = s;
  for (char& c : out)
    if (is_control_character(c)) c = '?';
  return out;
}

void require_script_safe(const std::string& value, const std::string& option) {
  if (const std::string bad = describe_control_character(value); !bad.empty())
    throw InputError(SourceLocation{"", 0, 0, option},
                     "holds " + bad + ", which a job script cannot carry safely; rename the path");
}

}  // namespace crowdlab::cli
