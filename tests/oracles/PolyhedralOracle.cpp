#include "oracles/PolyhedralOracle.h"

#include <algorithm>
#include <cmath>

namespace buoyancy_test {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Signed tetrahedron (v0, v1, v2, v3): volume det[v1−v0, v2−v0, v3−v0]/6, first moment V·(Σv)/4 and
/// covariance ∫ r rᵀ = V/20 (Σ v_i v_iᵀ + s sᵀ), s = Σ v_i (standard closed form, e.g. Tonon 2004).
void addTetrahedron(const Eigen::Vector3d& v0, const Eigen::Vector3d& v1, const Eigen::Vector3d& v2,
                    const Eigen::Vector3d& v3, double& vol, Eigen::Vector3d& first, Eigen::Matrix3d& second) {
    const double v = (v1 - v0).cross(v2 - v0).dot(v3 - v0) / 6.0;
    const Eigen::Vector3d s = v0 + v1 + v2 + v3;
    vol += v;
    first += v * s / 4.0;
    Eigen::Matrix3d c = v0 * v0.transpose() + v1 * v1.transpose() + v2 * v2.transpose() + v3 * v3.transpose();
    c += s * s.transpose();
    second += (v / 20.0) * c;
}

Eigen::Vector3d vertexMean(const std::vector<Eigen::Vector3d>& verts) {
    Eigen::Vector3d m = Eigen::Vector3d::Zero();
    for (const auto& v : verts) m += v;
    return verts.empty() ? m : Eigen::Vector3d(m / double(verts.size()));
}

struct ClipVertex {
    Eigen::Vector3d p;
    bool onPlane;
};

/// Keep the part of triangle (a, b, c) with y ≤ h (Sutherland–Hodgman against one plane). Returns the
/// number of kept vertices (0..4) in `out`, in the triangle's winding order.
int clipBelow(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double h, ClipVertex out[4]) {
    const Eigen::Vector3d* in[3] = {&a, &b, &c};
    int n = 0;
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d& p = *in[i];
        const Eigen::Vector3d& q = *in[(i + 1) % 3];
        const double dp = p.y() - h, dq = q.y() - h;
        if (dp <= 0) out[n++] = {p, dp == 0};
        if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
            const double t = dp / (dp - dq);
            Eigen::Vector3d x = p + t * (q - p);
            x.y() = h;
            out[n++] = {x, true};
        }
    }
    return n;
}

}  // namespace

Eigen::Matrix3d OracleMoments::inertiaAboutCentroid() const {
    const Eigen::Matrix3d sc = second - volume * centroid * centroid.transpose();
    return sc.trace() * Eigen::Matrix3d::Identity() - sc;
}

OracleMoments oracleDryMoments(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris) {
    const Eigen::Vector3d ref = vertexMean(verts);
    double vol = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    for (const auto& t : tris) addTetrahedron(ref, verts[t[0]], verts[t[1]], verts[t[2]], vol, first, second);
    OracleMoments m;
    m.volume = vol;
    m.centroid = vol != 0 ? Eigen::Vector3d(first / vol) : Eigen::Vector3d::Zero();
    m.second = second;
    return m;
}

OracleMoments oracleSubmergedMoments(const std::vector<Eigen::Vector3d>& verts,
                                     const std::vector<Eigen::Vector3i>& tris, double h) {
    Eigen::Vector3d apex = vertexMean(verts);
    apex.y() = h;  // apex on the water plane: cap faces give flat (zero-volume) tetrahedra
    double vol = 0;
    Eigen::Vector3d first = Eigen::Vector3d::Zero();
    Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
    ClipVertex poly[4];
    for (const auto& t : tris) {
        const int n = clipBelow(verts[t[0]], verts[t[1]], verts[t[2]], h, poly);
        for (int k = 1; k + 1 < n; ++k) addTetrahedron(apex, poly[0].p, poly[k].p, poly[k + 1].p, vol, first, second);
    }
    OracleMoments m;
    m.volume = vol;
    m.centroid = vol != 0 ? Eigen::Vector3d(first / vol) : Eigen::Vector3d::Zero();
    m.second = second;
    return m;
}

double oracleCapArea(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris, double h) {
    // The cap closes the submerged solid with outward normal +y; its boundary runs along each kept
    // polygon's cut edge in the opposite direction. Shoelace: area along +y = ½ Σ (z_a x_b − x_a z_b).
    const Eigen::Vector3d o = vertexMean(verts);
    double twice = 0;
    ClipVertex poly[4];
    for (const auto& t : tris) {
        const int n = clipBelow(verts[t[0]], verts[t[1]], verts[t[2]], h, poly);
        if (n < 3) continue;
        for (int k = 0; k < n; ++k) {
            const ClipVertex& p = poly[k];
            const ClipVertex& q = poly[(k + 1) % n];
            if (!(p.onPlane && q.onPlane)) continue;
            // cap edge q → p
            const double ax = q.p.x() - o.x(), az = q.p.z() - o.z(), bx = p.p.x() - o.x(), bz = p.p.z() - o.z();
            twice += az * bx - ax * bz;
        }
    }
    return 0.5 * twice;
}

double oracleSurfaceArea(const std::vector<Eigen::Vector3d>& verts, const std::vector<Eigen::Vector3i>& tris) {
    double a = 0;
    for (const auto& t : tris) a += 0.5 * (verts[t[1]] - verts[t[0]]).cross(verts[t[2]] - verts[t[0]]).norm();
    return a;
}

std::vector<Eigen::Vector3d> oraclePose(const std::vector<Eigen::Vector3d>& verts, const Eigen::Isometry3d& pose) {
    std::vector<Eigen::Vector3d> out;
    out.reserve(verts.size());
    for (const auto& v : verts) out.push_back(pose * v);
    return out;
}

double sphereVolume(double R) { return 4.0 * kPi * R * R * R / 3.0; }

double sphereCapVolume(double R, double h) { return kPi * h * h * (3.0 * R - h) / 3.0; }

double sphereCapCentroidDistance(double R, double h) {
    return 3.0 * (2.0 * R - h) * (2.0 * R - h) / (4.0 * (3.0 * R - h));
}

double boxSubmergedVolume(double a, double b, double c, double h) {
    const double d = std::min(std::max(h + 0.5 * b, 0.0), b);
    return a * d * c;
}

double boxCentreOfBuoyancyY(double a, double b, double c, double h) {
    (void)a;
    (void)c;
    const double d = std::min(std::max(h + 0.5 * b, 0.0), b);
    return -0.5 * b + 0.5 * d;
}

Eigen::Matrix3d boxInertia(double a, double b, double c) {
    const double m = a * b * c;
    return Eigen::Vector3d(m * (b * b + c * c) / 12.0, m * (a * a + c * c) / 12.0, m * (a * a + b * b) / 12.0)
        .asDiagonal();
}

Eigen::Matrix3d sphereInertia(double R) {
    return (0.4 * sphereVolume(R) * R * R) * Eigen::Matrix3d::Identity();
}

}  // namespace buoyancy_test
