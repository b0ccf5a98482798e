#pragma once
/// @file HydrostaticsTestCases.h
/// Cases shared by the exact-mesh oracle tests (the moment tree: TreeHydrostaticsTest.cpp; the per-vertex shares:
/// VertexHydrostaticsTest.cpp): named oracle meshes, random poses, the benchmark's scaling sea, and a pose that puts a body
/// across the local waterline of a wave field.

#include <BulletBuoyancy/mesh/TriangleMesh.h>
#include "oracles/OracleMeshes.h"
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace buoyancy_test {

/// An oracle mesh and its name for the messages.
struct NamedMesh {
    const char* name;
    OracleMesh mesh;
};

/// A random rigid pose: rotation by up to π about a random axis, translation up to ±spread in x and z and ±0.3 in y.
inline Eigen::Isometry3d randomPose(std::mt19937& rng, double spread) {
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::Vector3d axis(u(rng), u(rng), u(rng));
    if (axis.norm() < 1e-3) axis = Eigen::Vector3d::UnitY();
    return Eigen::Translation3d(spread * u(rng), 0.3 * u(rng), spread * u(rng)) *
           Eigen::AngleAxisd(M_PI * u(rng), axis.normalized());
}

/// The benchmark's scaling sea (bullet_examples/benchmark/Scaling.h): amplitudes 1, 0.6, 0.35, 0.2 m, wavelengths
/// 60, 35, 20, 10 m.
inline std::vector<btGerstnerWave> p3SeaWaves() {
    return {{1.0, 60.0, 1.0, 0.0, 0.5, 0.0},
            {0.6, 35.0, 0.8, 0.6, 0.5, 1.3},
            {0.35, 20.0, -0.3, 1.0, 0.5, 2.1},
            {0.2, 10.0, 0.6, -0.8, 0.5, 0.4}};
}

/// Vertical range and bounding-box diagonal of posed vertices, m.
struct PosedBounds {
    double lo = 0, hi = 0;  ///< lowest and highest y
    double diag = 0;        ///< bounding-box diagonal
};

/// posedBounds of `posed` (at least one vertex).
inline PosedBounds posedBounds(const std::vector<Eigen::Vector3d>& posed) {
    PosedBounds b;
    b.lo = 1e300;
    b.hi = -1e300;
    Eigen::Vector3d blo = posed[0], bhi = posed[0];
    for (const auto& v : posed) {
        b.lo = std::min(b.lo, v.y());
        b.hi = std::max(b.hi, v.y());
        blo = blo.cwiseMin(v);
        bhi = bhi.cwiseMax(v);
    }
    b.diag = (bhi - blo).norm();
    return b;
}

/// The mean of a mesh's vertices and the largest distance from it to a vertex, m.
struct MeshBall {
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double radius = 0;
};

/// meshBall of `mesh` (at least one vertex).
inline MeshBall meshBall(const buoyancy::TriangleMesh& mesh) {
    MeshBall b;
    for (const auto& v : mesh.vertices) b.centre += v;
    b.centre /= double(mesh.vertices.size());
    for (const auto& v : mesh.vertices) b.radius = std::max(b.radius, (v - b.centre).norm());
    return b;
}

/// randomPose(rng, horizontal), then lifted so that the ball's centre is at the water height under it at time t, plus
/// a uniform random offset within ±offset × radius (drawn after the pose, from the same generator).
inline Eigen::Isometry3d poseAcrossWaterline(std::mt19937& rng, const btWaterSurface& water, double t,
                                             const MeshBall& ball, double horizontal, double offset) {
    Eigen::Isometry3d pose = randomPose(rng, horizontal);
    const Eigen::Vector3d centre = pose * ball.centre;
    double x = centre.x(), z = centre.z(), h = 0;
    water.heights(&x, &z, 1, t, &h);
    pose.translation().y() +=
        h - centre.y() + ball.radius * std::uniform_real_distribution<double>(-offset, offset)(rng);
    return pose;
}

/// Five closed oracle meshes of different kinds (flat faces, a tetrahedron, curved, genus 1, mixed).
inline std::vector<NamedMesh> fiveOracleShapes() {
    return {{"box", oracleBox(1.0, 0.6, 0.8)},
            {"tetrahedron", oracleTetrahedron(0.9)},
            {"sphere", oracleSphere(0.5, 32, 16)},
            {"torus", oracleTorus(0.6, 0.2, 40, 20)},
            {"cylinder", oracleCylinder(0.3, 1.2, 24)}};
}

/// The part of the triangle (a, b, c) with y ≤ h (Sutherland–Hodgman against the plane, written here independently of
/// the library's clipping): its corners in order into poly, their count returned (0, 3 or 4; corners on the plane
/// are kept, crossings added only where an edge goes strictly from one side to the other).
inline int clipTriangleBelow(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double h,
                             Eigen::Vector3d poly[4]) {
    const Eigen::Vector3d* corner[3] = {&a, &b, &c};
    int n = 0;
    for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d& p = *corner[k];
        const Eigen::Vector3d& q = *corner[(k + 1) % 3];
        if (p.y() <= h) poly[n++] = p;
        if ((p.y() < h && q.y() > h) || (p.y() > h && q.y() < h)) poly[n++] = p + (h - p.y()) / (q.y() - p.y()) * (q - p);
    }
    return n;
}

}  // namespace buoyancy_test
