// Buoyancy on the links of a btMultiBody: a chain of boxes joined by hinges settles flat at the single box's
// Archimedes draft, and the parts of a straight chain at a tilted pose add up to one box of the same size.
#include "MultiBodyChainScene.h"

#include <BulletBuoyancy/bullet/btBuoyancyImmediate.h>
#include <BulletBuoyancy/bullet/btBuoyancyMultiBodyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <vector>

using buoyancy_test::ChainScene;

TEST_CASE("multibody: a chain of boxes joined by hinges settles flat at the single box's draft", "[bullet][multibody]") {
    const btVector3 half(0.5f, 0.2f, 0.4f);
    const double s = 0.3;  // density ratio: draft s × 0.4 m, stable flat (a face-down box needs s < 0.211 or s > 0.789
                           // for a cube; this box is 2.5 × 2 × 1 in its proportions, far wider than high)
    btTransform start = btTransform::getIdentity();
    start.setOrigin(btVector3(0, 0.3f, 0));
    start.setRotation(btQuaternion(btVector3(0, 0, 1), btScalar(0.15)));
    ChainScene scene(4, half, 1000 * s, start);
    btFlatWaterSurface water(0.0);
    btBuoyancyWorld buoyancy(&scene.world, &water, 1000.0);
    btBuoyancyMultiBodyAction action(scene.chain.get(), &buoyancy);
    scene.world.addAction(&action);
    for (int frame = 0; frame < 60 * 40; ++frame) scene.world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
    const double expected = 0.2 - s * 0.4;  // centre height above the water at the draft
    for (const auto& c : scene.colliders) {
        const btTransform& t = c->getWorldTransform();
        INFO("part " << c->m_link << " centre height " << t.getOrigin().y() << " m, expected " << expected
                     << "; its y axis tilted " << std::acos(std::min(btScalar(1), t.getBasis().getColumn(1).y())) << " rad");
        CHECK(double(t.getOrigin().y()) == Approx(expected).margin(3e-3));
        CHECK(double(t.getBasis().getColumn(1).y()) > std::cos(0.02));
    }
    CHECK(action.getSubmergedVolume() == Approx(4 * s * 0.32).epsilon(1e-2));
    for (int link = -1; link < 3; ++link) REQUIRE(action.getPartResult(link) != nullptr);
    CHECK(action.getPartResult(3) == nullptr);
    scene.world.removeAction(&action);
}

TEST_CASE("multibody: the parts of a straight chain add up to one box of the same size", "[bullet][multibody]") {
    // Three 1 m boxes in a row against one 3 m box, both at a tilted pose cutting the water: submerged volume, total
    // force and total torque about the middle box's centre (all exact, so equal to float rounding).
    const btVector3 half(0.5f, 0.25f, 0.4f);
    btTransform base = btTransform::getIdentity();
    const btQuaternion q(btVector3(0.2f, 0.4f, 1).normalized(), btScalar(0.5));
    base.setRotation(q);
    const btVector3 centre(0.3f, 0.05f, -0.2f);
    base.setOrigin(centre - quatRotate(q, btVector3(1, 0, 0)));  // the base box one box length before the middle
    ChainScene scene(3, half, 500, base);
    btFlatWaterSurface water(0.0);
    btBuoyancyWorld buoyancy(&scene.world, &water, 1000.0);
    btBuoyancyMultiBodyAction action(scene.chain.get(), &buoyancy);
    action.updateAction(&scene.world, btScalar(1.0 / 240));

    btBoxShape longBox(btVector3(1.5f, 0.25f, 0.4f));
    btRigidBody::btRigidBodyConstructionInfo info(100, nullptr, &longBox, btVector3(10, 10, 10));
    info.m_startWorldTransform.setRotation(q);
    info.m_startWorldTransform.setOrigin(centre);
    btRigidBody single(info);
    btBuoyancySettings noDrag;
    noDrag.dragCoefficient = 0;
    noDrag.skinFriction = 0;
    noDrag.linearDamping = 0;
    noDrag.radiationDamping = 0;
    btBuoyancyImmediate one(&single, noDrag);
    const btBuoyancyResult& r = one.applyBuoyancyImpulse(water, btVector3(0, btScalar(-9.81), 0), 1000.0, 0.0, 1.0 / 240);

    double volume = 0;
    btVector3 force(0, 0, 0), torque(0, 0, 0);
    for (int link = -1; link < 2; ++link) {
        const btBuoyancyResult* p = action.getPartResult(link);
        REQUIRE(p);
        const btVector3 at = scene.colliders[size_t(link + 1)]->getWorldTransform().getOrigin();
        volume += p->submergedVolume;
        force += p->buoyancyForce;
        torque += p->buoyancyTorque + (at - centre).cross(p->buoyancyForce);
    }
    INFO("chain " << volume << " m3, one box " << r.submergedVolume << " m3");
    REQUIRE(r.submergedVolume > 0.2);
    REQUIRE(r.submergedVolume < 0.9 * 1.2);
    CHECK(volume == Approx(r.submergedVolume).epsilon(1e-5));
    CHECK(double((force - r.buoyancyForce).length()) < 1e-5 * double(r.buoyancyForce.length()));
    CHECK(double((torque - r.buoyancyTorque).length()) < 1e-4 * double(r.buoyancyForce.length()));
}

TEST_CASE("multibody: bad input is refused by name", "[bullet][multibody]") {
    btFlatWaterSurface water(0.0);
    btBuoyancyWorld buoyancy(&water);
    CHECK_THROWS_WITH(btBuoyancyMultiBodyAction(nullptr, &buoyancy), Catch::Contains("multiBody is null"));
    btMultiBody bare(0, 1, btVector3(1, 1, 1), false, false);
    bare.finalizeMultiDof();
    CHECK_THROWS_WITH(btBuoyancyMultiBodyAction(&bare, &buoyancy), Catch::Contains("no collider"));
}
