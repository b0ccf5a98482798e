#pragma once
/// @file BoxTree.h
/// Bounding-volume hierarchy over axis-aligned boxes (mesh checks: near-linear broad phase).

#include <Eigen/Geometry>

#include <vector>

namespace buoyancy {

/// Static binary tree over a set of boxes: median split on the longest axis of the box centres, leaves of
/// at most 4 boxes. Build O(n log n); a query costs O(log n + k) for k reported boxes on well-spread input.
class BoxTree {
public:
    /// Build over `boxes` (copied; box i is reported as index i).
    explicit BoxTree(std::vector<Eigen::AlignedBox3d> boxes);

    /// Call visit(i) for every box i that intersects `query` (closed boxes: touching counts).
    /// @param stack  scratch storage, reused between queries to avoid allocation
    template <class Visit>
    void query(const Eigen::AlignedBox3d& query, std::vector<int>& stack, Visit&& visit) const {
        stack.clear();
        if (!m_nodes.empty()) stack.push_back(0);
        while (!stack.empty()) {
            const Node& node = m_nodes[std::size_t(stack.back())];
            stack.pop_back();
            if (!node.box.intersects(query)) continue;
            if (node.child < 0) {
                for (int k = node.first; k < node.first + node.count; ++k)
                    if (m_boxes[std::size_t(m_order[std::size_t(k)])].intersects(query)) visit(m_order[std::size_t(k)]);
            } else {
                stack.push_back(node.child);
                stack.push_back(node.child + 1);
            }
        }
    }

    /// Box i as given to the constructor.
    const Eigen::AlignedBox3d& box(int i) const { return m_boxes[std::size_t(i)]; }

private:
    static constexpr int kLeaf = 4;
    /// Node n covers boxes m_order[first, first + count) and holds the box of all of them; an inner
    /// node's children are nodes child and child + 1, a leaf has child = −1.
    struct Node {
        Eigen::AlignedBox3d box;
        int first, count;
        int child;
    };
    std::vector<Eigen::AlignedBox3d> m_boxes;
    std::vector<int> m_order;
    std::vector<Node> m_nodes;
};

}  // namespace buoyancy
