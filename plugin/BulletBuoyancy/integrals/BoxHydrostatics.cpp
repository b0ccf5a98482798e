/// @file BoxHydrostatics.cpp
/// The part of a box below flat water (design.md 2.5 "Boxes in flat water"). The submerged solid is closed by the
/// wet parts of the six faces and the waterline polygon. Seen from a point O on the water plane, it is the union of
/// the cones from O over the wet face polygons (the waterline polygon lies in the plane through O: its cone is
/// flat), so V = Σ_f A_f d_f / 3 with A_f the wet area of face f and d_f the signed distance from O to its plane
/// along the outward normal, and ∫(x − O) dV = Σ_f (3/4) V_f (g_f − O) with g_f the wet polygon's centroid (a cone's
/// centroid lies 3/4 of the way from its apex to its base's centroid). Each face is clipped in its own 2D
/// coordinates (u, v) ∈ [−1, 1]² along its two edges, where the height above the water is linear; the polygon's
/// area and centroid come from the shoelace sums, taken over its boundary: the wet part of each edge of the square
/// and the waterline chord. The segment each crossing face leaves on the water plane runs
/// along the waterline, so the waterline's area and moments follow from Green's theorem over those segments.

#include <BulletBuoyancy/integrals/BoxHydrostatics.h>

#include <algorithm>
#include <cmath>

