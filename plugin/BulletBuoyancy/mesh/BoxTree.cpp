/// @file BoxTree.cpp
/// Bounding-volume hierarchy build (top-down median split, as in Wald 2007's survey of BVH builders without
/// the surface-area heuristic: the broad phase of the mesh checks only needs O(log n) depth).

#include <BulletBuoyancy/mesh/BoxTree.h>

#include <algorithm>
#include <numeric>

namespace buoyancy {

BoxTree::BoxTree(std::vector<Eigen::AlignedBox3d> boxes) : m_boxes(std::move(boxes)), m_order(m_boxes.size()) {
    const int n = static_cast<int>(m_boxes.size());
    if (n == 0) return;
    std::iota(m_order.begin(), m_order.end(), 0);
    std::vector<Eigen::Vector3d> centre(m_boxes.size());
    for (std::size_t i = 0; i < m_boxes.size(); ++i) centre[i] = m_boxes[i].center();
    m_nodes.reserve(m_boxes.size() + 2);  // leaves hold ≥ 2 boxes (n > 1): fewer than n nodes
    m_nodes.push_back({Eigen::AlignedBox3d(), 0, n, -1});
    std::vector<int> todo{0};
    while (!todo.empty()) {
        const int node = todo.back();
        todo.pop_back();
        const int first = m_nodes[std::size_t(node)].first, count = m_nodes[std::size_t(node)].count;
        Eigen::AlignedBox3d box, centres;
        for (int k = first; k < first + count; ++k) {
            box.extend(m_boxes[std::size_t(m_order[std::size_t(k)])]);
            centres.extend(centre[std::size_t(m_order[std::size_t(k)])]);
        }
        m_nodes[std::size_t(node)].box = box;
        if (count <= kLeaf) continue;
        int axis = 0;
        centres.diagonal().maxCoeff(&axis);
        const int half = count / 2;
        std::nth_element(m_order.begin() + first, m_order.begin() + first + half, m_order.begin() + first + count,
                         [&](int a, int b) { return centre[std::size_t(a)][axis] < centre[std::size_t(b)][axis]; });
        const int left = static_cast<int>(m_nodes.size());
        m_nodes[std::size_t(node)].child = left;
        m_nodes.push_back({Eigen::AlignedBox3d(), first, half, -1});
        m_nodes.push_back({Eigen::AlignedBox3d(), first + half, count - half, -1});
        todo.push_back(left);
        todo.push_back(left + 1);
    }
}

}  // namespace buoyancy
