// The working range of sizes and densities, in this build's precision (the test runs in the float and the double
// build): a cube of side 1 mm … 100 km and density 1 … 20,000 kg/m³ placed at its Archimedes draft stays there (or,
// denser than water, sinks with a finite state), or is refused with the documented reason. The expected draft is
// Archimedes' (draft / L = ρ_body / ρ_water); whether a body must be refused is decided here from its inertia
// (ρ L⁵ / 6 against the single-precision bound), not by asking the library.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyInvariants.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <memory>

using Catch::Matchers::Contains;

TEST_CASE("scale range: 1 mm to 100 km, 1 to 20,000 kg/m^3, floats at its draft or is refused with the reason",
          "[bullet][dynamics]") {
    const bool single = sizeof(btScalar) == sizeof(float);
    const double rhoWater = 1000, g = 9.81;
    int ran = 0, refused = 0, stiff = 0;
    for (double L : {1e-3, 1e-2, 1e-1, 1.0, 10.0, 100.0, 1e3, 1e4, 1e5}) {
        for (double rho : {1.0, 500.0, 950.0, 20000.0}) {
            INFO("side " << L << " m, density " << rho << " kg/m^3");
            btDefaultCollisionConfiguration config;
            btCollisionDispatcher dispatcher(&config);
            btDbvtBroadphase broadphase;
            btSequentialImpulseConstraintSolver solver;
            btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
            world.setGravity(btVector3(0, btScalar(-g), 0));
            btFlatWaterSurface water(0.0);
            btBuoyancyWorld buoyancy(&world, &water, rhoWater);

            const bool floats = rho < rhoWater;
            // Centre height at rest: the cube's bottom at −draft, draft = L ρ/ρ_w.
            const double y0 = floats ? L * (0.5 - rho / rhoWater) : 0.0;
            btBuoyantBodySettings settings;
            settings.density = rho;
            btTransform pose;
            pose.setIdentity();
            pose.setOrigin(btVector3(0, btScalar(y0), 0));
            // Explicit integration's limit, which no scale check can lift: a floating cube's heave frequency
            // ω² = ρ_w g / (ρ L) (waterplane stiffness over mass, added mass left out) against the 240 Hz substep.
            // Beyond ω dt = 2 the heave is unstable (very light, very small bodies: 1 cm at 1 kg/m³).
            const double dt = 1.0 / 240.0;
            if (floats && std::sqrt(rhoWater * g / (rho * L)) * dt > 2.0) {
                ++stiff;
                continue;
            }
            const double inertia = rho * std::pow(L, 5) / 6.0;  // a solid cube about its centre
            const bool outOfRange = single && inertia > 1e18;
            std::unique_ptr<btBuoyantBody> body;
            if (outOfRange) {
                CHECK_THROWS_WITH(std::make_unique<btBuoyantBody>(btBuoyancyShape::create(buoyancy::makeBoxMesh(L, L, L)),
                                                                  settings, pose),
                                  Contains("beyond single-precision Bullet's range") && Contains("double-precision"));
                ++refused;
                continue;
            }
            REQUIRE_NOTHROW(body = std::make_unique<btBuoyantBody>(
                                btBuoyancyShape::create(buoyancy::makeBoxMesh(L, L, L)), settings, pose));
            btBuoyancyAction action(*body, &buoyancy);
            world.addRigidBody(body->getRigidBody());
            world.addAction(&action);
            const double seconds = 1.0;
            for (int i = 0; i < 60; ++i) world.stepSimulation(btScalar(1.0 / 60.0), 4, btScalar(1.0 / 240.0));
            const btRigidBody* rb = body->getRigidBody();
            CHECK(btBuoyancyCheckBody(*rb).empty());
            const double y = double(rb->getCenterOfMassPosition().y());
            const double vy = double(rb->getLinearVelocity().y());
            if (floats) {
                // At rest where Archimedes puts it (float rounding of the position: 1e-6 relative to the side).
                CHECK(std::abs(y - y0) < 1e-3 * L);
                // Bullet's stored velocity holds this substep's buoyancy kick but not the next gravity kick: up to
                // g dt off at rest.
                CHECK(std::abs(vy) < 1.01 * g * dt + 1e-3 * std::sqrt(g * L));
                // Upright only where upright is stable: a cube floating face down has a negative metacentric height
                // for 0.211 < ρ/ρ_w < 0.789 (BM = L / (12 s), BG = L (1 − s) / 2), so at 500 kg/m³ the rounding of
                // the start tips it over (at 1 mm within the second: its growth rate is sqrt(g / (2 L)) ≈ 70 /s).
                const double s = rho / rhoWater;
                if (1.0 / (12.0 * s) > (1.0 - s) / 2.0) CHECK(std::abs(double(rb->getOrientation().getAngle())) < 1e-3);
            } else {
                // Sinking: downward, no faster than free fall.
                CHECK(vy < 0);
                CHECK(std::abs(vy) <= g * seconds * 1.001);
                CHECK(y < 0);
            }
            world.removeAction(&action);
            world.removeRigidBody(body->getRigidBody());
            ++ran;
        }
    }
    std::printf("scale range (%s precision): %d bodies simulated, %d refused, %d too stiff for 240 Hz\n",
                single ? "single" : "double", ran, refused, stiff);
    CHECK(stiff == 2);                   // 1 mm and 1 cm at 1 kg/m³
    CHECK(refused == (single ? 9 : 0));  // float: I = ρ L⁵/6 > 1e18 (1 km at 20,000 kg/m³, and all of 10 and 100 km)
}
