// Deformable bodies (paper Fig. 17): re-baking through the fixed texel → (triangle, barycentric) map
// gives what a fresh bake of the deformed mesh through the same UVs gives (CPU and device), its volume is the
// deformed mesh's exact polyhedral volume (oracle), and a body whose samples follow the vertices gets the
// buoyancy of the deformed shape on the CPU and on the device alike.
#include "OpenClTestSupport.h"

#include <BulletBuoyancy/atlas/UvLayout.h>
#include <BulletBuoyancy/bake/BakeSamples.h>
#include <BulletBuoyancy/bake/DeformableRebake.h>
#include <BulletBuoyancy/bullet/btBuoyancyDeformable.h>
#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include "oracles/BulletTestWorld.h"
#include "oracles/PolyhedralOracle.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

using namespace buoyancy_test;

namespace {

/// A balloon-like deformation: anisotropic inflation plus a wobble, written here (independent of the code
/// under test). Triangles stay non-degenerate.
std::vector<Eigen::Vector3d> deform(const std::vector<Eigen::Vector3d>& v, double s) {
    std::vector<Eigen::Vector3d> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) {
        const Eigen::Vector3d& p = v[i];
        const double wobble = 1.0 + 0.1 * s * std::sin(3 * p.x() + 1) * std::cos(2 * p.z());
        out[i] = Eigen::Vector3d(p.x() * (1 + 0.3 * s), p.y() * (1 + 0.6 * s), p.z() * (1 + 0.1 * s)) * wobble;
    }
    return out;
}

/// Largest difference between two sample sets: positions relative to `length`, area vectors and areas
/// relative to the mean sample area.
double sampleDifference(const buoyancy::SurfaceSamples& a, const buoyancy::SurfaceSamples& b, double length) {
    REQUIRE(a.size() == b.size());
    double meanArea = 0;
    for (double x : b.area) meanArea += x;
    meanArea /= double(b.size());
    double d = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        REQUIRE(a.texel[i] == b.texel[i]);
        d = std::max(d, (Eigen::Vector3d(a.px[i], a.py[i], a.pz[i]) - Eigen::Vector3d(b.px[i], b.py[i], b.pz[i])).norm() / length);
        d = std::max(d, (Eigen::Vector3d(a.ax[i], a.ay[i], a.az[i]) - Eigen::Vector3d(b.ax[i], b.ay[i], b.az[i])).norm() / meanArea);
        d = std::max(d, std::abs(a.area[i] - b.area[i]) / meanArea);
    }
    return d;
}

}  // namespace

TEST_CASE("deformable: re-bake through the fixed map equals a fresh bake of the deformed mesh (CPU)", "[opencl][bake]") {
    for (const buoyancy::BakeMethod method : {buoyancy::BakeMethod::ExactCoverage, buoyancy::BakeMethod::TexelCentre}) {
        const buoyancy::TriangleMesh mesh = buoyancy::makeSphereMesh(0.5, 24, 12);
        const int n = 64;
        const buoyancy::UvLayout layout = buoyancy::chooseUvLayout(mesh, n, true);
        const buoyancy::RebakeMap map = buoyancy::buildRebakeMap(mesh, layout.corner_uvs, n, method);
        // At rest: the map reproduces the baker's samples.
        buoyancy::SurfaceSamples rebaked;
        buoyancy::rebakeSamples(map, mesh.vertices, rebaked);
        CHECK(sampleDifference(rebaked, buoyancy::bakeSurfaceSamples(mesh, layout.corner_uvs, n, method), 1.0) < 1e-12);
        // Deformed: the same as baking the deformed mesh from scratch through the same UVs.
        buoyancy::TriangleMesh moved = mesh;
        moved.vertices = deform(mesh.vertices, 1.0);
        buoyancy::rebakeSamples(map, moved.vertices, rebaked);
        const buoyancy::SurfaceSamples fresh = buoyancy::bakeSurfaceSamples(moved, layout.corner_uvs, n, method);
        const double d = sampleDifference(rebaked, fresh, 1.0);
        std::printf("[opencl] deformable %s: re-bake vs fresh bake %.3g\n", buoyancy::bakeMethodName(method), d);
        CHECK(d < 1e-12);
    }
}

