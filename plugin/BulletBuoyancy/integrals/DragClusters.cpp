/// @file DragClusters.cpp
/// Drag level of detail (declared in DragClusters.h; design.md 2.5–2.6).

#include <BulletBuoyancy/integrals/DragClusters.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

namespace buoyancy {

namespace {

/// Normal bin of an area vector: dominant axis and sign (6 cube-map faces) × the signs of the two other
/// components (4 quadrants).
int normalBin(double x, double y, double z) {
    const double ax = std::abs(x), ay = std::abs(y), az = std::abs(z);
    int axis = 0;
    double u = y, v = z, s = x;
    if (ay >= ax && ay >= az) {
        axis = 1;
        u = z;
        v = x;
        s = y;
    } else if (az >= ax && az >= ay) {
        axis = 2;
        u = x;
        v = y;
        s = z;
    }
    const int face = 2 * axis + (s < 0 ? 1 : 0);
    return 4 * face + (u < 0 ? 1 : 0) + (v < 0 ? 2 : 0);
}

struct Keyed {
    std::vector<std::uint64_t> key;  // per kept fine sample
    std::vector<std::uint32_t> index;
};

}  // namespace

DragClusters clusterDragSamples(const SurfaceSamples& fine, std::size_t maxClusters) {
    DragClusters out;
    const std::size_t n = fine.size();
    out.fineCount = n;
    const bool haveArea = fine.area.size() == n;
    std::vector<std::uint32_t> kept;
    kept.reserve(n);
    std::vector<int> bin(n, 0);
    double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity()};
    double hi[3] = {-lo[0], -lo[0], -lo[0]};
    for (std::size_t i = 0; i < n; ++i) {
        const double a = haveArea ? fine.area[i] : std::sqrt(fine.ax[i] * fine.ax[i] + fine.ay[i] * fine.ay[i] +
                                                             fine.az[i] * fine.az[i]);
        if (!(a > 0) || !std::isfinite(a)) continue;
        kept.push_back(std::uint32_t(i));
        bin[i] = normalBin(fine.ax[i], fine.ay[i], fine.az[i]);
        const double p[3] = {fine.px[i], fine.py[i], fine.pz[i]};
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], p[k]);
            hi[k] = std::max(hi[k], p[k]);
        }
    }
    const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-12});

    int binDivisor = 1;  // 1: 24 normal bins; 4: the 6 cube faces; 24: one bin (only when 6 are too many)
    auto keysFor = [&](int g, std::vector<std::uint64_t>& keys) {
        keys.resize(kept.size());
        const double scale = double(g) / extent;
        for (std::size_t j = 0; j < kept.size(); ++j) {
            const std::uint32_t i = kept[j];
            auto cell = [&](double v, double l) {
                return std::uint64_t(std::clamp(int((v - l) * scale), 0, g - 1));
            };
            const std::uint64_t c = (cell(fine.px[i], lo[0]) * 64 + cell(fine.py[i], lo[1])) * 64 + cell(fine.pz[i], lo[2]);
            keys[j] = c * kDragNormalBins + std::uint64_t(bin[i] / binDivisor);
        }
    };
    auto distinct = [](std::vector<std::uint64_t> keys) {
        std::sort(keys.begin(), keys.end());
        return std::size_t(std::unique(keys.begin(), keys.end()) - keys.begin());
    };

    std::vector<std::uint64_t> keys;
    int grid = 64;
    if (maxClusters == 0 || maxClusters >= kept.size()) {
        // No merging: one cluster per fine sample.
        keys.resize(kept.size());
        for (std::size_t j = 0; j < kept.size(); ++j) keys[j] = j;
        grid = 0;
    } else {
        // Largest G in 1..64 whose cluster count fits (the count grows with G; binary search). When even one
        // cell has too many normal bins, coarser bins (6 faces, then 1).
        for (int d : {1, 4, 24}) {
            binDivisor = d;
            keysFor(1, keys);
            if (distinct(keys) <= maxClusters) break;
        }
        int good = 1, bad = 65;
        while (bad - good > 1) {
            const int mid = (good + bad) / 2;
            keysFor(mid, keys);
            if (distinct(keys) <= maxClusters) good = mid;
            else bad = mid;
        }
        grid = good;
        keysFor(grid, keys);
    }
    out.grid = grid;

    // Group kept samples by key.
    std::vector<std::uint32_t> order(kept.size());
    for (std::size_t j = 0; j < order.size(); ++j) order[j] = std::uint32_t(j);
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
    for (std::size_t s = 0; s < order.size();) {
        std::size_t e = s;
        while (e < order.size() && keys[order[e]] == keys[order[s]]) ++e;
        double A[3] = {0, 0, 0}, area = 0, c[3] = {0, 0, 0};
        for (std::size_t j = s; j < e; ++j) {
            const std::uint32_t i = kept[order[j]];
            const double a = haveArea ? fine.area[i] : std::sqrt(fine.ax[i] * fine.ax[i] + fine.ay[i] * fine.ay[i] +
                                                                 fine.az[i] * fine.az[i]);
            A[0] += fine.ax[i];
            A[1] += fine.ay[i];
            A[2] += fine.az[i];
            area += a;
            c[0] += a * fine.px[i];
            c[1] += a * fine.py[i];
            c[2] += a * fine.pz[i];
        }
        for (double& v : c) v /= area;
        // Spread about the centroid: Σ a_i (d dᵀ + (a_i/12)(I − n nᵀ)) / Σ a_i, each fine sample a square of its area.
        double C[6] = {0, 0, 0, 0, 0, 0};  // xx xy xz yy yz zz
        for (std::size_t j = s; j < e; ++j) {
            const std::uint32_t i = kept[order[j]];
            const double an = std::sqrt(fine.ax[i] * fine.ax[i] + fine.ay[i] * fine.ay[i] + fine.az[i] * fine.az[i]);
            const double a = haveArea ? fine.area[i] : an;
            const double d[3] = {fine.px[i] - c[0], fine.py[i] - c[1], fine.pz[i] - c[2]};
            const double nn[3] = {an > 0 ? fine.ax[i] / an : 0, an > 0 ? fine.ay[i] / an : 0, an > 0 ? fine.az[i] / an : 0};
            const double own = a / 12.0;
            int q = 0;
            for (int r = 0; r < 3; ++r)
                for (int k = r; k < 3; ++k, ++q) C[q] += a * (d[r] * d[k] + own * ((r == k ? 1.0 : 0.0) - nn[r] * nn[k]));
        }
        for (double& v : C) v /= area;
        out.px.push_back(c[0]);
        out.py.push_back(c[1]);
        out.pz.push_back(c[2]);
        out.ax.push_back(A[0]);
        out.ay.push_back(A[1]);
        out.az.push_back(A[2]);
        out.area.push_back(area);
        out.cxx.push_back(C[0]);
        out.cxy.push_back(C[1]);
        out.cxz.push_back(C[2]);
        out.cyy.push_back(C[3]);
        out.cyz.push_back(C[4]);
        out.czz.push_back(C[5]);
        s = e;
    }
    assignVelocityProbes(out, 0);
    return out;
}

