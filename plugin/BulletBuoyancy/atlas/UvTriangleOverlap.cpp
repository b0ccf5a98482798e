#include <BulletBuoyancy/atlas/UvTriangleOverlap.h>

#include <BulletBuoyancy/geometry/PolygonClip.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace buoyancy {

std::vector<char> findOverlappingUvTriangles(const std::vector<Eigen::Vector2d>& uvs, const std::vector<char>& active,
                                             double relTolerance) {
    const std::size_t T = uvs.size() / 3;
    std::vector<char> flagged(T, 0);
    Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
    std::size_t count = 0;
    for (std::size_t t = 0; t < T; ++t) {
        if (!active[t]) continue;
        ++count;
        for (int k = 0; k < 3; ++k) {
            lo = lo.cwiseMin(uvs[3 * t + k]);
            hi = hi.cwiseMax(uvs[3 * t + k]);
        }
    }
    if (count < 2) return flagged;

    // Grid of G×G cells, about one triangle per cell on average.
    const int G = std::max(1, std::min(1024, static_cast<int>(std::sqrt(static_cast<double>(count)))));
    const Eigen::Vector2d extent = (hi - lo).cwiseMax(Eigen::Vector2d::Constant(1e-300));
    auto cellOf = [&](double v, int axis) {
        const int c = static_cast<int>((v - lo[axis]) / extent[axis] * G);
        return std::max(0, std::min(G - 1, c));
    };
    struct Box {
        Eigen::Vector2d lo, hi;
        int c0[2], c1[2];
    };
    std::vector<Box> box(T);
    std::vector<std::uint32_t> cellStart(static_cast<std::size_t>(G) * G + 1, 0);
    for (std::size_t t = 0; t < T; ++t) {
        if (!active[t]) continue;
        Box& b = box[t];
        b.lo = uvs[3 * t].cwiseMin(uvs[3 * t + 1]).cwiseMin(uvs[3 * t + 2]);
        b.hi = uvs[3 * t].cwiseMax(uvs[3 * t + 1]).cwiseMax(uvs[3 * t + 2]);
        for (int a = 0; a < 2; ++a) {
            b.c0[a] = cellOf(b.lo[a], a);
            b.c1[a] = cellOf(b.hi[a], a);
        }
        for (int y = b.c0[1]; y <= b.c1[1]; ++y)
            for (int x = b.c0[0]; x <= b.c1[0]; ++x) ++cellStart[static_cast<std::size_t>(y) * G + x + 1];
    }
    for (std::size_t c = 0; c + 1 < cellStart.size(); ++c) cellStart[c + 1] += cellStart[c];
    std::vector<std::uint32_t> fill(cellStart.begin(), cellStart.end() - 1), members(cellStart.back());
    for (std::size_t t = 0; t < T; ++t) {
        if (!active[t]) continue;
        const Box& b = box[t];
        for (int y = b.c0[1]; y <= b.c1[1]; ++y)
            for (int x = b.c0[0]; x <= b.c1[0]; ++x)
                members[fill[static_cast<std::size_t>(y) * G + x]++] = static_cast<std::uint32_t>(t);
    }

    auto areaOf = [&](std::size_t t) {
        return 0.5 * std::abs(cross2(uvs[3 * t], uvs[3 * t + 1], uvs[3 * t + 2]));
    };
    for (int cy = 0; cy < G; ++cy) {
        for (int cx = 0; cx < G; ++cx) {
            const std::size_t c = static_cast<std::size_t>(cy) * G + cx;
            for (std::uint32_t i = cellStart[c]; i < cellStart[c + 1]; ++i) {
                const std::uint32_t j = members[i];
                if (flagged[j]) continue;  // its partners find it from their own side
                const Box& bj = box[j];
                for (std::uint32_t m = cellStart[c]; m < cellStart[c + 1]; ++m) {
                    const std::uint32_t k = members[m];
                    if (k == j) continue;
                    const Box& bk = box[k];
                    // Bounding boxes must overlap, and each pair is tested only in the cell holding the
                    // lower corner of the boxes' intersection.
                    if (bj.lo.x() > bk.hi.x() || bk.lo.x() > bj.hi.x() || bj.lo.y() > bk.hi.y() || bk.lo.y() > bj.hi.y())
                        continue;
                    if (std::max(bj.c0[0], bk.c0[0]) != cx || std::max(bj.c0[1], bk.c0[1]) != cy) continue;
                    const double overlap = triangleIntersectionArea(uvs[3 * j], uvs[3 * j + 1], uvs[3 * j + 2],
                                                                    uvs[3 * k], uvs[3 * k + 1], uvs[3 * k + 2]);
                    if (overlap > relTolerance * std::min(areaOf(j), areaOf(k))) {
                        flagged[j] = flagged[k] = 1;
                        break;
                    }
                }
            }
        }
    }
    return flagged;
}

}  // namespace buoyancy
