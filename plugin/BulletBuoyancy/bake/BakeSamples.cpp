#include <BulletBuoyancy/bake/BakeSamples.h>

#include <BulletBuoyancy/geometry/PolygonClip.h>
#include <BulletBuoyancy/atlas/TexelCoverage.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

/// The affine UV→3D map of one triangle, in texel coordinates s = N·uv (design.md 1.1: the map is
/// affine per triangle, so a piece's 3D centroid is the image of its UV centroid).
struct TriangleMap {
    Eigen::Vector2d s[3];                 ///< corners in texel coordinates
    Eigen::Vector3d p0;                   ///< 3D corner 0, m
    Eigen::Matrix<double, 3, 2> jacobian; ///< dP/ds, m per texel
    double texelArea = 0;                 ///< |UV area| in texels²
    Eigen::Vector3d areaVector;           ///< ½ (b − a) × (c − a): area × outward normal, m²
    double area = 0;                      ///< |areaVector|, m²

    Eigen::Vector3d map(const Eigen::Vector2d& st) const { return p0 + jacobian * (st - s[0]); }
};

/// Per-texel sums; a dense texel → sample slot table keeps adding O(1) without hashing.
class TexelAccumulator {
public:
    explicit TexelAccumulator(int N) : slot_(static_cast<std::size_t>(N) * N, kNone) {}

    /// Add a piece of triangle `tri` covering texel `texel`: area vector A (m²), unsigned area a (m²),
    /// 3D centroid c (m).
    void add(std::uint32_t texel, std::uint32_t tri, const Eigen::Vector3d& A, double a, const Eigen::Vector3d& c) {
        std::uint32_t& s = slot_[texel];
        if (s == kNone) {
            s = static_cast<std::uint32_t>(texel_.size());
            texel_.push_back(texel);
            sumA_.emplace_back(Eigen::Vector3d::Zero());
            sumWc_.emplace_back(Eigen::Vector3d::Zero());
            sumArea_.push_back(0);
            bestPiece_.push_back(-1);
            bestTri_.push_back(tri);
        }
        sumA_[s] += A;
        sumWc_[s] += a * c;
        sumArea_[s] += a;
        if (a > bestPiece_[s]) {
            bestPiece_[s] = a;
            bestTri_[s] = tri;
        }
    }

    /// Samples in increasing texel order; p = area-weighted centroid of the texel's pieces.
    SurfaceSamples finish(int N, BakeMethod method) const {
        SurfaceSamples out;
        out.texture_size = N;
        out.method = method;
        std::vector<std::uint32_t> order(texel_.size());
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return texel_[a] < texel_[b]; });
        out.reserve(order.size());
        for (std::uint32_t s : order) {
            if (!(sumArea_[s] > 0)) continue;  // only zero-area slivers landed here
            const Eigen::Vector3d p = sumWc_[s] / sumArea_[s];
            out.push(p.x(), p.y(), p.z(), sumA_[s].x(), sumA_[s].y(), sumA_[s].z(), sumArea_[s], texel_[s],
                     bestTri_[s]);
        }
        return out;
    }

private:
    static constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> slot_;
    std::vector<std::uint32_t> texel_;
    std::vector<Eigen::Vector3d> sumA_, sumWc_;
    std::vector<double> sumArea_, bestPiece_;
    std::vector<std::uint32_t> bestTri_;
};

/// Exact coverage (design.md 1.1): each piece of the triangle inside a texel adds
/// A_tri·(piece UV area / triangle UV area) and its mapped centroid. The piece areas are taken unsigned,
/// so mirrored (clockwise) UV triangles need no special case.
void bakeExact(const TriangleMap& m, std::uint32_t t, int N, TexelAccumulator& acc) {
    forEachTexelPiece(m.s[0], m.s[1], m.s[2], N, [&](int x, int y, const ClipPolygon& piece) {
        double a;
        Eigen::Vector2d c;
        areaAndCentroid(piece, a, c);
        const double f = std::abs(a) / m.texelArea;
        if (!(f > 0)) return;
        acc.add(static_cast<std::uint32_t>(y) * N + x, t, f * m.areaVector, f * m.area, m.map(c));
    });
}

