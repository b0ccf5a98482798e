// A node's water has its own inertia (follow-up; paper eq. 17 only has point masses): the rigid
// inertia of its free-surface shape about its centroid. Oracles: textbook formulas (half-filled box, a
// hemisphere's 83/320 m R², a full sphere's 2/5 m R²), a triangular prism from the triangle second-moment
// formula, and a general spherical cap by numerical quadrature over slices written here.
#include <catch2/catch.hpp>

#include <BulletBuoyancy/graph/NodeLevel.h>
#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/graph/WaterGraphState.h>
#include <BulletBuoyancy/graph/WaterMassProperties.h>

#include <Eigen/Geometry>

#include <cmath>

using namespace buoyancy;

namespace {

constexpr double kPi = 3.14159265358979323846;

WaterNode boxNode(const Eigen::Vector3d& size, const Eigen::Vector3d& pos = Eigen::Vector3d::Zero()) {
    WaterNode n;
    n.name = "box";
    n.shape = WaterNodeShape::Box;
    n.size = size;
    n.capacity = size.prod();
    n.position = pos;
    return n;
}

WaterNode sphereNode(double capacity, const Eigen::Vector3d& pos = Eigen::Vector3d::Zero()) {
    WaterNode n;
    n.name = "sphere";
    n.capacity = capacity;
    n.position = pos;
    return n;
}

double relErr(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return (a - b).norm() / b.norm(); }

/// A spherical cap of height k at the bottom of a sphere of radius R, by Simpson's rule over horizontal
/// slices (discs of radius² R² − z²): volume, centroid height (from the sphere centre, along up) and the
/// axial / transverse inertia about the centroid for unit density.
void capByQuadrature(double R, double k, double& V, double& zc, double& axial, double& transverse) {
    const int n = 20000;  // even
    const double z0 = -R, h = k / n;
    double v = 0, mz = 0, mzz = 0, mxx = 0;
    for (int i = 0; i <= n; ++i) {
        const double z = z0 + i * h;
        const double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        const double r2 = std::max(0.0, R * R - z * z);
        v += w * kPi * r2;
        mz += w * kPi * r2 * z;
        mzz += w * kPi * r2 * z * z;
        mxx += w * kPi * r2 * r2 / 4;  // ∫ x² over a disc of radius r: π r⁴ / 4
    }
    v *= h / 3;
    mz *= h / 3;
    mzz *= h / 3;
    mxx *= h / 3;
    V = v;
    zc = mz / v;
    axial = 2 * mxx;
    transverse = mxx + (mzz - v * zc * zc);
}

}  // namespace

TEST_CASE("node inertia: a half-filled upright box is a box of half the height", "[graph]") {
    const Eigen::Vector3d size(2.0, 1.2, 0.8);
    const WaterNode node = boxNode(size);
    const double v = 0.5 * size.prod();
    const Eigen::Matrix3d I = nodeWaterInertia(node, Eigen::Vector3d::UnitY(), v);
    // Textbook cuboid a × b × c about its centre: m/12 (b² + c², a² + c², a² + b²), here b = 0.6, m = V (ρ = 1).
    const double a = size.x(), b = 0.5 * size.y(), c = size.z();
    const Eigen::Matrix3d expected = Eigen::Vector3d(v / 12 * (b * b + c * c), v / 12 * (a * a + c * c),
                                                     v / 12 * (a * a + b * b)).asDiagonal();
    CHECK(relErr(I, expected) < 1e-12);
    // Full: the whole box.
    const Eigen::Matrix3d full = nodeWaterInertia(node, Eigen::Vector3d::UnitY(), node.capacity);
    const double m = node.capacity, A = size.x(), B = size.y(), C = size.z();
    CHECK(relErr(full, Eigen::Matrix3d(Eigen::Vector3d(m / 12 * (B * B + C * C), m / 12 * (A * A + C * C),
                                                       m / 12 * (A * A + B * B)).asDiagonal())) < 1e-12);
    CHECK(nodeWaterInertia(node, Eigen::Vector3d::UnitY(), 0.0).norm() == 0.0);
}

