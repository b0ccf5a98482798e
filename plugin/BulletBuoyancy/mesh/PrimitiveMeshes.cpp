/// @file PrimitiveMeshes.cpp
/// Closed, welded, outward meshes of analytic shapes with per-corner UVs that form a valid atlas: every
/// chart inside [0,1]², charts separated by gaps, every triangle counter-clockwise in UV as in 3D.
/// Parameterisations: spherical (θ from +y, φ around y), cylindrical, toroidal — standard textbook forms.

#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kGap = 0.02;  ///< UV margin around each chart (fraction of the unit square)

void requirePositive(double v, const char* what) {
    if (!(std::isfinite(v) && v > 0.0))
        throw std::invalid_argument(std::string("primitive mesh: ") + what + " must be finite and > 0");
}
void requireAtLeast(int v, int least, const char* what) {
    if (v < least)
        throw std::invalid_argument(std::string("primitive mesh: ") + what + " must be at least " + std::to_string(least));
}

void addTri(TriangleMesh& m, int a, int b, int c, const Eigen::Vector2d& ua, const Eigen::Vector2d& ub,
            const Eigen::Vector2d& uc) {
    m.triangles.emplace_back(a, b, c);
    m.corner_uvs.push_back(ua);
    m.corner_uvs.push_back(ub);
    m.corner_uvs.push_back(uc);
}

/// Point on the circle of radius rho around y at azimuth phi; increasing phi turns from +x towards −z,
/// which makes (down, around) a right-handed pair with the outward normal.
Eigen::Vector3d ring(double rho, double y, double phi) { return {rho * std::cos(phi), y, -rho * std::sin(phi)}; }

}  // namespace

TriangleMesh makeBoxMesh(double sx, double sy, double sz) {
    requirePositive(sx, "box size x");
    requirePositive(sy, "box size y");
    requirePositive(sz, "box size z");
    TriangleMesh m;
    const Eigen::Vector3d half(0.5 * sx, 0.5 * sy, 0.5 * sz);
    // Vertex index = ix + 2 iy + 4 iz (corner at ±half).
    for (int i = 0; i < 8; ++i)
        m.vertices.emplace_back((i & 1 ? 1 : -1) * half.x(), (i & 2 ? 1 : -1) * half.y(), (i & 4 ? 1 : -1) * half.z());
    // Six charts in a 3 × 2 grid of cells, each shrunk by kGap.
    const double cw = 1.0 / 3.0, ch = 0.5;
    int face = 0;
    for (int axis = 0; axis < 3; ++axis) {
        const int ua = (axis + 1) % 3, va = (axis + 2) % 3;  // e_ua × e_va = e_axis
        for (int side = 0; side < 2; ++side, ++face) {
            const Eigen::Vector2d cellMin((face % 3) * cw + kGap, (face / 3) * ch + kGap);
            const Eigen::Vector2d chartSize(cw - 2 * kGap, ch - 2 * kGap);
            auto vertexAt = [&](int cu, int cv) {
                int bits[3];
                bits[axis] = side;
                bits[ua] = cu;
                bits[va] = cv;
                return bits[0] + 2 * bits[1] + 4 * bits[2];
            };
            // Quad corners counter-clockwise seen from outside, with their UVs (also counter-clockwise).
            int cu[4], cv[4];
            Eigen::Vector2d uv[4];
            const int pu[4] = {0, 1, 1, 0}, pv[4] = {0, 0, 1, 1};
            for (int k = 0; k < 4; ++k) {
                if (side == 1) { cu[k] = pu[k]; cv[k] = pv[k]; }      // +axis face: (u, v) order
                else { cu[k] = pv[k]; cv[k] = pu[k]; }                // −axis face: mirrored order
                const double tu = side == 1 ? cu[k] : 1 - cu[k];       // keep the UV chart unmirrored
                uv[k] = cellMin + Eigen::Vector2d(tu * chartSize.x(), cv[k] * chartSize.y());
            }
            const int q[4] = {vertexAt(cu[0], cv[0]), vertexAt(cu[1], cv[1]), vertexAt(cu[2], cv[2]), vertexAt(cu[3], cv[3])};
            addTri(m, q[0], q[1], q[2], uv[0], uv[1], uv[2]);
            addTri(m, q[0], q[2], q[3], uv[0], uv[2], uv[3]);
        }
    }
    return m;
}

