#include <BulletBuoyancy/graph/NodeLevel.h>

#include <BulletBuoyancy/graph/MonotoneRoot.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace buoyancy {

namespace {

constexpr double kPi = 3.14159265358979323846;

double sphereRadius(double capacity) { return std::cbrt(3.0 * capacity / (4.0 * kPi)); }

/// Cap of height k of a sphere of radius R: volume, textbook.
double capVolume(double R, double k) { return kPi * k * k * (3.0 * R - k) / 3.0; }

/// Clip triangle (a, b, c) to x·up ≤ h and add the signed tetrahedra from p0 (a point of the plane): volume,
/// first moment and (when `second` is not null) second moment ∫ x xᵀ dV = v/20 (Σ p pᵀ + s sᵀ), s = Σ p over
/// the four corners (exact for a tetrahedron: Tonon, J. Math. Stat. 1(1), 2004).
void clipTriangle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                  const Eigen::Vector3d& up, double h, const Eigen::Vector3d& p0, double& vol, Eigen::Vector3d& mom,
                  Eigen::Matrix3d* second) {
    const Eigen::Vector3d in[3] = {a, b, c};
    Eigen::Vector3d out[4];
    int n = 0;
    for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d& p = in[i];
        const Eigen::Vector3d& q = in[(i + 1) % 3];
        const double dp = p.dot(up) - h, dq = q.dot(up) - h;
        if (dp <= 0) out[n++] = p;
        if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) out[n++] = p + (dp / (dp - dq)) * (q - p);
    }
    for (int i = 1; i + 1 < n; ++i) {
        const Eigen::Vector3d u = out[0] - p0, v = out[i] - p0, w = out[i + 1] - p0;
        const double tv = u.dot(v.cross(w)) / 6.0;
        vol += tv;
        const Eigen::Vector3d sum = p0 + out[0] + out[i] + out[i + 1];
        mom += tv * sum / 4.0;
        if (second) {
            const Eigen::Matrix3d pp = p0 * p0.transpose() + out[0] * out[0].transpose() +
                                       out[i] * out[i].transpose() + out[i + 1] * out[i + 1].transpose();
            *second += (tv / 20.0) * (pp + sum * sum.transpose());
        }
    }
}

/// Volume, first and second moments of the box part below the plane (see boxVolumeBelowPlane).
double boxBelowPlane(const Eigen::Vector3d& half, const Eigen::Vector3d& up, double h, Eigen::Vector3d& moment,
                     Eigen::Matrix3d* second) {
    moment.setZero();
    if (second) second->setZero();
    double vol = 0;
    const Eigen::Vector3d p0 = h * up;
    // The six faces, outward, each as two triangles.
    for (int axis = 0; axis < 3; ++axis) {
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        for (int s = -1; s <= 1; s += 2) {
            Eigen::Vector3d corner[4];
            const double cu[4] = {-1, 1, 1, -1}, cv[4] = {-1, -1, 1, 1};
            for (int k = 0; k < 4; ++k) {
                corner[k][axis] = s * half[axis];
                corner[k][u] = cu[k] * half[u];
                corner[k][v] = cv[k] * half[v];
            }
            // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
            if (s > 0) {
                clipTriangle(corner[0], corner[1], corner[2], up, h, p0, vol, moment, second);
                clipTriangle(corner[0], corner[2], corner[3], up, h, p0, vol, moment, second);
            } else {
                clipTriangle(corner[0], corner[2], corner[1], up, h, p0, vol, moment, second);
                clipTriangle(corner[0], corner[3], corner[2], up, h, p0, vol, moment, second);
            }
        }
    }
    return vol;
}

}  // namespace

double boxVolumeBelowPlane(const Eigen::Vector3d& half, const Eigen::Vector3d& up, double h, Eigen::Vector3d& moment) {
    return boxBelowPlane(half, up, h, moment, nullptr);
}

double nodeHalfHeight(const WaterNode& node, const Eigen::Vector3d& up) {
    if (node.shape == WaterNodeShape::Box) return 0.5 * node.size.cwiseAbs().dot(up.cwiseAbs());
    return sphereRadius(node.capacity);
}

double nodeVolumeBelow(const WaterNode& node, const Eigen::Vector3d& up, double h) {
    const double H = nodeHalfHeight(node, up);
    if (!(h > -H)) return 0.0;
    if (h >= H) return node.capacity;
    if (node.shape == WaterNodeShape::Box) {
        Eigen::Vector3d m;
        const double boxVol = node.size.prod();
        const double v = boxVolumeBelowPlane(0.5 * node.size, up, h, m);
        return std::clamp(v / boxVol, 0.0, 1.0) * node.capacity;
    }
    return std::min(capVolume(H, h + H), node.capacity);
}

