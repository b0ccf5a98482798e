#include <BulletBuoyancy/bake/DeformableRebake.h>

#include <BulletBuoyancy/bake/BakeSamples.h>
#include <BulletBuoyancy/geometry/PolygonClip.h>
#include <BulletBuoyancy/atlas/TexelCoverage.h>
#include <BulletBuoyancy/geometry/SampleFormulas.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

struct Piece {
    std::uint32_t texel, tri;
    double weight, beta1, beta2, restArea;
};

}  // namespace

RebakeMap buildRebakeMap(const TriangleMesh& mesh, const std::vector<Eigen::Vector2d>& cornerUvs, int textureSize,
                         BakeMethod method) {
    const int N = textureSize;
    if (N < 1 || N > 16384)
        throw std::invalid_argument("buildRebakeMap: texture size " + std::to_string(N) + " is outside 1..16384");
    const std::size_t T = mesh.triangles.size();
    if (cornerUvs.size() != 3 * T)
        throw std::invalid_argument("buildRebakeMap: " + std::to_string(cornerUvs.size()) + " corner UVs given for " +
                                    std::to_string(T) + " triangles (need 3 per triangle)");
    const double slack = 1e-9;
    std::vector<Piece> pieces;
    for (std::size_t t = 0; t < T; ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] < 0 || static_cast<std::size_t>(tri[k]) >= mesh.vertices.size())
                throw std::invalid_argument("buildRebakeMap: triangle " + std::to_string(t) +
                                            " has a vertex index out of range");
        Eigen::Vector2d s[3];
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector2d& uv = cornerUvs[3 * t + k];
            if (!uv.allFinite() || uv.minCoeff() < -slack || uv.maxCoeff() > 1 + slack)
                throw std::invalid_argument("buildRebakeMap: triangle " + std::to_string(t) +
                                            " has a UV outside [0,1] or not finite");
            s[k] = uv * static_cast<double>(N);
        }
        const Eigen::Vector3d& p0 = mesh.vertices[tri[0]];
        const double area = 0.5 * (mesh.vertices[tri[1]] - p0).cross(mesh.vertices[tri[2]] - p0).norm();
        if (!(area > 0)) continue;  // as the baker: a degenerate triangle adds nothing at rest
        const Eigen::Vector2d d1 = s[1] - s[0], d2 = s[2] - s[0];
        const double det = d1.x() * d2.y() - d1.y() * d2.x();
        if (det == 0 || !std::isfinite(det))
            throw std::invalid_argument("buildRebakeMap: triangle " + std::to_string(t) +
                                        " has zero UV area but a surface area of " + std::to_string(area) + " m^2");
        const double texelArea = 0.5 * std::abs(det);
        Eigen::Matrix2d D;
        D.col(0) = d1;
        D.col(1) = d2;
        const Eigen::Matrix2d Dinv = D.inverse();
        auto add = [&](std::uint32_t texel, double weight, const Eigen::Vector2d& c) {
            const Eigen::Vector2d beta = Dinv * (c - s[0]);  // c = s0 + β1 d1 + β2 d2
            pieces.push_back(Piece{texel, static_cast<std::uint32_t>(t), weight, beta.x(), beta.y(), weight * area});
        };
        if (method == BakeMethod::ExactCoverage) {
            forEachTexelPiece(s[0], s[1], s[2], N, [&](int x, int y, const ClipPolygon& piece) {
                double a;
                Eigen::Vector2d c;
                areaAndCentroid(piece, a, c);
                const double f = std::abs(a) / texelArea;
                if (!(f > 0)) return;
                add(static_cast<std::uint32_t>(y) * N + x, f, c);
            });
        } else {
            Eigen::Vector2d a = s[0], b = s[1], c = s[2];
            if (cross2(a, b, c) < 0) std::swap(b, c);
            const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}) - 0.5)));
            const int x1 = std::min(N - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}) - 0.5)));
            const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}) - 0.5)));
            const int y1 = std::min(N - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}) - 0.5)));
            const bool own0 = ownsEdge(a, b), own1 = ownsEdge(b, c), own2 = ownsEdge(c, a);
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                    const Eigen::Vector2d p(x + 0.5, y + 0.5);
                    const double e0 = edgeFunction(a, b, p), e1 = edgeFunction(b, c, p), e2 = edgeFunction(c, a, p);
                    const bool in = (e0 > 0 || (e0 == 0 && own0)) && (e1 > 0 || (e1 == 0 && own1)) &&
                                    (e2 > 0 || (e2 == 0 && own2));
                    if (in) add(static_cast<std::uint32_t>(y) * N + x, 1.0 / texelArea, p);
                }
        }
    }
    // Group by texel (stable: pieces of one texel keep the baker's triangle order).
    std::stable_sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.texel < b.texel; });
    RebakeMap map;
    map.texture_size = N;
    map.method = method;
    map.triangles = mesh.triangles;
    map.vertexCount = mesh.vertices.size();
    map.pieceStart.push_back(0);
    map.pieceTriangle.reserve(pieces.size());
    map.pieceWeight.reserve(pieces.size());
    map.pieceBeta1.reserve(pieces.size());
    map.pieceBeta2.reserve(pieces.size());
    for (std::size_t i = 0; i < pieces.size();) {
        std::size_t j = i;
        double best = -1;
        std::uint32_t bestTri = pieces[i].tri;
        for (; j < pieces.size() && pieces[j].texel == pieces[i].texel; ++j) {
            map.pieceTriangle.push_back(pieces[j].tri);
            map.pieceWeight.push_back(pieces[j].weight);
            map.pieceBeta1.push_back(pieces[j].beta1);
            map.pieceBeta2.push_back(pieces[j].beta2);
            if (pieces[j].restArea > best) {
                best = pieces[j].restArea;
                bestTri = pieces[j].tri;
            }
        }
        map.pieceStart.push_back(static_cast<std::uint32_t>(map.pieceTriangle.size()));
        map.texel.push_back(pieces[i].texel);
        map.triangle.push_back(bestTri);
        i = j;
    }
    return map;
}

