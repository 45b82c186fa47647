#include "framework/io/gltf_node_parents.hpp"

#include "framework/core/error.hpp"

namespace crowdlab {

std::vector<int> gltf_node_parents(const tinygltf::Model& model, const std::string& context) {
  const std::size_t n = model.nodes.size();
  const auto node = [](std::size_t i) { return "nodes[" + std::to_string(i) + "]"; };
  std::vector<int> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i)
    for (const int c : model.nodes[i].children) {
      if (c < 0 || static_cast<std::size_t>(c) >= n)
        throw InputError(context + ": " + node(i) + ": child index " + std::to_string(c) + " out of range (" +
                         std::to_string(n) + " nodes)");
      int& p = parent[static_cast<std::size_t>(c)];
      if (p >= 0)
        throw InputError(context + ": " + node(static_cast<std::size_t>(c)) + " is a child of both " +
                         node(static_cast<std::size_t>(p)) + " and " + node(i) +
                         " (glTF nodes form trees: one parent each)");
      p = static_cast<int>(i);
    }
  // With one parent each, a cycle is a walk upwards that comes back to a node of the same walk. Each
  // node is walked over once: a walk stops at a root or at a node an earlier walk has cleared.
  enum : char { kUnseen, kOnWalk, kCleared };
  std::vector<char> state(n, kUnseen);
  std::vector<std::size_t> walk;
  for (std::size_t start = 0; start < n; ++start) {
    walk.clear();
    for (int a = static_cast<int>(start); a >= 0 && state[static_cast<std::size_t>(a)] != kCleared;
         a = parent[static_cast<std::size_t>(a)]) {
      if (state[static_cast<std::size_t>(a)] == kOnWalk)
        throw InputError(context + ": " + node(static_cast<std::size_t>(a)) +
                         " is its own ancestor (the node hierarchy has a cycle)");
      state[static_cast<std::size_t>(a)] = kOnWalk;
      walk.push_back(static_cast<std::size_t>(a));
    }
    for (const std::size_t w : walk) state[w] = kCleared;
  }
  return parent;
}

}  // namespace crowdlab