double nodeLevelForVolume(const WaterNode& node, const Eigen::Vector3d& up, double volume) {
    const double H = nodeHalfHeight(node, up);
    if (!(volume > 0)) return -H;
    if (volume >= node.capacity) return H;
    if (node.shape == WaterNodeShape::Sphere) {
        // Fraction φ = V/C; t = h/R solves t³ − 3t + (4φ − 2) = 0 (from the cap volume); the root in
        // [−1, 1] is 2 cos((arccos(1 − 2φ) − 2π)/3) (trigonometric solution of the depressed cubic).
        const double phi = volume / node.capacity;
        double t = 2.0 * std::cos((std::acos(std::clamp(1.0 - 2.0 * phi, -1.0, 1.0)) - 2.0 * kPi) / 3.0);
        for (int it = 0; it < 2; ++it) {  // Newton polish on f(t) = (2 + 3t − t³)/4 − φ
            const double f = (2.0 + 3.0 * t - t * t * t) / 4.0 - phi;
            const double df = 0.75 * (1.0 - t * t);
            if (df > 1e-12) t -= f / df;
        }
        return std::clamp(t, -1.0, 1.0) * H;
    }
    return monotoneRoot([&](double h) { return nodeVolumeBelow(node, up, h) - volume; }, -H, H, -volume,
                        node.capacity - volume, 1e-13 * H);
}

Eigen::Vector3d nodeWaterCentroid(const WaterNode& node, const Eigen::Vector3d& up, double volume) {
    if (!(volume > 0) || volume >= node.capacity) return node.position;
    const double h = nodeLevelForVolume(node, up, volume);
    if (node.shape == WaterNodeShape::Box) {
        Eigen::Vector3d m;
        const double v = boxVolumeBelowPlane(0.5 * node.size, up, h, m);
        if (!(v > 0)) return node.position - nodeHalfHeight(node, up) * up;
        return node.position + m / v;
    }
    const double R = nodeHalfHeight(node, up);
    const double k = std::clamp(h + R, 0.0, 2.0 * R);
    const double d = 3.0 * (2.0 * R - k) * (2.0 * R - k) / (4.0 * (3.0 * R - k));
    return node.position - d * up;
}

Eigen::Matrix3d nodeWaterInertia(const WaterNode& node, const Eigen::Vector3d& up, double volume) {
    if (!(volume > 0)) return Eigen::Matrix3d::Zero();
    const double v = std::min(volume, node.capacity);
    const double h = nodeLevelForVolume(node, up, v);
    if (node.shape == WaterNodeShape::Box) {
        Eigen::Vector3d m;
        Eigen::Matrix3d second;
        const double vg = boxBelowPlane(0.5 * node.size, up, h, m, &second);
        if (!(vg > 0)) return Eigen::Matrix3d::Zero();
        const Eigen::Vector3d c = m / vg;
        const Eigen::Matrix3d cov = second - vg * c * c.transpose();  // about the water's centroid
        const Eigen::Matrix3d inertia = cov.trace() * Eigen::Matrix3d::Identity() - cov;
        return (v / vg) * inertia;  // the box's geometry scaled to the node's volume (as nodeVolumeBelow)
    }
    // Sphere: the water is the bottom cap s = z + R in [0, k] of a sphere of radius R (z along up from the
    // centre); slices are discs of radius² s(2R − s). Integrals in s (no cancellation for a small cap):
    //   V = π (R k² − k³/3),  ∫ s dV = π (2R k³/3 − k⁴/4),  ∫ s² dV = π (R k⁴/2 − k⁵/5),
    //   ∫ x² dV = (π/4) ∫ s²(2R − s)² ds = (π/4)(4R² k³/3 − R k⁴ + k⁵/5)  (a disc: ∫ x² dA = π ρ⁴ / 4).
    const double R = nodeHalfHeight(node, up);
    const double k = std::clamp(h + R, 0.0, 2.0 * R);
    if (!(k > 0)) return Eigen::Matrix3d::Zero();
    const double k2 = k * k, k3 = k2 * k, k4 = k3 * k, k5 = k4 * k;
    const double V = kPi * (R * k2 - k3 / 3.0);
    const double S1 = kPi * (2.0 * R * k3 / 3.0 - k4 / 4.0);
    const double S2 = kPi * (R * k4 / 2.0 - k5 / 5.0);
    const double Sxx = 0.25 * kPi * (4.0 * R * R * k3 / 3.0 - R * k4 + k5 / 5.0);
    if (!(V > 0)) return Eigen::Matrix3d::Zero();
    const double sc = S1 / V;
    const double axial = 2.0 * Sxx;                                  // about the up axis
    const double transverse = Sxx + std::max(0.0, S2 - V * sc * sc); // about a horizontal axis through the centroid
    const Eigen::Matrix3d uu = up * up.transpose();
    return (v / V) * (transverse * (Eigen::Matrix3d::Identity() - uu) + axial * uu);
}

}  // namespace buoyancy
