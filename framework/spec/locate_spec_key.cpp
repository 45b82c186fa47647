#include "framework/spec/locate_spec_key.hpp"

#include <yaml-cpp/yaml.h>

#include <optional>
#include <sstream>
#include <stdexcept>

namespace crowdlab {

SourceLocation locate_spec_key(const std::string& spec_path, const std::string& key_path) {
  SourceLocation where{spec_path, 0, 0, key_path};
  try {
    YAML::Node node = YAML::LoadFile(spec_path);  // the spec was loaded (and its size checked) before
    std::stringstream keys(key_path);
    for (std::string key; std::getline(keys, key, '.');) {
      // "dance_clips[2]": the key, then the list item (a referenced file's place, issue 33).
      std::optional<std::size_t> index;
      if (const auto open = key.find('['); open != std::string::npos && key.back() == ']') {
        index = std::stoul(key.substr(open + 1, key.size() - open - 2));
        key.resize(open);
      }
      if (!node.IsMap()) return where;
      const YAML::Node& map = node;  // const: a lookup must not insert the key
      const YAML::Node next = map[key];
      if (!next.IsDefined()) return where;
      node.reset(next);  // rebinds (operator= would assign through to the parent's value)
      if (index) {
        if (!node.IsSequence() || *index >= node.size()) return where;
        const YAML::Node& list = node;
        const YAML::Node item = list[*index];
        node.reset(item);
      }
    }
    where.line = node.Mark().line + 1;  // yaml-cpp's Mark is 0-based
    where.column = node.Mark().column + 1;
  } catch (const YAML::Exception&) {
    // The file changed since it was loaded: the message still names the file and the key.
  } catch (const std::logic_error&) {
    // A list index in key_path that is not a number (std::stoul): the file and the key still name it.
  }
  return where;
}

}  // namespace crowdlab
