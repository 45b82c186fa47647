#include "framework/spec/yaml_flow_nesting.hpp"

#include <string>

namespace crowdlab {
namespace {

bool blank_before(std::string_view s, std::size_t i) {
  return i == 0 || s[i - 1] == ' ' || s[i - 1] == '\t' || s[i - 1] == '\n' || s[i - 1] == '\r';
}

// Whether a node (a quoted scalar, a flow collection) can start at `i`: after white space, or after a
// flow indicator or `:` (JSON-style `{"a":[1]}`). Inside a word (`don't`, `a[1]`) it cannot.
bool node_can_start(std::string_view s, std::size_t i) {
  if (blank_before(s, i)) return true;
  const char p = s[i - 1];
  return p == '[' || p == '{' || p == ',' || p == ':';
}

// Index of the quote that closes the scalar opened by the quote at `open` (YAML 1.2 §7.3: '' escapes a
// single quote, a backslash escapes in double quotes), or the text's size when it is not closed.
std::size_t closing_quote(std::string_view s, std::size_t open) {
  const char quote = s[open];
  for (std::size_t i = open + 1; i < s.size(); ++i) {
    if (quote == '"' && s[i] == '\\') {
      ++i;
    } else if (s[i] == quote) {
      if (quote == '\'' && i + 1 < s.size() && s[i + 1] == '\'') {
        ++i;
        continue;
      }
      return i;
    }
  }
  return s.size();
}

}  // namespace

std::size_t deep_flow_nesting_start(std::string_view s, std::size_t depth) {
  std::size_t level = 0, outermost = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '#' && blank_before(s, i)) {
      while (i < s.size() && s[i] != '\n') ++i;
    } else if ((c == '\'' || c == '"') && node_can_start(s, i)) {
      i = closing_quote(s, i);
    } else if ((c == '[' || c == '{') && (level > 0 || node_can_start(s, i))) {
      // (inside a flow collection every bracket counts: a plain scalar there cannot hold one)
      if (level++ == 0) outermost = i;
      if (level > depth) return outermost;
    } else if ((c == ']' || c == '}') && level > 0) {
      --level;
    }
  }
  return std::string_view::npos;
}

}  // namespace crowdlab
