// vds internal: the one depth-first walk over the winding engine's trees
// (BoundaryCaps' chain tree, its tree of cap triangles and its tree of
// edges), used by the labels, the values, the occupancy sweep and the
// GPU's packing of the chain tree.
#pragma once

#include <cstdint>
#include <vector>

namespace vds::detail {

/// The nodes a walk has still to visit, the last pushed first. The trees
/// are built by halving (each level halves the loops, a loop's edges or
/// the triangles), so a walk that pushes both children of a node holds at
/// most about one entry per level: 64 entries hold every walk of a tree of
/// 32-bit indices, and a deeper one (a tree built otherwise) spills to the
/// heap instead of running past the end.
class TreeStack {
public:
    void push(std::uint32_t node) {
        if (top_ < kInline) local_[top_++] = node;
        else spill_.push_back(node);
    }
    bool empty() const { return top_ == 0; }
    /// The last node pushed; the stack must not be empty.
    std::uint32_t pop() {
        if (!spill_.empty()) {
            const std::uint32_t node = spill_.back();
            spill_.pop_back();
            return node;
        }
        return local_[--top_];
    }

private:
    static constexpr int kInline = 64;
    std::uint32_t local_[kInline];
    int top_ = 0;
    std::vector<std::uint32_t> spill_; ///< past kInline entries (never, for a tree built by halving)
};

/// Walks the tree from `root` depth first: `visit(node, stack)` handles one
/// node and pushes onto `stack` the nodes it opens (its children, in the
/// reverse of the order they are to be visited in). Returns false as soon
/// as `visit` does (the walk stopped early), else true.
template <class Visit>
bool walkTree(std::uint32_t root, Visit&& visit) {
    TreeStack stack;
    stack.push(root);
    while (!stack.empty())
        if (!visit(stack.pop(), stack)) return false;
    return true;
}

} // namespace vds::detail