void assignVelocityProbes(DragClusters& c, std::size_t maxProbes) {
    const std::size_t k = c.size();
    c.probeX.clear();
    c.probeY.clear();
    c.probeZ.clear();
    c.probeOf.assign(k, 0);
    if (maxProbes == 0 || maxProbes >= k) {
        c.probeX = c.px;
        c.probeY = c.py;
        c.probeZ = c.pz;
        for (std::size_t i = 0; i < k; ++i) c.probeOf[i] = std::uint32_t(i);
        return;
    }
    SurfaceSamples s;
    s.reserve(k);
    for (std::size_t i = 0; i < k; ++i) s.push(c.px[i], c.py[i], c.pz[i], c.ax[i], c.ay[i], c.az[i], c.area[i], 0u, 0u);
    const DragClusters g = clusterDragSamples(s, maxProbes);
    c.probeX = g.px;
    c.probeY = g.py;
    c.probeZ = g.pz;
    for (std::size_t i = 0; i < k; ++i) {
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < g.size(); ++j) {
            const double dx = c.px[i] - g.px[j], dy = c.py[i] - g.py[j], dz = c.pz[i] - g.pz[j];
            const double d2 = dx * dx + dy * dy + dz * dz;
            if (d2 < best) {
                best = d2;
                c.probeOf[i] = std::uint32_t(j);
            }
        }
    }
}

}  // namespace buoyancy
