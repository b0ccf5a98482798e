#pragma once
/// @file BodyFrameSums.h
/// Body-frame accumulators of the exact-mesh hydrostatic integrals, shared by the moment tree
/// (TreeHydrostatics.cpp) and the vertex-share pass (VertexHydrostatics.cpp): D = y − f (≤ 0 under water) at the
/// corners of flat pieces, positions s relative to the reference point in the body frame, the sums rotated into the
/// world once per evaluation (toWetIntegrals). Fields of design.md 2.2 and pressure of 2.3 (as in
/// WetTriangleIntegrals.h, which works in the world frame); integrated with the edge-midpoint rule, exact for the
/// degree ≤ 2 integrands over a flat piece with D linear over it.

#include <BulletBuoyancy/integrals/WetTriangleIntegrals.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

/// The argument checks of the body-frame evaluations (treeHydrostatics, vertexHydrostatics): `who` names the function
/// in the message.
/// @throws std::invalid_argument for a negative or non-finite density, a non-finite gravity, pose or reference point
inline void checkBodyFrameArguments(const char* who, double fluidDensity, double gravity, const Eigen::Isometry3d& pose,
                                    const Eigen::Vector3d& torqueReference) {
    if (!std::isfinite(fluidDensity) || fluidDensity < 0)
        throw std::invalid_argument(std::string(who) + ": fluid density must be finite and ≥ 0, got " +
                                    std::to_string(fluidDensity));
    if (!std::isfinite(gravity)) throw std::invalid_argument(std::string(who) + ": gravity is not finite");
    if (!pose.matrix().allFinite() || !torqueReference.allFinite())
        throw std::invalid_argument(std::string(who) + ": the pose or the reference point is not finite");
}

/// Accumulators of the wetted integrals, body frame, positions relative to the reference point q_r (rotated once at
/// the end: toWetIntegrals).
struct NodeSums {
    double V = 0, D2 = 0, Ay = 0, area = 0;
    Eigen::Vector3d F = Eigen::Vector3d::Zero();  ///< Σ ∫ D n, body frame
    Eigen::Vector3d T = Eigen::Vector3d::Zero();  ///< Σ ∫ D (q − q_r) × n, body frame
    Eigen::Vector3d Q = Eigen::Vector3d::Zero();  ///< Σ ∫ (q − q_r) D n_y, body frame
    WaterlineSums waterline;  ///< the waterline's segments, world horizontal axes (WetTriangleIntegrals.h)
};

/// A corner of a wetted piece in the body frame: position relative to the reference point q_r, s (m), and
/// D = y − f there (m, ≤ 0 under water; linear over a triangle, as the clip of ClippedHydrostatics.cpp assumes).
struct BodyCorner {
    Eigen::Vector3d s;
    double D;
};

/// Add the flat triangle (a, b, c), wetted everywhere (D ≤ 0), to the body-frame sums: the same integrals as
/// WetIntegrals::addTriangle (edge-midpoint rule, exact for the degree ≤ 2 integrands), written in the body frame so
/// the corners need no rotation (the sums are rotated once at the end, as the wet nodes'). u = world up, body frame.
inline void addBodyTriangle(const BodyCorner& a, const BodyCorner& b, const BodyCorner& c, const Eigen::Vector3d& u,
                            NodeSums& acc) {
    const Eigen::Vector3d A = 0.5 * (b.s - a.s).cross(c.s - a.s);
    const double Dab = 0.5 * (a.D + b.D), Dbc = 0.5 * (b.D + c.D), Dca = 0.5 * (c.D + a.D);
    const double sD = (Dab + Dbc + Dca) / 3.0;
    const double sD2 = (Dab * Dab + Dbc * Dbc + Dca * Dca) / 3.0;
    const Eigen::Vector3d sDm = (Dab * (a.s + b.s) + Dbc * (b.s + c.s) + Dca * (c.s + a.s)) / 6.0;
    const double ny = u.dot(A);
    acc.V += ny * sD;           // ∫ D n_y
    acc.F += sD * A;            // ∫ D n
    acc.T += sDm.cross(A);      // ∫ D s × n
    acc.Q += ny * sDm;          // ∫ s D n_y
    acc.D2 += ny * sD2;         // ∫ D² n_y
    acc.Ay += ny;
    acc.area += A.norm();
}

/// Clip the triangle (in[0], in[1], in[2]) against D ≤ 0 (Sutherland–Hodgman, D linear along its edges) and add the
/// wetted part (addBodyTriangle), and its edges on the waterline to acc.waterline (X, Z: the world x and z axes in the
/// body frame, the rows of R, so that X·s and Z·s are the world horizontal coordinates relative to the reference).
inline void addClippedBodyTriangle(const BodyCorner in[3], const Eigen::Vector3d& u, const Eigen::Vector3d& X,
                                   const Eigen::Vector3d& Z, NodeSums& acc) {
    const double d0 = in[0].D, d1 = in[1].D, d2 = in[2].D;
    if (d0 >= 0 && d1 >= 0 && d2 >= 0) return;  // dry (or touching)
    if (d0 < 0 && d1 < 0 && d2 < 0) {
        addBodyTriangle(in[0], in[1], in[2], u, acc);
        return;
    }
    BodyCorner poly[4];
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        const BodyCorner& p = in[k];
        const BodyCorner& q = in[(k + 1) % 3];
        if (p.D <= 0) poly[n++] = p;
        if ((p.D < 0 && q.D > 0) || (p.D > 0 && q.D < 0)) {
            const double w = p.D / (p.D - q.D);
            poly[n++] = BodyCorner{p.s + w * (q.s - p.s), 0.0};  // on the waterline
        }
    }
    for (int k = 1; k + 1 < n; ++k) addBodyTriangle(poly[0], poly[k], poly[k + 1], u, acc);
    for (int k = 0; k < n; ++k) {  // the piece's edges on the waterline (both ends at D = 0), in its order
        const BodyCorner& e = poly[k];
        const BodyCorner& m = poly[(k + 1) % n];
        if (e.D == 0 && m.D == 0) acc.waterline.add(X.dot(e.s), Z.dot(e.s), X.dot(m.s), Z.dot(m.s));
    }
}

/// The body-frame sums as world-frame WetIntegrals relative to the reference point (R: body → world rotation):
/// first moment ∫ (q − q_r) D n_y with its y part turned into ∫ (y'² − f'²)/2 n_y = ∫ y' D n_y − ½ ∫ D² n_y.
inline WetIntegrals toWetIntegrals(const NodeSums& acc, const Eigen::Matrix3d& R) {
    WetIntegrals I;
    I.V = acc.V;
    I.dA = R * acc.F;
    I.dpxA = R * acc.T;
    I.first = R * acc.Q;
    I.first.y() -= 0.5 * acc.D2;
    I.Ay = acc.Ay;
    I.area = acc.area;
    I.waterline = acc.waterline;
    return I;
}

}  // namespace buoyancy