TEST_CASE("node inertia: a half-filled cube heeled 45 degrees holds a triangular prism", "[graph]") {
    const double a = 0.9;
    const WaterNode node = boxNode(Eigen::Vector3d(a, a, a));
    const Eigen::Vector3d up = Eigen::Vector3d(1, 1, 0).normalized();  // world up in body axes
    const double v = 0.5 * a * a * a;
    const Eigen::Matrix3d I = nodeWaterInertia(node, up, v);
    // The water is x + y ≤ 0: the right triangle (−a/2, −a/2), (a/2, −a/2), (−a/2, a/2) extruded over z.
    // Triangle: ∫ p pᵀ dA = A/12 (Σ p_i p_iᵀ + s sᵀ), s = Σ p_i (standard polygon moment formula).
    const Eigen::Vector2d p[3] = {{-a / 2, -a / 2}, {a / 2, -a / 2}, {-a / 2, a / 2}};
    const double A = a * a / 2;
    const Eigen::Vector2d s = p[0] + p[1] + p[2];
    Eigen::Matrix2d S2 = s * s.transpose();
    for (const auto& q : p) S2 += q * q.transpose();
    S2 *= A / 12;
    const Eigen::Vector2d c = s / 3;  // centroid
    const Eigen::Matrix2d cov2 = S2 - A * c * c.transpose();
    // Prism of length a: ∫ xxᵀ dV = a · cov2 (in x, y); ∫ z² dV = A a³ / 12; cross terms with z vanish.
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    cov.topLeftCorner<2, 2>() = a * cov2;
    cov(2, 2) = A * a * a * a / 12;
    const Eigen::Matrix3d expected = cov.trace() * Eigen::Matrix3d::Identity() - cov;
    CHECK(relErr(I, expected) < 1e-12);
    // Its centroid too (the free-surface centre).
    const Eigen::Vector3d centroid = nodeWaterCentroid(node, up, v);
    CHECK((centroid - Eigen::Vector3d(c.x(), c.y(), 0)).norm() < 1e-12);
}

TEST_CASE("node inertia: sphere cap vs the hemisphere, the full sphere and quadrature", "[graph]") {
    const double C = 0.3;
    const double R = std::cbrt(3 * C / (4 * kPi));
    const WaterNode node = sphereNode(C);
    const Eigen::Vector3d up = Eigen::Vector3d(0.3, 0.8, -0.52).normalized();
    const Eigen::Matrix3d uu = up * up.transpose();
    auto tensor = [&](double axial, double transverse) {
        return Eigen::Matrix3d(transverse * (Eigen::Matrix3d::Identity() - uu) + axial * uu);
    };
    // Hemisphere (half full), about its centroid: axial 2/5 m R², transverse 83/320 m R² (textbook).
    const double mh = C / 2;
    CHECK(relErr(nodeWaterInertia(node, up, mh), tensor(0.4 * mh * R * R, 83.0 / 320.0 * mh * R * R)) < 1e-9);
    // Full: 2/5 m R² about every axis.
    CHECK(relErr(nodeWaterInertia(node, up, C), tensor(0.4 * C * R * R, 0.4 * C * R * R)) < 1e-9);
    // Caps of several heights against quadrature (the volume given is the quadrature's, so the cap matches).
    for (double k : {0.05 * R, 0.3 * R, 0.7 * R, 1.4 * R, 1.9 * R}) {
        double V, zc, axial, transverse;
        capByQuadrature(R, k, V, zc, axial, transverse);
        INFO("k/R = " << k / R);
        CHECK(relErr(nodeWaterInertia(node, up, V), tensor(axial, transverse)) < 1e-7);
        CHECK((nodeWaterCentroid(node, up, V) - zc * up).norm() < 1e-9 * R);
    }
}

TEST_CASE("water mass properties include each node's own inertia (shape model) and not with points", "[graph]") {
    // One half-filled upright box node off the origin: the graph's water inertia about its centre is the node's.
    WaterGraph g;
    WaterNode n = boxNode(Eigen::Vector3d(1.0, 0.5, 0.4), Eigen::Vector3d(0.3, -0.2, 0.1));
    n.water = 0.5 * n.capacity;
    g.nodes = {n};
    WaterGraphState s(g);
    s.setPose(Eigen::Isometry3d::Identity());
    const double rho = 1000;
    const MassProperties mp = waterMassProperties(s, rho);
    const double m = rho * n.water, a = 1.0, b = 0.25, c = 0.4;
    const Eigen::Matrix3d expected =
        Eigen::Vector3d(m / 12 * (b * b + c * c), m / 12 * (a * a + c * c), m / 12 * (a * a + b * b)).asDiagonal();
    CHECK(mp.mass == Approx(m));
    CHECK((mp.centre - Eigen::Vector3d(0.3, -0.2 - 0.125, 0.1)).norm() < 1e-12);
    CHECK(relErr(mp.inertia, expected) < 1e-12);
    // Paper eq. 17 (point masses): a single node has no inertia about its own centre.
    g.inertia = WaterInertiaModel::PointMass;
    WaterGraphState p(g);
    p.setPose(Eigen::Isometry3d::Identity());
    CHECK(waterMassProperties(p, rho).inertia.norm() < 1e-12);
}
