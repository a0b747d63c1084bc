// The winding engine's one tree walk (<vds/detail/tree_walk.h>): depth
// first in the order the visitor pushes, on trees deeper than its inline
// stack too, and stopping where the visitor says.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include <vds/detail/tree_walk.h>

namespace {

using vds::detail::TreeStack;
using vds::detail::walkTree;

/// A binary tree as child indices (leaves: -1).
struct Tree {
    std::vector<std::int64_t> left, right;
    std::uint32_t add() {
        left.push_back(-1);
        right.push_back(-1);
        return std::uint32_t(left.size() - 1);
    }
};

/// A comb `depth` levels deep whose left children continue the spine and
/// whose right children are leaves: walked left first, every level leaves
/// its right leaf on the stack, `depth` entries at the bottom.
Tree comb(int depth) {
    Tree t;
    std::uint32_t spine = t.add();
    for (int level = 0; level < depth; ++level) {
        const std::uint32_t next = t.add(), leaf = t.add();
        t.left[spine] = next;
        t.right[spine] = leaf;
        spine = next;
    }
    return t;
}

void preorder(const Tree& t, std::uint32_t node, std::vector<std::uint32_t>& out) {
    out.push_back(node);
    if (t.left[node] >= 0) preorder(t, std::uint32_t(t.left[node]), out);
    if (t.right[node] >= 0) preorder(t, std::uint32_t(t.right[node]), out);
}

TEST(TreeWalk, VisitsATreeDeeperThanItsInlineStackInPreorder) {
    for (const int depth : {3, 63, 64, 65, 300}) {
        const Tree t = comb(depth);
        std::vector<std::uint32_t> expected, visited;
        preorder(t, 0, expected);
        ASSERT_EQ(expected.size(), std::size_t(2 * depth + 1));
        const bool whole = walkTree(0, [&](std::uint32_t node, TreeStack& stack) {
            visited.push_back(node);
            if (t.right[node] >= 0) stack.push(std::uint32_t(t.right[node]));
            if (t.left[node] >= 0) stack.push(std::uint32_t(t.left[node]));
            return true;
        });
        EXPECT_TRUE(whole) << depth;
        EXPECT_EQ(visited, expected) << depth;
    }
}

TEST(TreeWalk, StopsWhereTheVisitorDoes) {
    const Tree t = comb(100);
    std::vector<std::uint32_t> expected, visited;
    preorder(t, 0, expected);
    const bool whole = walkTree(0, [&](std::uint32_t node, TreeStack& stack) {
        visited.push_back(node);
        if (visited.size() == 150) return false;
        if (t.right[node] >= 0) stack.push(std::uint32_t(t.right[node]));
        if (t.left[node] >= 0) stack.push(std::uint32_t(t.left[node]));
        return true;
    });
    EXPECT_FALSE(whole);
    expected.resize(150);
    EXPECT_EQ(visited, expected);
}

TEST(TreeWalk, StackIsLastInFirstOutAcrossItsSpill) {
    TreeStack stack;
    for (std::uint32_t k = 0; k < 200; ++k) stack.push(k);
    for (std::uint32_t k = 200; k-- > 0;) {
        ASSERT_FALSE(stack.empty());
        EXPECT_EQ(stack.pop(), k);
    }
    EXPECT_TRUE(stack.empty());
}

} // namespace
