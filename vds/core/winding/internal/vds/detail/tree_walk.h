// vds internal: the one depth-first walk over the winding engine's trees
// (BoundaryCaps' chain tree, its tree of cap triangles and its tree of
// edges), used by the labels, the values, the occupancy sweep and the
// GPU's packing of the chain tree.
#pragma once

#include <cstddef>
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
    TreeStack() = default;
    TreeStack(const TreeStack&) = delete;
    TreeStack& operator=(const TreeStack&) = delete;
    void push(std::uint32_t node) {
        if (top_ == capacity_) grow();
        data_[top_++] = node;
    }
    bool empty() const { return top_ == 0; }
    /// The last node pushed; the stack must not be empty.
    std::uint32_t pop() { return data_[--top_]; }

private:
    static constexpr std::size_t kInline = 64;
    /// Past kInline entries (never, for a tree built by halving): the
    /// entries move to the heap, twice as many places each time.
    void grow() {
        if (data_ == local_) spill_.assign(local_, local_ + top_);
        spill_.resize(2 * capacity_);
        data_ = spill_.data();
        capacity_ = spill_.size();
    }
    std::uint32_t local_[kInline];
    std::uint32_t* data_ = local_;
    std::size_t top_ = 0, capacity_ = kInline;
    std::vector<std::uint32_t> spill_;
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
