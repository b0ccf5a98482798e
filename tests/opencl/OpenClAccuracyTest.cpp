// The accuracy oracle through the OpenCL path ("the core's accuracy tests pass through the OpenCL
// path in double"): submerged volume and centre of buoyancy of posed meshes from the device's batch, against
// the exact polyhedral oracle of tests/oracles (an independent implementation), at the exact-coverage
// accuracy the core documents (design.md 2.4, docs/accuracy.md: 128² within 0.03 % of the volume).
#include "OpenClTestSupport.h"

#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include "oracles/BulletTestWorld.h"
#include "oracles/PolyhedralOracle.h"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

using namespace buoyancy_test;

TEST_CASE("OpenCL double: submerged volume and centre of buoyancy match the exact polyhedral oracle", "[opencl]") {
    btBuoyancySettings s;
    s.method = btBuoyancyMethod::ExactCoverage;
    s.textureSize = 128;
    struct Case {
        const char* name;
        buoyancy::TriangleMesh mesh;
    };
    const Case cases[] = {{"box", buoyancy::makeBoxMesh(1.0, 0.6, 0.8)},
                          {"sphere", buoyancy::makeSphereMesh(0.5, 48, 24)},
                          {"torus", buoyancy::makeTorusMesh(0.6, 0.2, 48, 24)},
                          {"cylinder", buoyancy::makeCylinderMesh(0.3, 1.0, 48)}};
    double worstV = 0, worstC = 0;
    int evaluated = 0;
    for (const Case& c : cases) {
        const auto shape = btBuoyancyShape::create(c.mesh, s);
        BulletTestWorld w;
        btBuoyantBodySettings body;
        w.add(shape, body, makePose(btVector3(0, 0, 0)), s);
        btOpenClBuoyancyBackend* backend = installTestBackend(w.water(), btOpenClOptions::Precision::Double);
        if (!backend) return;
        btBuoyancyAction& a = w.action(0);
        btRigidBody* rb = w.rigid(0);
        const btTransform meshInCom = a.getMeshInComFrame();
        const OracleMoments dry = oracleDryMoments(c.mesh.vertices, c.mesh.triangles);
        Eigen::Vector3d lo = c.mesh.vertices.front(), hi = lo;
        for (const auto& v : c.mesh.vertices) {
            lo = lo.cwiseMin(v);
            hi = hi.cwiseMax(v);
        }
        const double diagonal = (hi - lo).norm();
        for (double tilt : {0.0, 25.0, 60.0, 90.0}) {
            for (double level : {-0.1, 0.0, 0.1}) {
                // Mesh pose: tilted about a skew axis, then placed so the water y = 0 cuts it at `level`.
                const btTransform meshPose = makePose(btVector3(0.3, btScalar(-level), -0.2), btVector3(1, 0.2, 0.5), tilt);
                rb->setWorldTransform(meshPose * meshInCom.inverse());
                const Eigen::Isometry3d pose = buoyancy::toEigen(rb->getWorldTransform() * meshInCom);
                const Eigen::Vector3d com = buoyancy::toEigen(rb->getCenterOfMassPosition());
                backend->beginSubstep(1.0 / 240);
                buoyancy::HydrostaticsResult h;
                REQUIRE(backend->hydrostatics(a, pose, com, h));
                const OracleMoments sub = oracleSubmergedMoments(oraclePose(c.mesh.vertices, pose), c.mesh.triangles, 0.0);
                REQUIRE(sub.volume > 0.05 * dry.volume);
                worstV = std::max(worstV, std::abs(h.submerged_volume - sub.volume) / dry.volume);
                worstC = std::max(worstC, (h.centre_of_buoyancy - sub.centroid).norm() / diagonal);
                // Flat water: the vertical force is ρ g V_sub for any samples (design.md 2.3).
                CHECK(h.force.y() == Approx(1000 * 9.81 * h.submerged_volume).epsilon(1e-9));
                ++evaluated;
            }
        }
    }
    std::printf("[opencl] oracle through the device (exact-coverage 128, double): worst submerged volume %.3g %% of V, "
                "centre of buoyancy %.3g %% of the diagonal, %d poses\n",
                100 * worstV, 100 * worstC, evaluated);
    CHECK(worstV < 3e-4);  // 0.03 %
    CHECK(worstC < 1e-3);  // 0.1 %
}