TEST_CASE("deformable: btBuoyancyDeformable follows the vertices, its volume is the deformed mesh's", "[opencl][bake]") {
    btBuoyancySettings s;
    s.method = btBuoyancyMethod::ExactCoverage;
    s.textureSize = 128;
    const auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.5, 24, 12), s);
    const auto skin = btBuoyancyDeformable::create(*shape, s);
    REQUIRE(skin->getSamples().size() == shape->getSamples().size());
    const buoyancy::TriangleMesh& mesh = shape->getMesh();
    // At rest the samples are the shape's (the same bake); volumes are within the exact-coverage accuracy of the
    // exact polyhedral volume (a texel mixing pieces of non-coplanar triangles is not exact: design.md 2.1).
    CHECK(skin->getVolume() == Approx(shape->getVolume()).epsilon(1e-12));
    CHECK(skin->getVolume() == Approx(oracleDryMoments(mesh.vertices, mesh.triangles).volume).epsilon(3e-4));
    const std::uint64_t v0 = skin->getVersion();
    const std::vector<Eigen::Vector3d> moved = deform(mesh.vertices, 0.8);
    skin->setVertices(moved);
    CHECK(skin->getVersion() == v0 + 1);
    const double movedVolume = oracleDryMoments(moved, mesh.triangles).volume;
    CHECK(movedVolume > 1.5 * shape->getVolume());
    CHECK(skin->getVolume() == Approx(movedVolume).epsilon(3e-4));
    CHECK(skin->getBoundsRadius() > shape->getBoundsRadius());
    // Bad input: named, nothing changed.
    std::vector<Eigen::Vector3d> bad = moved;
    bad.pop_back();
    CHECK_THROWS_WITH(skin->setVertices(bad), Catch::Contains("vertices given"));
    bad = moved;
    bad[3].y() = std::nan("");
    CHECK_THROWS_WITH(skin->setVertices(bad), Catch::Contains("vertex 3 is not finite"));
    CHECK(skin->getVersion() == v0 + 1);
    // An action takes only a deformable of its own shape's sample count.
    {
        BulletTestWorld w;
        const auto other = btBuoyancyShape::create(buoyancy::makeBoxMesh(1, 1, 1), s);
        w.add(other, btBuoyantBodySettings(), makePose(btVector3(0, 0, 0)), s);
        CHECK_THROWS_WITH(w.action(0).setDeformable(skin), Catch::Contains("samples, the action's shape has"));
        CHECK(w.action(0).getDeformable() == nullptr);
    }
    // A shape without a texture cannot deform.
    btBuoyancySettings exact;
    exact.method = btBuoyancyMethod::ExactMesh;
    CHECK_THROWS_WITH(btBuoyancyDeformable::create(*btBuoyancyShape::create(buoyancy::makeBoxMesh(1, 1, 1), exact), exact),
                      Catch::Contains("exact-mesh"));
}

TEST_CASE("deformable: device re-bake matches the CPU re-bake, a deformed body floats the same on CPU and device",
          "[opencl][bake]") {
    btBuoyancySettings s;
    s.method = btBuoyancyMethod::ExactCoverage;
    s.textureSize = 128;
    s.waterPatchNodes = 0;
    const auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(0.5, 24, 12), s);
    const auto skin = btBuoyancyDeformable::create(*shape, s);
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 300;
    w.add(shape, body, makePose(btVector3(0, 0.05, 0), btVector3(1, 0, 0), 15), s);
    w.action(0).setDeformable(skin);
    btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Double);
    if (!backend) return;

    const std::vector<Eigen::Vector3d> moved = deform(shape->getMesh().vertices, 0.6);
    skin->setVertices(moved);
    buoyancy::SurfaceSamples onDevice;
    backend->rebakeOnDevice(skin->getMap(), moved, onDevice);
    const double d = sampleDifference(onDevice, skin->getSamples(), 1.0);
    std::printf("[opencl] deformable: device re-bake vs CPU re-bake %.3g\n", d);
    CHECK(d < 1e-12);

    // The action on the deformed samples: CPU and device agree, and the device re-baked from the vertices.
    std::vector<btBuoyancyResult> cpu, dev;
    std::uint64_t answered = 0;
    const std::uint64_t rebakes = backend->stats().rebakes;
    evaluateBoth(w.world(), w.water(), *backend, 1.0 / 240, cpu, dev, answered);
    CHECK(answered == 1);
    CHECK(backend->stats().rebakes == rebakes + 1);
    const double V = skin->getVolume(), weight = 1000 * 9.81 * V;
    CHECK(resultDifference(cpu[0], dev[0], weight, 1.0, V) < 1e-6);
    // The buoyancy is that of the deformed shape: the same as a rigid shape baked from the deformed mesh.
    buoyancy::TriangleMesh movedMesh = shape->getMesh();
    movedMesh.vertices = moved;
    const auto rigid = btBuoyancyShape::create(movedMesh, s);
    const btBuoyantBody& b0 = w.body(0);
    const Eigen::Isometry3d pose = buoyancy::toEigen(b0.getMeshWorldTransform());
    buoyancy::SampleWorkspace ws;
    const buoyancy::HydrostaticsResult ref = buoyancy::sampledHydrostatics(
        rigid->getSamples(), pose, *w.water().getWater(), w.water().getTime(), 1000, 9.81,
        buoyancy::toEigen(b0.getRigidBody()->getCenterOfMassPosition()), ws);
    CHECK(std::abs(double(dev[0].submergedVolume) - ref.submerged_volume) < 1e-6 * V);
    CHECK(double((dev[0].buoyancyForce - buoyancy::toBullet(ref.force)).length()) < 1e-6 * weight);
    // The deformed balloon displaces more than the rest shape at the same pose.
    buoyancy::SampleWorkspace ws2;
    const buoyancy::HydrostaticsResult rest = buoyancy::sampledHydrostatics(
        shape->getSamples(), pose, *w.water().getWater(), w.water().getTime(), 1000, 9.81,
        buoyancy::toEigen(b0.getRigidBody()->getCenterOfMassPosition()), ws2);
    CHECK(ref.submerged_volume > 1.2 * rest.submerged_volume);
}
