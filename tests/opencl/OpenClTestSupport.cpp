#include "OpenClTestSupport.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

namespace buoyancy_test {

bool deviceTestsDisabled() {
#if defined(__SANITIZE_ADDRESS__)
    WARN("OpenCL device test skipped: AddressSanitizer build (the OpenCL driver, PoCL with its LLVM JIT, is not "
         "leak-clean; the CPU side of tests/opencl still runs)");
    return true;
#else
    return false;
#endif
}

btOpenClBuoyancyBackend* installTestBackend(btBuoyancyWorld& world, btOpenClOptions::Precision precision) {
    if (deviceTestsDisabled()) return nullptr;
    btOpenClOptions o;
    o.precision = precision;
    std::string message;
    std::unique_ptr<btOpenClBuoyancyBackend> backend = btOpenClBuoyancyBackend::create(world, o, &message);
    if (!backend) {
        WARN("OpenCL test skipped: " << message);
        return nullptr;
    }
    btOpenClBuoyancyBackend* raw = backend.get();
    world.setDeviceBackend(std::move(backend));
    return raw;
}

void evaluateBoth(btDynamicsWorld& dynamics, btBuoyancyWorld& world, btOpenClBuoyancyBackend& backend, double dt,
                  std::vector<btBuoyancyResult>& cpu, std::vector<btBuoyancyResult>& device, std::uint64_t& answered) {
    const std::vector<btBuoyancyAction*> actions = world.getActions();
    std::vector<btVector3> v, w;
    for (btBuoyancyAction* a : actions) {
        v.push_back(a->getRigidBody()->getLinearVelocity());
        w.push_back(a->getRigidBody()->getAngularVelocity());
    }
    const double t0 = world.getTime();
    auto run = [&](std::vector<btBuoyancyResult>& out) {
        world.setTime(t0);
        for (std::size_t i = 0; i < actions.size(); ++i) {
            actions[i]->getRigidBody()->setLinearVelocity(v[i]);
            actions[i]->getRigidBody()->setAngularVelocity(w[i]);
        }
        out.clear();
        for (btBuoyancyAction* a : actions) {
            a->updateAction(&dynamics, btScalar(dt));
            out.push_back(a->getLastResult());
        }
    };
    backend.setEnabled(false);
    run(cpu);
    backend.setEnabled(true);
    const std::uint64_t before = backend.stats().hydroAnswers;
    run(device);
    answered = backend.stats().hydroAnswers - before;
    for (std::size_t i = 0; i < actions.size(); ++i) {  // leave the bodies as found
        actions[i]->getRigidBody()->setLinearVelocity(v[i]);
        actions[i]->getRigidBody()->setAngularVelocity(w[i]);
    }
}

double resultDifference(const btBuoyancyResult& a, const btBuoyancyResult& b, double weight, double length, double volume) {
    double d = std::abs(a.submergedVolume - b.submergedVolume) / volume;
    d = std::max(d, double((a.buoyancyForce - b.buoyancyForce).length()) / weight);
    d = std::max(d, double((a.buoyancyTorque - b.buoyancyTorque).length()) / (weight * length));
    d = std::max(d, double((a.dragForce - b.dragForce).length()) / weight);
    d = std::max(d, double((a.dragTorque - b.dragTorque).length()) / (weight * length));
    return d;
}

}  // namespace buoyancy_test
