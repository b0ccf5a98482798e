// Heave added mass against published hydrodynamics, through the public API as a user writes it: the user's own
// btRigidBody with a btBoxShape, one btBuoyancyAction, Y-up and Z-up worlds.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btWaterFrame.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

namespace {

/// The heave period of a free, undamped box released `offset` below its floating level, from the upward crossings
/// of that level over `seconds`, s. up: the world's up axis (gravity −g along it).
double heavePeriod(const btVector3& halfExtents, double density, const btVector3& up, const btBuoyancySettings& settings,
                   double offset, double seconds) {
    const double rho = 1000, g = 9.81;
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(-btScalar(g) * up);
    btFlatWaterSurface water(0.0);
    btBuoyancyWorld buoyancy(&world, &water, btWaterFrame::fromGravity(Eigen::Vector3d(-g * double(up.x()),
                                                                                        -g * double(up.y()),
                                                                                        -g * double(up.z()))),
                             rho);
    // The box's height is its extent along its local y, turned onto the world's up.
    const btQuaternion turn = up.y() > 0.5 ? btQuaternion::getIdentity() : btQuaternion(btVector3(1, 0, 0), btScalar(M_PI / 2));
    btBoxShape shape(halfExtents);
    const double height = 2 * double(halfExtents.y());
    const double mass = density * 8 * double(halfExtents.x() * halfExtents.y() * halfExtents.z());
    btVector3 inertia;
    shape.calculateLocalInertia(btScalar(mass), inertia);
    const double level = height / 2 - height * density / rho;  // the centre's height when floating (Archimedes)
    btDefaultMotionState motion(btTransform(turn, btScalar(level - offset) * up));
    btRigidBody body(btRigidBody::btRigidBodyConstructionInfo(btScalar(mass), &motion, &shape, inertia));
    body.setActivationState(DISABLE_DEACTIVATION);
    world.addRigidBody(&body);
    btBuoyancyAction action(&body, &buoyancy, settings);
    world.addAction(&action);
    std::vector<double> crossings;
    double last = -offset;
    const int frames = int(seconds * 60);
    for (int f = 0; f < frames; ++f) {
        for (int k = 0; k < 4; ++k) {
            world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
            const double y = double(body.getCenterOfMassPosition().dot(up)) - level;
            const double t = (f * 4 + k + 1) / 240.0;
            if (last < 0 && y >= 0) crossings.push_back(t - (y / (y - last)) / 240.0);
            last = y;
        }
    }
    world.removeAction(&action);
    world.removeRigidBody(&body);
    REQUIRE(crossings.size() >= 5);
    return (crossings.back() - crossings.front()) / double(crossings.size() - 1);
}

}  // namespace

TEST_CASE("added mass: a flat square box heaves with the period of a floating plate's added mass (DNV-RP-H103)",
          "[scenarios][added-mass]") {
    // A 2 × 0.5 × 2 m box at 250 kg/m³ floats at a draft of 0.125 m (draft/beam 1/16): its heave added mass is that of
    // its waterplane. DNV-RP-H103 (2011), Table A-2: a square plate of side a accelerating normal to itself in unbounded
    // water has m_a = C_A ρ (π/4) a³ with C_A = 0.579; floating, at high frequency, the free surface halves it (the plate
    // and its mirror image): 0.227 ρ a³ = 1,819 kg, against the box's own 500 kg. The undamped heave period is
    // T = 2π sqrt((m + m_a) / (ρ g A)) = 1.527 s; with the volume rule alone (C_a ρ V_sub = 250 kg) it would be 0.869 s.
    // The default's waterplane term 0.2 ρ A^(3/2) (design.md 2.7) sits 12 % below DNV's high-frequency value, itself the
    // lower end of a shallow body's heave added mass: within 6 %.
    btBuoyancySettings settings;
    settings.dragCoefficient = 0;
    settings.linearDamping = 0;
    settings.radiationDamping = 0;
    const double rho = 1000, g = 9.81, a = 2.0, m = 250.0 * a * a * 0.5;
    const double plate = 0.5 * 0.579 * rho * M_PI / 4 * a * a * a;
    const double reference = 2 * M_PI * std::sqrt((m + plate) / (rho * g * a * a));
    const double volumeRule = 2 * M_PI * std::sqrt((m + 0.5 * rho * a * a * 0.125) / (rho * g * a * a));
    for (const btVector3& up : {btVector3(0, 1, 0), btVector3(0, 0, 1)}) {
        const double T = heavePeriod(btVector3(1.0f, 0.25f, 1.0f), 250.0, up, settings, 0.01, 15.0);
        std::printf("flat square box, %s-up: heave period %.4f s, DNV plate %.4f s (%+.1f %%), volume rule %.4f s\n",
                    up.y() > 0.5 ? "Y" : "Z", T, reference, 100 * (T / reference - 1), volumeRule);
        INFO((up.y() > 0.5 ? "Y-up" : "Z-up"));
        CHECK(T == Approx(reference).epsilon(0.06));
        // The old default (no waterplane term) is caught: 43 % short.
        CHECK(std::abs(T / reference - 1) < 0.5 * std::abs(volumeRule / reference - 1));
    }
    // With the waterplane term off the period is the volume rule's (linear theory, the same formula).
    settings.addedMassWaterplaneCoefficient = 0;
    const double T0 = heavePeriod(btVector3(1.0f, 0.25f, 1.0f), 250.0, btVector3(0, 1, 0), settings, 0.01, 15.0);
    CHECK(T0 == Approx(volumeRule).epsilon(0.005));
}