TriangleMesh makeSphereMesh(double radius, int segments, int rings) {
    requirePositive(radius, "sphere radius");
    requireAtLeast(segments, 3, "sphere segments");
    requireAtLeast(rings, 2, "sphere rings");
    TriangleMesh m;
    // Vertex 0: north pole (+y), 1: south pole, then rings i = 1..rings−1 with `segments` vertices each.
    m.vertices.emplace_back(0.0, radius, 0.0);
    m.vertices.emplace_back(0.0, -radius, 0.0);
    for (int i = 1; i < rings; ++i) {
        const double theta = kPi * i / rings;
        for (int j = 0; j < segments; ++j)
            m.vertices.push_back(ring(radius * std::sin(theta), radius * std::cos(theta), 2 * kPi * j / segments));
    }
    auto idx = [&](int i, int j) { return i == 0 ? 0 : i == rings ? 1 : 2 + (i - 1) * segments + (j % segments); };
    // Lat-long chart (one chart, seam at φ = 0 where u jumps from 1 to 0), scaled into [kGap, 1 − kGap]².
    auto uv = [&](double i, double j) {
        return Eigen::Vector2d(kGap + (1 - 2 * kGap) * j / segments, kGap + (1 - 2 * kGap) * (1.0 - i / rings));
    };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const int a = idx(i, j), b = idx(i + 1, j), c = idx(i + 1, j + 1), d = idx(i, j + 1);
            if (i == 0) {
                addTri(m, a, b, c, uv(0, j + 0.5), uv(1, j), uv(1, j + 1));  // north fan
            } else if (i == rings - 1) {
                addTri(m, a, b, d, uv(i, j), uv(rings, j + 0.5), uv(i, j + 1));  // south fan
            } else {
                addTri(m, a, b, c, uv(i, j), uv(i + 1, j), uv(i + 1, j + 1));
                addTri(m, a, c, d, uv(i, j), uv(i + 1, j + 1), uv(i, j + 1));
            }
        }
    return m;
}

TriangleMesh makeCylinderMesh(double radius, double height, int segments) {
    requirePositive(radius, "cylinder radius");
    requirePositive(height, "cylinder height");
    requireAtLeast(segments, 3, "cylinder segments");
    TriangleMesh m;
    const double h2 = 0.5 * height;
    // 0: top centre, 1: bottom centre, then top ring, then bottom ring.
    m.vertices.emplace_back(0.0, h2, 0.0);
    m.vertices.emplace_back(0.0, -h2, 0.0);
    for (int j = 0; j < segments; ++j) m.vertices.push_back(ring(radius, h2, 2 * kPi * j / segments));
    for (int j = 0; j < segments; ++j) m.vertices.push_back(ring(radius, -h2, 2 * kPi * j / segments));
    auto top = [&](int j) { return 2 + j % segments; };
    auto bot = [&](int j) { return 2 + segments + j % segments; };
    // Charts: side in [kGap, 1 − kGap] × [kGap, 0.5 − kGap]; caps as discs in the upper half.
    auto side = [&](int j, bool upper) {
        return Eigen::Vector2d(kGap + (1 - 2 * kGap) * j / segments, upper ? 0.5 - kGap : kGap);
    };
    const double capR = 0.25 - kGap;
    const Eigen::Vector2d topC(0.25, 0.75), botC(0.75, 0.75);
    auto capUv = [&](const Eigen::Vector2d& c, int j, double mirror) {
        const double phi = 2 * kPi * j / segments;
        return Eigen::Vector2d(c.x() + capR * std::cos(phi), c.y() + mirror * capR * std::sin(phi));
    };
    for (int j = 0; j < segments; ++j) {
        addTri(m, top(j), bot(j), bot(j + 1), side(j, true), side(j, false), side(j + 1, false));
        addTri(m, top(j), bot(j + 1), top(j + 1), side(j, true), side(j + 1, false), side(j + 1, true));
        addTri(m, 0, top(j), top(j + 1), topC, capUv(topC, j, 1.0), capUv(topC, j + 1, 1.0));
        addTri(m, 1, bot(j + 1), bot(j), botC, capUv(botC, j + 1, -1.0), capUv(botC, j, -1.0));
    }
    return m;
}

TriangleMesh makeTorusMesh(double majorRadius, double minorRadius, int majorSegments, int minorSegments) {
    requirePositive(majorRadius, "torus major radius");
    requirePositive(minorRadius, "torus minor radius");
    if (!(minorRadius < majorRadius))
        throw std::invalid_argument("primitive mesh: torus minor radius must be smaller than the major radius");
    requireAtLeast(majorSegments, 3, "torus major segments");
    requireAtLeast(minorSegments, 3, "torus minor segments");
    TriangleMesh m;
    for (int i = 0; i < majorSegments; ++i) {
        const double phi = 2 * kPi * i / majorSegments;
        for (int j = 0; j < minorSegments; ++j) {
            const double psi = 2 * kPi * j / minorSegments;  // ψ = 0 on the outer equator, π/2 on top
            m.vertices.push_back(ring(majorRadius + minorRadius * std::cos(psi), minorRadius * std::sin(psi), phi));
        }
    }
    auto idx = [&](int i, int j) { return (i % majorSegments) * minorSegments + (j % minorSegments); };
    auto uv = [&](int i, int j) {
        return Eigen::Vector2d(kGap + (1 - 2 * kGap) * i / majorSegments, kGap + (1 - 2 * kGap) * j / minorSegments);
    };
    for (int i = 0; i < majorSegments; ++i)
        for (int j = 0; j < minorSegments; ++j) {
            const int a = idx(i, j), b = idx(i + 1, j), c = idx(i + 1, j + 1), d = idx(i, j + 1);
            addTri(m, a, b, c, uv(i, j), uv(i + 1, j), uv(i + 1, j + 1));
            addTri(m, a, c, d, uv(i, j), uv(i + 1, j + 1), uv(i, j + 1));
        }
    return m;
}

}  // namespace buoyancy
