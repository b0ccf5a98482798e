/// @file BoxHydrostatics.cpp
/// The part of a box below flat water (design.md 2.5 "Boxes in flat water"). The submerged solid is closed by the
/// wet parts of the six faces and the waterline polygon. Seen from a point O on the water plane, it is the union of
/// the cones from O over the wet face polygons (the waterline polygon lies in the plane through O: its cone is
/// flat), so V = Σ_f A_f d_f / 3 with A_f the wet area of face f and d_f the signed distance from O to its plane
/// along the outward normal, and ∫(x − O) dV = Σ_f (3/4) V_f (g_f − O) with g_f the wet polygon's centroid (a cone's
/// centroid lies 3/4 of the way from its apex to its base's centroid). Each face is clipped in its own 2D
/// coordinates (u, v) ∈ [−1, 1]² along its two edges, where the height above the water is linear; the polygon's
/// area and centroid come from the shoelace sums. The segment each crossing face leaves on the water plane runs
/// along the waterline, so the waterline's area and moments follow from Green's theorem over those segments.

#include <BulletBuoyancy/integrals/BoxHydrostatics.h>

#include <cmath>
#include <utility>

namespace buoyancy {

namespace {

// Face f is normal to box axis kAxis[f] with outward sign kSign[f]; (kU[f], kV[f]) are the axes along its edges.
constexpr int kAxis[6] = {0, 0, 1, 1, 2, 2};
constexpr double kSign[6] = {-1, 1, -1, 1, -1, 1};
constexpr int kU[6] = {1, 1, 2, 2, 0, 0};
constexpr int kV[6] = {2, 2, 0, 0, 1, 1};
// The face's corners, once round: (u, v).
constexpr double kCornerU[4] = {-1, 1, 1, -1};
constexpr double kCornerV[4] = {-1, -1, 1, 1};

}  // namespace

HydrostaticsResult boxHydrostatics(const Eigen::Isometry3d& pose, const Eigen::Vector3d& halfExtents,
                                   double waterHeight, double fluidDensity, double gravity,
                                   const Eigen::Vector3d& torqueReference) {
    HydrostaticsResult r;
    r.waterplane.valid = true;
    const Eigen::Matrix3d& R = pose.linear();
    const Eigen::Vector3d c = pose.translation();
    const double hx[3] = {halfExtents.x(), halfExtents.y(), halfExtents.z()};
    const Eigen::Vector3d e[3] = {R.col(0) * hx[0], R.col(1) * hx[1], R.col(2) * hx[2]};
    const double cy = c.y() - waterHeight;  // height of the centre above the water
    // The lowest and highest corner: dry, wholly under, or cut.
    const double reach = std::abs(e[0].y()) + std::abs(e[1].y()) + std::abs(e[2].y());
    if (cy - reach >= 0) return r;  // dry
    const double faceArea[3] = {4 * hx[1] * hx[2], 4 * hx[2] * hx[0], 4 * hx[0] * hx[1]};
    if (cy + reach <= 0) {  // under water: the whole box, centred at c
        r.submerged_volume = 8 * hx[0] * hx[1] * hx[2];
        r.centre_of_buoyancy = c;
        r.wetted_area = 2 * (faceArea[0] + faceArea[1] + faceArea[2]);
    } else {
        // Coordinates relative to O = (c.x, waterHeight, c.z); the waterline's (x, z) relative to the torque reference.
        const double rx = c.x() - torqueReference.x(), rz = c.z() - torqueReference.z();
        double volume3 = 0;                                 // 3 V
        Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // 4 ∫ (x − O) dV
        double wetted = 0;
        double a2 = 0, mx = 0, mz = 0, mxx = 0, mzz = 0, mxz = 0;
        for (int f = 0; f < 6; ++f) {
            const int i = kAxis[f], iu = kU[f], iv = kV[f];
            const Eigen::Vector3d q = Eigen::Vector3d(0, cy, 0) + kSign[f] * e[i];  // face centre − O
            const double dy[2] = {e[iu].y(), e[iv].y()};
            double y[4];
            int wet = 0;
            for (int k = 0; k < 4; ++k) {
                y[k] = q.y() + kCornerU[k] * dy[0] + kCornerV[k] * dy[1];
                wet += y[k] < 0;
            }
            if (wet == 0) continue;
            // Distance from O to the face's plane along its outward normal: q · (sign R_i).
            const double d = kSign[f] * (cy * R(1, i)) + hx[i];
            const double fullArea = faceArea[i];
            if (wet == 4) {  // the whole face: its centre is its centroid
                volume3 += fullArea * d;
                moment += (fullArea * d) * q;  // 4 · (3/4) · V_f · q with V_f = A d / 3
                wetted += fullArea;
                continue;
            }
            // Clip the square against y < 0 in (u, v), accumulating the shoelace sums as the kept polygon's corners
            // come (each edge from the previous corner to the new one; the last closes back to the first).
            double firstU = 0, firstV = 0, prevU = 0, prevV = 0;
            bool started = false;
            double s2 = 0, su = 0, sv = 0;  // 2 A', 6 A' ū, 6 A' v̄ in (u, v) units
            double exitU = 0, exitV = 0, entryU = 0, entryV = 0;
            auto emit = [&](double u, double v) {
                if (!started) {
                    firstU = u;
                    firstV = v;
                    started = true;
                } else {
                    const double cr = prevU * v - u * prevV;
                    s2 += cr;
                    su += (prevU + u) * cr;
                    sv += (prevV + v) * cr;
                }
                prevU = u;
                prevV = v;
            };
            for (int k = 0; k < 4; ++k) {
                const int l = (k + 1) & 3;
                const bool aWet = y[k] < 0, bWet = y[l] < 0;
                if (aWet) emit(kCornerU[k], kCornerV[k]);
                if (aWet != bWet) {
                    const double t = y[k] / (y[k] - y[l]);  // opposite signs: no division by zero
                    const double u = kCornerU[k] + t * (kCornerU[l] - kCornerU[k]);
                    const double v = kCornerV[k] + t * (kCornerV[l] - kCornerV[k]);
                    emit(u, v);
                    if (aWet) {
                        exitU = u;
                        exitV = v;
                    } else {
                        entryU = u;
                        entryV = v;
                    }
                }
            }
            {
                const double cr = prevU * firstV - firstU * prevV;
                s2 += cr;
                su += (prevU + firstU) * cr;
                sv += (prevV + firstV) * cr;
            }
            if (s2 > 0) {  // zero when only corners or an edge touch the water: no area, no volume
                const double area = 0.25 * fullArea * 0.5 * s2;  // (u, v) spans 2 × 2 for the whole face
                const Eigen::Vector3d g = q + (su / (3 * s2)) * e[iu] + (sv / (3 * s2)) * e[iv];
                volume3 += area * d;
                moment += (area * d) * g;
                wetted += area;
            }
            // The waterline segment exit → entry, in (x, z) about the torque reference. (u, v) turn about +axis on
            // both faces of an axis: on the face whose outward normal is −axis the segment runs the other way round.
            if (kSign[f] < 0) {
                std::swap(exitU, entryU);
                std::swap(exitV, entryV);
            }
            const double x0 = q.x() + exitU * e[iu].x() + exitV * e[iv].x() + rx;
            const double z0 = q.z() + exitU * e[iu].z() + exitV * e[iv].z() + rz;
            const double x1 = q.x() + entryU * e[iu].x() + entryV * e[iv].x() + rx;
            const double z1 = q.z() + entryU * e[iu].z() + entryV * e[iv].z() + rz;
            const double cr = x0 * z1 - x1 * z0;
            a2 += cr;
            mx += (x0 + x1) * cr;
            mz += (z0 + z1) * cr;
            mxx += (x0 * x0 + x0 * x1 + x1 * x1) * cr;
            mzz += (z0 * z0 + z0 * z1 + z1 * z1) * cr;
            mxz += (x0 * z1 + 2 * x0 * z0 + 2 * x1 * z1 + x1 * z0) * cr;
        }
        if (!(volume3 > 0)) return r;  // only an edge or a corner at the water line
        r.submerged_volume = volume3 / 3.0;
        r.centre_of_buoyancy = Eigen::Vector3d(c.x(), waterHeight, c.z()) + (0.75 / volume3) * moment;
        r.wetted_area = wetted;
        // The segments run one way round the waterline; which way in (x, z) depends on the frame's handedness in
        // that plane: the sign that makes the area positive orients every moment alike.
        const double s = a2 < 0 ? -1.0 : 1.0;
        r.waterline_area = s * a2 / 2.0;
        r.waterplane.x = s * mx / 6.0;
        r.waterplane.z = s * mz / 6.0;
        r.waterplane.xx = s * mxx / 12.0;
        r.waterplane.zz = s * mzz / 12.0;
        r.waterplane.xz = s * mxz / 24.0;
    }
    r.force = Eigen::Vector3d(0, fluidDensity * gravity * r.submerged_volume, 0);
    r.torque = (r.centre_of_buoyancy - torqueReference).cross(r.force);
    return r;
}

}  // namespace buoyancy
