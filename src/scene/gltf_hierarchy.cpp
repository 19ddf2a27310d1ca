// glTF 2.0 (section 3.5.3, "Transformations"/"Nodes"): the node hierarchy must be a set of
// disjoint strict trees: no node is listed twice, no node has two parents, no cycles, and a
// scene's root nodes have no parent. Walking anything else as a tree multiplies paths (a
// node shared by two parents at every level is 2^N paths from a kilobyte of JSON), so it is
// refused before the walk, naming the node; the walk itself then visits each node once.
#include <string>
#include <vector>

#include "scene/gltf_internal.hpp"

namespace penumbra {
namespace {

constexpr int kNoParent = -1;

std::string node_name(int index) { return "nodes[" + std::to_string(index) + "]"; }

// Each node's parent, refusing children that do not exist, that are their own parent or
// that have two parents (or are listed twice by one).
std::vector<int> parents_of(const GltfSource& source) {
    const std::vector<tinygltf::Node>& nodes = source.model.nodes;
    std::vector<int> parents(nodes.size(), kNoParent);
    for (size_t p = 0; p < nodes.size(); ++p) {
        const int parent = static_cast<int>(p);
        for (const int child : nodes[p].children) {
            if (child < 0 || static_cast<size_t>(child) >= nodes.size()) {
                source.fail(node_name(parent) + ".children", "node " + std::to_string(child) +
                                                                 " does not exist (the file has " +
                                                                 std::to_string(nodes.size()) + " nodes)");
            }
            if (child == parent) {
                source.fail(node_name(child), "node is its own child (the node hierarchy has a cycle)");
            }
            int& recorded = parents[static_cast<size_t>(child)];
            if (recorded == parent) {
                source.fail(node_name(parent) + ".children", "lists node " + std::to_string(child) + " twice");
            }
            if (recorded != kNoParent) {
                source.fail(node_name(child), "is a child of both " + node_name(recorded) + " and " +
                                                  node_name(parent) +
                                                  " (glTF requires each node to have at most one parent)");
            }
            recorded = parent;
        }
    }
    return parents;
}

// With one parent each, a cycle is a chain of parents that comes back to where it started.
void refuse_cycles(const GltfSource& source, const std::vector<int>& parents) {
    enum class State { Unvisited, OnChain, Done };
    std::vector<State> state(parents.size(), State::Unvisited);
    std::vector<int> chain;
    for (size_t start = 0; start < parents.size(); ++start) {
        chain.clear();
        int node = static_cast<int>(start);
        while (node != kNoParent && state[static_cast<size_t>(node)] == State::Unvisited) {
            state[static_cast<size_t>(node)] = State::OnChain;
            chain.push_back(node);
            node = parents[static_cast<size_t>(node)];
        }
        if (node != kNoParent && state[static_cast<size_t>(node)] == State::OnChain) {
            source.fail(node_name(node), "node is its own ancestor (the node hierarchy has a cycle)");
        }
        for (const int visited : chain) state[static_cast<size_t>(visited)] = State::Done;
    }
}

}  // namespace

std::vector<int> checked_root_nodes(const GltfSource& source) {
    const tinygltf::Model& model = source.model;
    const std::vector<int> parents = parents_of(source);
    refuse_cycles(source, parents);
    if (model.scenes.empty()) {
        // No scene: every node that is nobody's child is a root.
        std::vector<int> roots;
        for (size_t i = 0; i < parents.size(); ++i) {
            if (parents[i] == kNoParent) roots.push_back(static_cast<int>(i));
        }
        return roots;
    }
    const int scene = model.defaultScene >= 0 ? model.defaultScene : 0;
    if (static_cast<size_t>(scene) >= model.scenes.size()) {
        source.fail("scene", "scene " + std::to_string(scene) + " does not exist");
    }
    const std::string where = "scenes[" + std::to_string(scene) + "].nodes";
    const std::vector<int>& roots = model.scenes[static_cast<size_t>(scene)].nodes;
    std::vector<bool> listed(model.nodes.size(), false);
    for (const int root : roots) {
        if (root < 0 || static_cast<size_t>(root) >= model.nodes.size()) {
            source.fail(where, "node " + std::to_string(root) + " does not exist (the file has " +
                                   std::to_string(model.nodes.size()) + " nodes)");
        }
        if (listed[static_cast<size_t>(root)]) source.fail(where, "lists node " + std::to_string(root) + " twice");
        listed[static_cast<size_t>(root)] = true;
        if (parents[static_cast<size_t>(root)] != kNoParent) {
            source.fail(where, "node " + std::to_string(root) + " is a root but also a child of " +
                                   node_name(parents[static_cast<size_t>(root)]));
        }
    }
    return roots;
}

}  // namespace penumbra
