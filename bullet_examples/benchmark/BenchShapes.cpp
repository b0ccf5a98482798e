#include "benchmark/BenchShapes.h"

#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <utility>

namespace buoyancy::bench {

TriangleMesh subdivideMesh(const TriangleMesh& mesh) {
    TriangleMesh out;
    out.vertices = mesh.vertices;
    std::map<std::pair<int, int>, int> midpoint;  // shared edge midpoints keep the mesh welded (closed)
    auto mid = [&](int a, int b) {
        const std::pair<int, int> key(std::min(a, b), std::max(a, b));
        const auto it = midpoint.find(key);
        if (it != midpoint.end()) return it->second;
        out.vertices.push_back(0.5 * (mesh.vertices[a] + mesh.vertices[b]));
        const int id = int(out.vertices.size()) - 1;
        midpoint.emplace(key, id);
        return id;
    };
    const bool uv = mesh.hasUvs();
    out.triangles.reserve(4 * mesh.triangleCount());
    if (uv) out.corner_uvs.reserve(12 * mesh.triangleCount());
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const int a = mesh.triangles[t][0], b = mesh.triangles[t][1], c = mesh.triangles[t][2];
        const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
        out.triangles.emplace_back(a, ab, ca);
        out.triangles.emplace_back(ab, b, bc);
        out.triangles.emplace_back(ca, bc, c);
        out.triangles.emplace_back(ab, bc, ca);
        if (uv) {
            const Eigen::Vector2d ua = mesh.corner_uvs[3 * t], ub = mesh.corner_uvs[3 * t + 1], uc = mesh.corner_uvs[3 * t + 2];
            const Eigen::Vector2d uab = 0.5 * (ua + ub), ubc = 0.5 * (ub + uc), uca = 0.5 * (uc + ua);
            for (const Eigen::Vector2d& u : {ua, uab, uca, uab, ub, ubc, uca, ubc, uc, uab, ubc, uca}) out.corner_uvs.push_back(u);
        }
    }
    return out;
}

TriangleMesh loadBoatHull() {
    const std::string path = std::string(BUOYANCY_BENCH_SOURCE_DIR) + "/bullet_examples/models/boat_hull.obj";
    TriangleMesh mesh = importMeshFile(path);
    prepareMesh(mesh, path);
    return mesh;
}

TriangleMesh loadLowPolyHull() {
    const std::string path = std::string(BUOYANCY_BENCH_SOURCE_DIR) + "/bullet_examples/models/hull_lowpoly.obj";
    TriangleMesh mesh = importMeshFile(path);
    prepareMesh(mesh, path);
    return mesh;
}

std::vector<BenchShape> waveBenchShapes(std::vector<std::string>& warnings) {
    std::vector<BenchShape> shapes;
    shapes.push_back({"box", "makeBoxMesh(2, 0.6, 1)", makeBoxMesh(2.0, 0.6, 1.0)});
    // A log: the cylinder along y turned to lie along x ((x, y, z) -> (y, -x, z), a rotation: still outward).
    TriangleMesh log = makeCylinderMesh(0.4, 3.0, 16);
    for (Eigen::Vector3d& v : log.vertices) v = Eigen::Vector3d(v.y(), -v.x(), v.z());
    shapes.push_back({"cylinder", "makeCylinderMesh(0.4, 3, 16) lying along x", std::move(log)});
    try {
        shapes.push_back({"hull", "bullet_examples/models/hull_lowpoly.obj", loadLowPolyHull()});
    } catch (const std::exception& e) {
        warnings.push_back(std::string("hull left out: ") + e.what());
    }
    return shapes;
}

