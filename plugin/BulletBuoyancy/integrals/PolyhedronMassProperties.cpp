/// @file PolyhedronMassProperties.cpp
/// Exact mass properties of a closed triangle mesh (declared in MassProperties.h).
/// Method: the divergence theorem applied face by face with closed-form polynomial integrals over each
/// triangle (B. Mirtich, "Fast and accurate computation of polyhedral mass properties", JGT 1996, in the
/// per-triangle form of D. Eberly, "Polyhedral Mass Properties (Revisited)", 2002).

#include <BulletBuoyancy/integrals/MassProperties.h>

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

/// Eberly's per-coordinate subexpressions for one triangle with coordinates w0, w1, w2.
struct FaceTerms {
    double f1, f2, f3, g0, g1, g2;
    FaceTerms(double w0, double w1, double w2) {
        const double s01 = w0 + w1;
        const double q01 = w0 * w0;
        const double t = q01 + w1 * s01;  // w0² + w0 w1 + w1²
        f1 = s01 + w2;
        f2 = t + w2 * f1;
        f3 = w0 * q01 + w1 * t + w2 * f2;
        g0 = f2 + w0 * (f1 + w0);
        g1 = f2 + w1 * (f1 + w1);
        g2 = f2 + w2 * (f1 + w2);
    }
};

}  // namespace

MassProperties polyhedronMassProperties(const TriangleMesh& mesh, double density) {
    if (!std::isfinite(density) || density <= 0)
        throw std::invalid_argument("polyhedronMassProperties: density must be positive and finite, got " +
                                    std::to_string(density));
    if (mesh.triangles.empty()) throw std::invalid_argument("polyhedronMassProperties: mesh has no triangles");
    const int nv = int(mesh.vertices.size());

    // Integrate in coordinates relative to the vertex mean to limit cancellation for off-origin meshes.
    Eigen::Vector3d ref = Eigen::Vector3d::Zero();
    for (const auto& v : mesh.vertices) ref += v;
    ref /= double(nv);

    // intg: 1, x, y, z, x², y², z², xy, yz, zx (Eberly's order), each times 6, 24, 60 or 120.
    double intg[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    double area = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        const Eigen::Vector3i& tri = mesh.triangles[t];
        for (int k = 0; k < 3; ++k)
            if (tri[k] < 0 || tri[k] >= nv)
                throw std::invalid_argument("polyhedronMassProperties: triangle " + std::to_string(t) +
                                            " has vertex index " + std::to_string(tri[k]) + " out of range [0, " +
                                            std::to_string(nv) + ")");
        const Eigen::Vector3d p0 = mesh.vertices[tri[0]] - ref;
        const Eigen::Vector3d p1 = mesh.vertices[tri[1]] - ref;
        const Eigen::Vector3d p2 = mesh.vertices[tri[2]] - ref;
        const Eigen::Vector3d d = (p1 - p0).cross(p2 - p0);  // 2 × area × outward normal
        area += 0.5 * d.norm();
        const FaceTerms X(p0.x(), p1.x(), p2.x());
        const FaceTerms Y(p0.y(), p1.y(), p2.y());
        const FaceTerms Z(p0.z(), p1.z(), p2.z());
        intg[0] += d.x() * X.f1;
        intg[1] += d.x() * X.f2;
        intg[2] += d.y() * Y.f2;
        intg[3] += d.z() * Z.f2;
        intg[4] += d.x() * X.f3;
        intg[5] += d.y() * Y.f3;
        intg[6] += d.z() * Z.f3;
        intg[7] += d.x() * (p0.y() * X.g0 + p1.y() * X.g1 + p2.y() * X.g2);
        intg[8] += d.y() * (p0.z() * Y.g0 + p1.z() * Y.g1 + p2.z() * Y.g2);
        intg[9] += d.z() * (p0.x() * Z.g0 + p1.x() * Z.g1 + p2.x() * Z.g2);
    }
    const double V = intg[0] / 6.0;
    if (!std::isfinite(V) || V <= 0)
        throw std::invalid_argument("polyhedronMassProperties: enclosed volume " + std::to_string(V) +
                                    " m³ is not positive (open mesh or inward-facing triangles?)");
    const Eigen::Vector3d first(intg[1] / 24.0, intg[2] / 24.0, intg[3] / 24.0);
    Eigen::Matrix3d S;  // ∫ r rᵀ dv about ref
    S(0, 0) = intg[4] / 60.0;
    S(1, 1) = intg[5] / 60.0;
    S(2, 2) = intg[6] / 60.0;
    S(0, 1) = S(1, 0) = intg[7] / 120.0;
    S(1, 2) = S(2, 1) = intg[8] / 120.0;
    S(0, 2) = S(2, 0) = intg[9] / 120.0;

    const Eigen::Vector3d c = first / V;  // centre relative to ref
    // About the centre: S_c = S − V c cᵀ; I = ρ[(tr S_c) E − S_c] (design.md 2.1).
    const Eigen::Matrix3d Sc = S - V * c * c.transpose();
    MassProperties m;
    m.volume = V;
    m.mass = density * V;
    m.area = area;
    m.centre = ref + c;
    m.inertia = density * (Sc.trace() * Eigen::Matrix3d::Identity() - Sc);
    return m;
}

}  // namespace buoyancy
