// Game logic on the water (docs/integration.md "Events and queries"): a pool and a lake at different levels, a
// crate, a ball and a stone dropped into them, and a listener printing when each body enters the water, leaves it,
// becomes fully submerged or surfaces again, with the time. At 4 s a crane lifts the crate out of the pool. Then a
// few queries of the water without a body (a footstep, a splash) and a count of the debug-drawing segments.
// Usage: water_events_example. Exit status 0 when every body fired the events the scene makes it fire.
#include <BulletBuoyancy/BulletBuoyancy.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace {

/// Prints each event and keeps "name:event:water" for the check at the end.
class PrintingListener : public btBuoyancyEventListener {
public:
    std::vector<std::string> log;
    void onEnterWater(const btBuoyancyEvent& e) override { print(e); }
    void onLeaveWater(const btBuoyancyEvent& e) override { print(e); }
    void onFullySubmerged(const btBuoyancyEvent& e) override { print(e); }
    void onSurfaced(const btBuoyancyEvent& e) override { print(e); }

private:
    void print(const btBuoyancyEvent& e) {
        const char* name = static_cast<const char*>(e.body->getUserPointer());
        const char* water = e.water ? e.water->name.c_str() : "the sea";
        std::printf("t = %6.3f s  %-6s %-9s %-5s (%5.1f %% under water)\n", e.time, name,
                    btBuoyancyEventTypeName(e.type), water, 100.0 * e.submergedFraction);
        log.push_back(std::string(name) + ":" + btBuoyancyEventTypeName(e.type) + ":" + water);
    }
};

/// Counts the debug-drawing segments.
struct CountingDraw : btIDebugDraw {
    int lines = 0;
    void drawLine(const btVector3&, const btVector3&, const btVector3&) override { ++lines; }
    void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override {}
    void reportErrorWarning(const char*) override {}
    void draw3dText(const btVector3&, const char*) override {}
    void setDebugMode(int) override {}
    int getDebugMode() const override { return DBG_DrawWireframe; }
};

}  // namespace

int main() {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, btScalar(-9.81), 0));

    // The ground 3 m below the pool's level: the bed of both waters (their regions reach below it, so a body resting
    // on the bed is inside its water's region, not straddling the region's bottom).
    btStaticPlaneShape groundShape(btVector3(0, 1, 0), btScalar(-3));
    btRigidBody ground(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &groundShape));
    world.addRigidBody(&ground);

    // A fresh-water pool at y = 0 and a sea-water lake at y = 1.5 beside it.
    btFlatWaterSurface poolSurface(0.0), lakeSurface(1.5);
    btBuoyancyWorld water(&world, nullptr);
    water.addWaterBody(btWaterBodyInfo{"pool", &poolSurface, 1000.0, btVector3(-6, -4, -3), btVector3(-1, 1, 3)});
    water.addWaterBody(btWaterBodyInfo{"lake", &lakeSurface, 1025.0, btVector3(1, -4, -3), btVector3(9, 2.5, 3)});
    PrintingListener listener;
    water.addEventListener(&listener);

    // Bodies as they are: a Bullet shape, a mass from a density, a buoyancy action each.
    struct Body {
        std::unique_ptr<btCollisionShape> shape;
        std::unique_ptr<btRigidBody> rigid;
        std::unique_ptr<btBuoyancyAction> action;
    };
    std::vector<Body> bodies;
    const auto drop = [&](const char* name, btCollisionShape* shape, double density, double volume, const btVector3& at) {
        Body b;
        b.shape.reset(shape);
        const btScalar mass = btScalar(density * volume);
        btVector3 inertia(0, 0, 0);
        shape->calculateLocalInertia(mass, inertia);
        b.rigid = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(mass, nullptr, shape, inertia));
        b.rigid->setWorldTransform(btTransform(btQuaternion::getIdentity(), at));
        b.rigid->setUserPointer(const_cast<char*>(name));
        world.addRigidBody(b.rigid.get());
        b.action = std::make_unique<btBuoyancyAction>(b.rigid.get(), &water);
        world.addAction(b.action.get());
        bodies.push_back(std::move(b));
    };
    // A crate (400 kg/m^3) and a ball (300 kg/m^3) lowered to 5 cm above the water float; a stone (2500 kg/m^3)
    // dropped from 0.5 m sinks to the lake's bottom.
    drop("crate", new btBoxShape(btVector3(0.5, 0.25, 0.5)), 400, 1.0 * 0.5 * 1.0, btVector3(-3.5, btScalar(0.3), 0));
    drop("ball", new btSphereShape(btScalar(0.3)), 300, 4.0 / 3.0 * 3.14159265358979 * 0.027, btVector3(3, btScalar(1.85), 0));
    drop("stone", new btBoxShape(btVector3(0.2, 0.2, 0.2)), 2500, 0.064, btVector3(6, btScalar(2.2), 0));

    // 8 s at 60 Hz, four substeps per frame. At 4 s a crane lifts the crate out of the pool onto the land between
    // the waters (no water there: it falls to the ground).
    btRigidBody* crate = bodies[0].rigid.get();
    for (int frame = 0; frame < 8 * 60; ++frame) {
        if (frame == 4 * 60) {
            std::printf("t = %6.3f s  the crane lifts the crate out of the pool\n", water.getTime());
            crate->setWorldTransform(btTransform(btQuaternion::getIdentity(), btVector3(0, 2, 0)));
            crate->setLinearVelocity(btVector3(0, 0, 0));
            crate->setAngularVelocity(btVector3(0, 0, 0));
            crate->activate(true);
        }
        world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
    }

    // Queries without a body: what is under a footstep, how deep a splash lands.
    const btVector3 points[3] = {btVector3(5, 0, 1), btVector3(-2, 3, 0), btVector3(0, 0, 0)};
    const char* what[3] = {"a splash in the lake", "a step on the pool's diving board", "a step between the waters"};
    for (int i = 0; i < 3; ++i) {
        const btWaterQueryResult q = water.queryWater(points[i]);
        if (q.hasWater)
            std::printf("query: %s: %s, surface at y = %.2f m, depth %.2f m\n", what[i], q.waterBodyName,
                        double(q.surfaceHeight), double(q.depth));
        else
            std::printf("query: %s: no water\n", what[i]);
    }
    CountingDraw draw;
    water.debugDrawWater(&draw, btVector3(0, 0, 0), 50, 16);
    std::printf("debug drawing: %d segments\n", draw.lines);

    for (Body& b : bodies) {
        world.removeAction(b.action.get());
        world.removeRigidBody(b.rigid.get());
    }
    world.removeRigidBody(&ground);

    // The events the scene makes: each floating body enters once, the stone enters and goes under, the crate leaves.
    const std::vector<std::string> expected = {"crate:enter:pool", "ball:enter:lake", "stone:enter:lake",
                                               "stone:submerged:lake", "crate:leave:pool"};
    const bool same = listener.log.size() == expected.size() &&
                      std::is_permutation(listener.log.begin(), listener.log.end(), expected.begin());
    const bool leaveLast = !listener.log.empty() && listener.log.back() == "crate:leave:pool";
    if (!same || !leaveLast) {
        std::printf("unexpected events\n");
        return 1;
    }
    std::printf("all events as expected\n");
    return 0;
}
