#pragma once
// The parent of every node of a glTF model, checked to form the disjoint strict trees glTF 2.0 §3.5.3
// requires ("no node may be a direct descendant of more than one node", no cycles). Readers that walk
// the hierarchy up or down rely on this: a cycle made the motion importer loop for ever, and a fuzzed
// 100,000-node parent->child chain overflowed its recursive walk (issue 21). One linear pass, no
// recursion. Input: the model; output: parents[i] (-1 for a root).
#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace crowdlab {

/// Throws InputError "<context>: nodes[i]: ..." for a child index out of range, a node with two
/// parents, and a node that is its own ancestor.
std::vector<int> gltf_node_parents(const tinygltf::Model& model, const std::string& context);

}  // namespace crowdlab