std::vector<BenchShape> benchShapes(bool quick, std::vector<std::string>& warnings) {
    std::vector<BenchShape> shapes;
    shapes.push_back({"box", "makeBoxMesh(2, 0.6, 1)", makeBoxMesh(2.0, 0.6, 1.0)});
    shapes.push_back({"sphere", "makeSphereMesh(0.5, 64, 32)", makeSphereMesh(0.5, 64, 32)});
    if (!quick) shapes.push_back({"torus", "makeTorusMesh(1, 0.3, 64, 32)", makeTorusMesh(1.0, 0.3, 64, 32)});
    try {
        shapes.push_back({"boat", "bullet_examples/models/boat_hull.obj", loadBoatHull()});
    } catch (const std::exception& e) {
        warnings.push_back(std::string("boat left out: ") + e.what());
    }
    if (quick) return shapes;
    try {
        const std::string path = std::string(BUOYANCY_BENCH_ASSIMP_MODELS_DIR) + "/Collada/duck.dae";
        TriangleMesh duck = importMeshFile(path);
        prepareMesh(duck, path);
        TriangleMesh duck4 = subdivideMesh(duck);
        shapes.push_back({"duck", "assimp-testmodels Collada/duck.dae", std::move(duck)});
        shapes.push_back({"duck-x4", "duck.dae, flat 1:4 subdivision (same solid)", std::move(duck4)});
    } catch (const std::exception& e) {
        warnings.push_back(std::string("duck left out: ") + e.what());
    }
    shapes.push_back({"torus-fine", "makeTorusMesh(1, 0.3, 160, 64)", makeTorusMesh(1.0, 0.3, 160, 64)});
    return shapes;
}

std::vector<BenchPose> benchPoses(const TriangleMesh& mesh, const std::vector<double>& draftFractions,
                                  const std::vector<double>& heelDegrees) {
    Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
    for (const auto& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    std::vector<BenchPose> poses;
    for (double heel : heelDegrees) {
        const Eigen::Matrix3d R = Eigen::AngleAxisd(heel * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
        double ymin = 1e300, ymax = -1e300;
        for (const auto& v : mesh.vertices) {
            const double y = (R * (v - centre)).y();
            ymin = std::min(ymin, y);
            ymax = std::max(ymax, y);
        }
        for (double f : draftFractions) {
            BenchPose p;
            char id[64];
            std::snprintf(id, sizeof id, "d%.2f_h%g", f, heel);
            p.id = id;
            p.draftFraction = f;
            p.heelDegrees = heel;
            // world = R (x − centre) + t, with t chosen so that the lowest point is at −f·H below y = 0.
            const double lift = -(ymin + f * (ymax - ymin));
            p.pose.linear() = R;
            p.pose.translation() = -R * centre + Eigen::Vector3d(0, lift, 0);
            poses.push_back(p);
        }
    }
    return poses;
}

std::vector<BenchPose> waveBenchPoses(const TriangleMesh& mesh, const btWaterSurface& water,
                                      const std::vector<double>& times, const std::vector<double>& offsetFractions,
                                      const std::vector<double>& heelDegrees) {
    Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
    for (const auto& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    std::vector<BenchPose> poses;
    for (std::size_t i = 0; i < times.size(); ++i)
        for (std::size_t j = 0; j < offsetFractions.size(); ++j) {
            const double heel = heelDegrees.empty() ? 0.0 : heelDegrees[(i + j) % heelDegrees.size()];
            const Eigen::Matrix3d R = Eigen::AngleAxisd(heel * M_PI / 180.0, Eigen::Vector3d::UnitX()).toRotationMatrix();
            double ymin = 1e300, ymax = -1e300;
            for (const auto& v : mesh.vertices) {
                const double y = (R * (v - centre)).y();
                ymin = std::min(ymin, y);
                ymax = std::max(ymax, y);
            }
            const double t = times[i], o = offsetFractions[j];
            BenchPose p;
            char id[80];
            std::snprintf(id, sizeof id, "t%.2f_dy%.2f_heel%g", t, o, heel);
            p.id = id;
            p.heelDegrees = heel;
            p.time = t;
            p.offsetFraction = o;
            // world = R (x − centre) + (0, η(0, 0, t) + o·H, 0): the heeled bounding-box centre over the origin.
            p.pose.linear() = R;
            p.pose.translation() = -R * centre + Eigen::Vector3d(0, water.height(0.0, 0.0, t) + o * (ymax - ymin), 0);
            poses.push_back(p);
        }
    return poses;
}

double boundingBoxDiagonal(const TriangleMesh& mesh) {
    Eigen::Vector3d lo = mesh.vertices.front(), hi = lo;
    for (const auto& v : mesh.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    return (hi - lo).norm();
}

}  // namespace buoyancy::bench