TEST_CASE("added mass: a light box dropped onto flat water plunges no deeper than the energy it fell with allows",
          "[scenarios][added-mass]") {
    // A 1 × 0.2 × 1 m box at 20 kg/m³ (draft 4 mm) dropped from 5 cm: on touching the water it takes on a heave
    // added mass of 200 kg, fifty times its own 4 kg. Energy bound: the potential energy it loses falling to its
    // floating level, m g (drop + draft), is all the waterplane's spring ½ ρ g A x² can store, so it plunges at most
    // x = sqrt(2 m (drop + draft) / (ρ A)) = 6.6 mm below that level; nor does it rise above its release height. Without
    // the momentum of the water entry (design.md 2.7) it would keep its speed into the water with 51 times the inertia,
    // carrying ½ m_a v² that it never had: 10 cm deep.
    btBuoyancySettings settings;  // the defaults, damping included
    const double rho = 1000, density = 20, height = 0.2, drop = 0.05;
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, -9.81f, 0));
    btFlatWaterSurface water(0.0);
    btBuoyancyWorld buoyancy(&world, &water, rho);
    btBoxShape shape(btVector3(0.5f, 0.1f, 0.5f));
    const double mass = density * height;
    btVector3 inertia;
    shape.calculateLocalInertia(btScalar(mass), inertia);
    const double start = height / 2 + drop;
    btDefaultMotionState motion(btTransform(btQuaternion::getIdentity(), btVector3(0, btScalar(start), 0)));
    btRigidBody body(btRigidBody::btRigidBodyConstructionInfo(btScalar(mass), &motion, &shape, inertia));
    world.addRigidBody(&body);
    btBuoyancyAction action(&body, &buoyancy, settings);
    world.addAction(&action);
    bool touched = false;
    double highest = -1e9, lowest = 1e9;
    for (int k = 0; k < 240 * 4; ++k) {
        world.stepSimulation(btScalar(1.0 / 240), 1, btScalar(1.0 / 240));
        const double y = double(body.getCenterOfMassPosition().y());
        touched = touched || y - height / 2 < 0;
        if (touched) highest = std::max(highest, y), lowest = std::min(lowest, y);
    }
    const double level = height / 2 - height * density / rho;
    std::printf("light box dropped from %.2f m: lowest %.4f m, highest after touching %.4f m, floats at %.4f m, ends at %.4f m\n",
                drop, lowest - level, highest - level, 0.0, double(body.getCenterOfMassPosition().y()) - level);
    REQUIRE(touched);
    const double draft = height * density / rho;
    CHECK(level - lowest <= std::sqrt(2 * mass * (drop + draft) / (rho * 1.0)));
    CHECK(highest < start);
    CHECK(std::abs(double(body.getCenterOfMassPosition().y()) - level) < 0.01);
    world.removeAction(&action);
    world.removeRigidBody(&body);
}
