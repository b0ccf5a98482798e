#include <BulletBuoyancy/atlas/UvLayout.h>

#include <BulletBuoyancy/atlas/MeshAdjacency.h>
#include <BulletBuoyancy/atlas/UvTriangleOverlap.h>
#include <BulletBuoyancy/atlas/TexelCoverage.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace buoyancy {

namespace {

std::string plural(std::size_t n, const char* one, const char* many) {
    return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

UvLayoutCheck checkUvLayout(const TriangleMesh& mesh, int textureSize) {
    if (textureSize < 1 || textureSize > 16384)
        throw std::invalid_argument("checkUvLayout: texture size " + std::to_string(textureSize) +
                                    " is outside 1..16384");
    UvLayoutCheck result;
    const std::size_t T = mesh.triangles.size();
    if (!mesh.hasUvs()) {
        result.problems.push_back(mesh.corner_uvs.empty() ? "no UVs"
                                                          : "UVs incomplete (" + std::to_string(mesh.corner_uvs.size()) +
                                                                " corner UVs for " + plural(T, "triangle", "triangles") + ")");
        return result;
    }
    const std::vector<Eigen::Vector2d>& uv = mesh.corner_uvs;

    // Per-triangle checks; triangles failing one are left out of the overlap and texel checks.
    std::vector<char> active(T, 1);
    std::size_t nonFinite = 0, outside = 0, zeroArea = 0;
    const double tol = 1e-9;  // rounding slack on the [0,1] bounds
    for (std::size_t t = 0; t < T; ++t) {
        const Eigen::Vector2d &a = uv[3 * t], &b = uv[3 * t + 1], &c = uv[3 * t + 2];
        if (!a.allFinite() || !b.allFinite() || !c.allFinite()) {
            ++nonFinite;
            active[t] = 0;
            continue;
        }
        const double lo = std::min({a.minCoeff(), b.minCoeff(), c.minCoeff()});
        const double hi = std::max({a.maxCoeff(), b.maxCoeff(), c.maxCoeff()});
        if (lo < -tol || hi > 1 + tol) {
            ++outside;
            active[t] = 0;
        }
        // Zero UV area: below (1e-6 texel)² relative to the texel grid, or exactly zero.
        const double texel2 = 1.0 / (static_cast<double>(textureSize) * textureSize);
        if (std::abs(0.5 * cross2(a, b, c)) <= 1e-12 * texel2) {
            ++zeroArea;
            active[t] = 0;
        }
    }
    if (nonFinite) result.problems.push_back(plural(nonFinite, "triangle has", "triangles have") + " non-finite UVs");
    if (outside) result.problems.push_back(plural(outside, "triangle", "triangles") + " outside [0,1]");
    if (zeroArea) result.problems.push_back(plural(zeroArea, "triangle has", "triangles have") + " zero UV area");

    // Overlap: two UV triangles covering the same region with positive area.
    const std::vector<char> overlapping = findOverlappingUvTriangles(uv, active);
    std::size_t overlapCount = 0;
    for (char f : overlapping) overlapCount += f ? 1 : 0;
    if (overlapCount)
        result.problems.push_back("overlapping UVs (" + plural(overlapCount, "triangle", "triangles") + ")");

    // Texels shared by different charts at this texture size (design.md 1.2: one sample would mix
    // unrelated pieces). Charts = triangles connected through UV-continuous edges.
    const TriangleAdjacency adj = buildTriangleAdjacency(mesh, uv);
    int chartCount = 0;
    const std::vector<int> chart = labelUvCharts(adj, active, chartCount);
    const int N = textureSize;
    std::vector<std::int32_t> owner(static_cast<std::size_t>(N) * N, -1);  // triangle first seen in the texel
    std::vector<char> shared(owner.size(), 0), triangleShares(T, 0);
    std::size_t sharedTexels = 0;
    for (std::size_t t = 0; t < T; ++t) {
        if (!active[t]) continue;
        const Eigen::Vector2d s0 = uv[3 * t] * N, s1 = uv[3 * t + 1] * N, s2 = uv[3 * t + 2] * N;
        const double minPiece = 1e-12 * std::abs(0.5 * cross2(s0, s1, s2));  // ignore rounding slivers
        forEachTexelPiece(s0, s1, s2, N, [&](int x, int y, const ClipPolygon& piece) {
            if (std::abs(signedArea(piece)) <= minPiece) return;
            const std::size_t texel = static_cast<std::size_t>(y) * N + x;
            const std::int32_t o = owner[texel];
            if (o < 0) {
                owner[texel] = static_cast<std::int32_t>(t);
            } else if (chart[o] != chart[t]) {
                if (!shared[texel]) {
                    shared[texel] = 1;
                    ++sharedTexels;
                }
                triangleShares[o] = triangleShares[t] = 1;
            }
        });
    }
    if (sharedTexels) {
        std::size_t tris = 0;
        for (char f : triangleShares) tris += f ? 1 : 0;
        result.problems.push_back(plural(sharedTexels, "texel", "texels") + " shared by different UV charts at " +
                                  std::to_string(N) + "x" + std::to_string(N) + " (" +
                                  plural(tris, "triangle", "triangles") + ", " + std::to_string(chartCount) +
                                  " charts; charts need a gap of at least one texel)");
    }
    result.usable = result.problems.empty();
    return result;
}

UvLayout chooseUvLayout(const TriangleMesh& mesh, int textureSize, bool preferModelUvs) {
    UvLayout layout;
    if (preferModelUvs) {
        const UvLayoutCheck check = checkUvLayout(mesh, textureSize);
        if (check.usable) {
            layout.corner_uvs = mesh.corner_uvs;
            layout.generated = false;
            return layout;
        }
        layout.reasons = check.problems;
    } else {
        layout.reasons.push_back("model UVs not requested");
    }
    layout.corner_uvs = generateAtlas(mesh, textureSize);
    layout.generated = true;
    return layout;
}

}  // namespace buoyancy