namespace buoyancy {

namespace {

// Face f is normal to box axis kAxis[f] with outward sign kSign[f]; (kU[f], kV[f]) are the axes along its edges.
constexpr int kAxis[6] = {0, 0, 1, 1, 2, 2};
constexpr double kSign[6] = {-1, 1, -1, 1, -1, 1};
// Edge k runs from corner k to corner k + 1: along u (k even) or v (k odd); y_k − y_{k+1} = kEdgeSign[k] · 2 e_j.y.
constexpr double kEdgeSign[4] = {-1, -1, 1, 1};
constexpr double kBack[6] = {1, 0, 1, 0, 1, 0};  // 1 where the outward normal is −axis
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
        // Along an edge of a face the height changes by ±2 e_j.y (e_j the box axis the edge runs along), so each
        // crossing t = y_k / (y_k − y_l) needs one of three reciprocals. A level edge (e_j.y = 0) has no crossing:
        // its reciprocal is a finite stand-in that no kept value uses.
        double invHalf[3];
        for (int j = 0; j < 3; ++j) {
            const double twice = 2 * e[j].y();
            invHalf[j] = 1.0 / (twice + double(twice == 0));
        }
        double volume3 = 0;                                 // 3 V
        double mX = 0, mY = 0, mZ = 0;                      // 4 ∫ (x − O) dV
        double wetted = 0;
        double a2 = 0, mx = 0, mz = 0, mxx = 0, mzz = 0, mxz = 0;
        for (int f = 0; f < 6; ++f) {
            const int i = kAxis[f], iu = kU[f], iv = kV[f];
            const double sg = kSign[f];
            const double qx = sg * e[i].x(), qy = cy + sg * e[i].y(), qz = sg * e[i].z();  // face centre − O
            const double uy = e[iu].y(), vy = e[iv].y();
            double y[4];
            for (int k = 0; k < 4; ++k) y[k] = qy + kCornerU[k] * uy + kCornerV[k] * vy;
            if (std::min(std::min(y[0], y[1]), std::min(y[2], y[3])) >= 0) continue;  // dry face
            // Distance from O to the face's plane along its outward normal: q · (sign R_i).
            const double d = sg * (cy * R(1, i)) + hx[i];
            if (std::max(std::max(y[0], y[1]), std::max(y[2], y[3])) < 0) {  // wholly wet: its centre is its centroid
                const double w = faceArea[i] * d;
                volume3 += w;
                mX += w * qx;
                mY += w * qy;
                mZ += w * qz;
                wetted += faceArea[i];
                continue;
            }
            const double inv[2] = {invHalf[iu], invHalf[iv]};
            // A cut face. The wet polygon's boundary: the wet part of each edge of the square, then the waterline chord
            // from the point where it leaves the water (exit) to where it enters (entry). The shoelace sums are sums
            // over the boundary's segments, so one pass over the four edges, with selects in place of a polygon clip
            // (a dry edge gives a point segment), serves every way the water cuts the square. Measured: half the time
            // of clipping the polygon corner by corner (bullet_examples/benchmark/PrimitiveTiming.cpp).
            double s2 = 0, su = 0, sv = 0;  // 2 A', 6 A' ū, 6 A' v̄ in (u, v) units
            double exitU = 0, exitV = 0, entryU = 0, entryV = 0;
            for (int k = 0; k < 4; ++k) {
                const int l = (k + 1) & 3;
                // The crossing, when the sides differ; kept on the edge where rounding would put it off (a nearly level
                // edge at the water: any point of it is on the waterline to rounding).
                const double t = std::min(std::max(y[k] * kEdgeSign[k] * inv[k & 1], 0.0), 1.0);
                const bool aWet = y[k] < 0, bWet = y[l] < 0;
                const double s0 = aWet ? 0.0 : (bWet ? t : 0.0);
                const double s1 = bWet ? 1.0 : (aWet ? t : 0.0);
                const double du = kCornerU[l] - kCornerU[k], dv = kCornerV[l] - kCornerV[k];
                const double au = kCornerU[k] + s0 * du, av = kCornerV[k] + s0 * dv;
                const double bu = kCornerU[k] + s1 * du, bv = kCornerV[k] + s1 * dv;
                const double cr = au * bv - bu * av;
                s2 += cr;
                su += (au + bu) * cr;
                sv += (av + bv) * cr;
                const bool exits = aWet && !bWet, enters = bWet && !aWet;
                exitU = exits ? bu : exitU;
                exitV = exits ? bv : exitV;
                entryU = enters ? au : entryU;
                entryV = enters ? av : entryV;
            }
            {
                const double cr = exitU * entryV - entryU * exitV;
                s2 += cr;
                su += (exitU + entryU) * cr;
                sv += (exitV + entryV) * cr;
            }
            const double k8 = 0.125 * faceArea[i];  // the wet area is k8 · s2 ((u, v) spans 2 × 2 for the whole face)
            const double w = k8 * d;                // area · d = w s2; area · d · centroid = w (s2 q + (su e_u + sv e_v) / 3)
            volume3 += w * s2;
            mX += w * (s2 * qx + (su * e[iu].x() + sv * e[iv].x()) * (1.0 / 3.0));
            mY += w * (s2 * qy + (su * uy + sv * vy) * (1.0 / 3.0));
            mZ += w * (s2 * qz + (su * e[iu].z() + sv * e[iv].z()) * (1.0 / 3.0));
            wetted += k8 * s2;
            // The waterline segment exit → entry, in (x, z) about the torque reference. (u, v) turn about +axis on
            // both faces of an axis: on the face whose outward normal is −axis the segment runs the other way round.
            // A face without a crossing has exit = entry: its segment is a point and adds nothing.
            const double back = kBack[f];
            const double fu0 = exitU + back * (entryU - exitU), fv0 = exitV + back * (entryV - exitV);
            const double fu1 = entryU + back * (exitU - entryU), fv1 = entryV + back * (exitV - entryV);
            const double x0 = qx + fu0 * e[iu].x() + fv0 * e[iv].x() + rx;
            const double z0 = qz + fu0 * e[iu].z() + fv0 * e[iv].z() + rz;
            const double x1 = qx + fu1 * e[iu].x() + fv1 * e[iv].x() + rx;
            const double z1 = qz + fu1 * e[iu].z() + fv1 * e[iv].z() + rz;
            const double cr = x0 * z1 - x1 * z0;
            a2 += cr;
            mx += (x0 + x1) * cr;
            mz += (z0 + z1) * cr;
            mxx += (x0 * x0 + x0 * x1 + x1 * x1) * cr;
            mzz += (z0 * z0 + z0 * z1 + z1 * z1) * cr;
            mxz += (x0 * z1 + 2 * x0 * z0 + 2 * x1 * z1 + x1 * z0) * cr;
        }
        const Eigen::Vector3d moment(mX, mY, mZ);
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