/// Texel-centre rasterisation (the paper, design.md 1.1): a texel whose centre is inside the triangle
/// gets A_tri·(texel UV area / triangle UV area) at the 3D point of its centre.
void bakeTexelCentre(const TriangleMap& m, std::uint32_t t, int N, TexelAccumulator& acc) {
    // Counter-clockwise order in texel space for the inside test (mirrored triangles swap two corners).
    Eigen::Vector2d a = m.s[0], b = m.s[1], c = m.s[2];
    if (cross2(a, b, c) < 0) std::swap(b, c);
    int x0, x1, y0, y1;
    // Centres x + ½ inside [min, max]: x from ceil(min − ½) to floor(max − ½).
    x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}) - 0.5)));
    x1 = std::min(N - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}) - 0.5)));
    y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}) - 0.5)));
    y1 = std::min(N - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}) - 0.5)));
    const double f = 1.0 / m.texelArea;
    const Eigen::Vector3d A = f * m.areaVector;
    const double area = f * m.area;
    const bool own0 = ownsEdge(a, b), own1 = ownsEdge(b, c), own2 = ownsEdge(c, a);
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            const Eigen::Vector2d p(x + 0.5, y + 0.5);
            const double e0 = edgeFunction(a, b, p), e1 = edgeFunction(b, c, p), e2 = edgeFunction(c, a, p);
            const bool in = (e0 > 0 || (e0 == 0 && own0)) && (e1 > 0 || (e1 == 0 && own1)) &&
                            (e2 > 0 || (e2 == 0 && own2));
            if (in) acc.add(static_cast<std::uint32_t>(y) * N + x, t, A, area, m.map(p));
        }
    }
}

}  // namespace

SurfaceSamples bakeSurfaceSamples(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& cornerUvs,
                                  int textureSize, BakeMethod method) {
    const int N = textureSize;
    if (N < 1 || N > 16384)
        throw std::invalid_argument("bakeSurfaceSamples: texture size " + std::to_string(N) +
                                    " is outside 1..16384");
    const std::size_t T = mesh.triangles.size();
    if (cornerUvs.size() != 3 * T)
        throw std::invalid_argument("bakeSurfaceSamples: " + std::to_string(cornerUvs.size()) +
                                    " corner UVs given for " + std::to_string(T) + " triangles (need 3 per triangle)");
    const double slack = 1e-9;  // UVs a hair outside [0,1] (rounding) are accepted; what lies outside is dropped
    TexelAccumulator acc(N);
    for (std::size_t t = 0; t < T; ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] < 0 || static_cast<std::size_t>(tri[k]) >= mesh.vertices.size())
                throw std::invalid_argument("bakeSurfaceSamples: triangle " + std::to_string(t) +
                                            " has a vertex index out of range");
        TriangleMap m;
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector2d& uv = cornerUvs[3 * t + k];
            if (!uv.allFinite() || uv.minCoeff() < -slack || uv.maxCoeff() > 1 + slack)
                throw std::invalid_argument("bakeSurfaceSamples: triangle " + std::to_string(t) +
                                            " has a UV outside [0,1] or not finite");
            m.s[k] = uv * static_cast<double>(N);
        }
        const Eigen::Vector3d& p0 = mesh.vertices[tri[0]];
        const Eigen::Vector3d e1 = mesh.vertices[tri[1]] - p0, e2 = mesh.vertices[tri[2]] - p0;
        m.areaVector = 0.5 * e1.cross(e2);
        m.area = m.areaVector.norm();
        if (!(m.area > 0)) continue;  // a degenerate triangle adds nothing to any integral
        const Eigen::Vector2d d1 = m.s[1] - m.s[0], d2 = m.s[2] - m.s[0];
        const double det = d1.x() * d2.y() - d1.y() * d2.x();
        if (det == 0 || !std::isfinite(det))
            throw std::invalid_argument("bakeSurfaceSamples: triangle " + std::to_string(t) +
                                        " has zero UV area but a surface area of " + std::to_string(m.area) +
                                        " m^2 (the UV layout loses surface)");
        m.texelArea = 0.5 * std::abs(det);
        m.p0 = p0;
        // J = [e1 e2] · [d1 d2]⁻¹ (chain rule of the barycentric map).
        Eigen::Matrix2d D;
        D.col(0) = d1;
        D.col(1) = d2;
        Eigen::Matrix<double, 3, 2> E;
        E.col(0) = e1;
        E.col(1) = e2;
        m.jacobian = E * D.inverse();
        if (method == BakeMethod::ExactCoverage)
            bakeExact(m, static_cast<std::uint32_t>(t), N, acc);
        else
            bakeTexelCentre(m, static_cast<std::uint32_t>(t), N, acc);
    }
    return acc.finish(N, method);
}

}  // namespace buoyancy