void checkRebakeVertices(const RebakeMap& map, const std::vector<Eigen::Vector3d>& vertices) {
    if (vertices.size() != map.vertexCount)
        throw std::invalid_argument("rebakeSamples: " + std::to_string(vertices.size()) + " vertices given, the mesh has " +
                                    std::to_string(map.vertexCount));
    for (std::size_t v = 0; v < vertices.size(); ++v)
        if (!vertices[v].allFinite())
            throw std::invalid_argument("rebakeSamples: vertex " + std::to_string(v) + " is not finite");
}

void rebakeSamples(const RebakeMap& map, const std::vector<Eigen::Vector3d>& vertices, SurfaceSamples& out) {
    checkRebakeVertices(map, vertices);
    const std::size_t n = map.size();
    out.texture_size = map.texture_size;
    out.method = map.method;
    for (auto* a : {&out.px, &out.py, &out.pz, &out.ax, &out.ay, &out.az, &out.area})
        if (a->size() != n) a->resize(n);
    if (out.texel != map.texel) out.texel = map.texel;
    if (out.triangle != map.triangle) out.triangle = map.triangle;
    for (std::size_t i = 0; i < n; ++i) {
        double acc[7] = {0, 0, 0, 0, 0, 0, 0};
        for (std::uint32_t k = map.pieceStart[i]; k < map.pieceStart[i + 1]; ++k) {
            const Eigen::Vector3i& t = map.triangles[map.pieceTriangle[k]];
            formulas::bb_rebake_piece(vertices[t[0]].data(), vertices[t[1]].data(), vertices[t[2]].data(),
                                      map.pieceWeight[k], map.pieceBeta1[k], map.pieceBeta2[k], acc);
        }
        const double inv = acc[3] > 0 ? 1.0 / acc[3] : 0.0;
        out.px[i] = acc[4] * inv;
        out.py[i] = acc[5] * inv;
        out.pz[i] = acc[6] * inv;
        out.ax[i] = acc[0];
        out.ay[i] = acc[1];
        out.az[i] = acc[2];
        out.area[i] = acc[3];
    }
}

}  // namespace buoyancy
