// The density-map mass model ("solid / shell / density map"): a shell whose areal density varies over
// the surface. Oracle: a hemispherical shell has mass σ 2πR² and its centre R/2 from the sphere's centre.
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <catch2/catch.hpp>

#include <cmath>

TEST_CASE("density map: a sphere heavy on its lower half has the hemispherical shell's mass and centre",
          "[bullet][massprops]") {
    const double R = 0.5, sigma = 10.0;  // kg/m²
    const auto method = GENERATE(btBuoyancyMethod::ExactMesh, btBuoyancyMethod::ExactCoverage);
    btBuoyancySettings bs;
    bs.method = method;
    auto shape = btBuoyancyShape::create(buoyancy::makeSphereMesh(R, 128, 64), bs);
    btBuoyantBodySettings body;
    body.massModel = btBuoyantMassModel::DensityMap;
    body.arealDensity = [&](const Eigen::Vector3d& p) { return p.y() < 0 ? sigma : 0.0; };
    const buoyancy::MassProperties mp = btBuoyantBodyMassProperties(*shape, body);
    INFO(btBuoyancyMethodName(method));
    CHECK(mp.mass == Approx(sigma * 2 * M_PI * R * R).epsilon(0.01));
    CHECK(mp.centre.y() == Approx(-R / 2).epsilon(0.01));
    CHECK(std::abs(mp.centre.x()) < 1e-3 * R);
    CHECK(std::abs(mp.centre.z()) < 1e-3 * R);
    // A given mass rescales the map and keeps its centre.
    body.mass = 3.0;
    const buoyancy::MassProperties scaled = btBuoyantBodyMassProperties(*shape, body);
    CHECK(scaled.mass == Approx(3.0));
    CHECK(scaled.centre.y() == Approx(mp.centre.y()));
    // The body floats with its heavy half down: build it and check Bullet got the same mass.
    btBuoyantBody b(shape, body, btTransform::getIdentity());
    CHECK(b.getMass() == Approx(3.0));
}

TEST_CASE("density map: bad maps are refused with the field's name", "[bullet][massprops]") {
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1, 1, 1));
    btBuoyantBodySettings body;
    body.massModel = btBuoyantMassModel::DensityMap;
    CHECK_THROWS_WITH(btBuoyantBodyMassProperties(*shape, body), Catch::Contains("arealDensity"));
    body.arealDensity = [](const Eigen::Vector3d&) { return -1.0; };
    CHECK_THROWS_WITH(btBuoyantBodyMassProperties(*shape, body), Catch::Contains("arealDensity"));
    body.arealDensity = [](const Eigen::Vector3d&) { return std::nan(""); };
    CHECK_THROWS_WITH(btBuoyantBodyMassProperties(*shape, body), Catch::Contains("arealDensity"));
}
