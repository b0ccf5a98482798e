// Marine hydrodynamics (Fossen's model, design.md 2.10) against closed forms: surge decay under linear + quadratic
// damping, terminal speeds under a constant force and in a current, the apparent mass and inertia of a fully
// submerged body, the added mass's Coriolis forces (momentum and energy kept), stability of a light body with an
// added mass ten times its own at 240 Hz, matrices given in Fossen's axes or about another point, the integration
// guide's datasheet example, the scene file's hydrodynamics block, and bad input.
#include "oracles/FloatingPointTraps.h"
#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"
#include <BulletBuoyancy/BulletBuoyancy.h>

#include <btBulletDynamicsCommon.h>

#include <catch2/catch.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace {

constexpr double kRho = 1000.0;

/// Settings with every per-sample drag and damping off and the scalar added mass off: only the marine model acts.
btBuoyancySettings quietSettings() {
    btBuoyancySettings s;
    s.dragCoefficient = 0;
    s.skinFriction = 0;
    s.radiationDamping = 0;
    s.linearDamping = 0;
    s.addedMass = false;
    s.hydrostaticsInterval = 1;
    return s;
}

/// A Bullet world with flat water at y = 0 (optionally a current along x) and one box body with its action.
struct MarineScene {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btFlatWaterSurface water;
    btBoxShape box;
    std::unique_ptr<btRigidBody> body;
    std::unique_ptr<btBuoyancyWorld> buoyancy;
    std::unique_ptr<btBuoyancyAction> action;
    double mass = 0;

    /// @param half     box half extents, m   @param density  kg/m³   @param centre  m   @param currentX  m/s
    MarineScene(const btVector3& half, double density, const btVector3& centre, double currentX = 0.0,
                const btQuaternion& attitude = btQuaternion::getIdentity())
        : water(0.0, currentX, 0.0), box(half) {
        world.setGravity(btVector3(0, btScalar(-9.81), 0));
        body = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &box));
        body->setWorldTransform(btTransform(attitude, centre));
        body->setActivationState(DISABLE_DEACTIVATION);
        world.addRigidBody(body.get());
        buoyancy = std::make_unique<btBuoyancyWorld>(&world, &water, kRho);
        action = std::make_unique<btBuoyancyAction>(body.get(), buoyancy.get(), quietSettings());
        action->setBodyMassFromShape(density);
        mass = 1.0 / double(body->getInvMass());
        world.addAction(action.get());
    }
    ~MarineScene() {
        world.removeAction(action.get());
        world.removeRigidBody(body.get());
    }
    /// n substeps of dt, one per stepSimulation call.
    void step(int n, double dt) {
        for (int i = 0; i < n; ++i) world.stepSimulation(btScalar(dt), 1, btScalar(dt));
    }
    /// The body's velocity over the substep to come, [v; ω] in its own axes: the stored velocity plus the gravity kick
    /// Bullet adds before it integrates (the action leaves the velocity less that kick, design.md 3).
    Eigen::Matrix<double, 6, 1> bodyVelocity(double dt) const {
        const btMatrix3x3 R = body->getWorldTransform().getBasis();
        const btVector3 v = R.transpose() * (body->getLinearVelocity() + body->getGravity() * btScalar(dt));
        const btVector3 w = R.transpose() * body->getAngularVelocity();
        Eigen::Matrix<double, 6, 1> nu;
        nu << v.x(), v.y(), v.z(), w.x(), w.y(), w.z();
        return nu;
    }
    /// ½ νᵀ (M_RB + M_A) ν in the body's axes, J.
    double kineticEnergy(double dt) const {
        const Eigen::Matrix<double, 6, 1> nu = bodyVelocity(dt);
        Eigen::Matrix<double, 6, 6> M = Eigen::Matrix<double, 6, 6>::Zero();
        const btVector3 I = body->getLocalInertia();
        for (int k = 0; k < 3; ++k) {
            M(k, k) = mass;
            M(3 + k, 3 + k) = double(I[k]);
        }
        const btMarineHydrodynamics& h = action->getMarineHydrodynamics();
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j) M(i, j) += h.addedMass[std::size_t(6 * i + j)];
        return 0.5 * nu.dot(M * nu);
    }
};

/// A neutrally buoyant 1 × 0.5 × 0.5 m box (250 kg) five metres under still water.
std::unique_ptr<MarineScene> submergedBox(double currentX = 0.0, const btQuaternion& q = btQuaternion::getIdentity()) {
    return std::make_unique<MarineScene>(btVector3(0.5, 0.25, 0.25), kRho, btVector3(0, -5, 0), currentX, q);
}

btMarineHydrodynamics diagonalModel(const std::array<double, 6>& addedMass, const std::array<double, 6>& linear,
                                    const std::array<double, 6>& quadratic) {
    btMarineHydrodynamics h;
    h.enabled = true;
    h.addedMass = btMarineHydrodynamics::diagonalMatrix(addedMass);
    h.linearDamping = btMarineHydrodynamics::diagonalMatrix(linear);
    h.quadraticDamping = quadratic;
    return h;
}

}  // namespace

TEST_CASE("marine surge decays from its initial speed as the closed form of linear plus quadratic damping",
          "[bullet][marine]") {
    // (m + X) du/dt = −d1 u − d2 |u| u from u0 > 0:  u(t) = d1 u0 e^(−d1 t/M) / (d1 + d2 u0 (1 − e^(−d1 t/M))).
    // The damping is solved by implicit Euler, which is first order and contractive here (the right side decreases in
    // u): each step's error (dt²/2)|u''| is never amplified, so the error at any time is at most (dt/2)∫|u''| dt ≤
    // (dt/2)|u'(0)| (u' is monotone), plus the float state's rounding.
    const double dt = GENERATE(1.0 / 240.0, 1.0 / 60.0);
    auto s = submergedBox();
    const double m = s->mass, X = 2.0 * m, d1 = 100.0, d2 = 200.0, u0 = 2.0;
    REQUIRE(m == Approx(250.0));
    s->action->setMarineHydrodynamics(diagonalModel({X, 0, 0, 0, 0, 0}, {d1, 0, 0, 0, 0, 0}, {d2, 0, 0, 0, 0, 0}));
    s->body->setLinearVelocity(btVector3(btScalar(u0), 0, 0));
    const double M = m + X;
    const double bound = 0.5 * dt * (d1 * u0 + d2 * u0 * u0) / M + 1e-4;
    double t = 0;
    for (const double target : {0.25, 0.5, 1.0, 2.0, 4.0, 8.0}) {
        const int n = int(std::lround((target - t) / dt));
        s->step(n, dt);
        t += n * dt;
        const double e = std::exp(-d1 * t / M);
        const double expected = d1 * u0 * e / (d1 + d2 * u0 * (1.0 - e));
        const double u = s->bodyVelocity(dt)[0];
        INFO("dt = " << dt << "  t = " << t << "  u = " << u << "  closed form " << expected << "  bound " << bound);
        CHECK(std::abs(u - expected) <= bound);
        CHECK(std::abs(s->bodyVelocity(dt)[1]) < 1e-3);  // no heave: neutrally buoyant
    }
}

TEST_CASE("marine terminal speed under a constant force solves d1 u + d2 u^2 = F", "[bullet][marine]") {
    // At steady state the implicit step is exact: d1 u + d2 u² = F, u = (−d1 + √(d1² + 4 d2 F)) / (2 d2) = 1 m/s here.
    // The force is applied to the body through Bullet (applyCentralForce each substep), at the rigid mass; the action
    // shares it with the added mass. 30 s are 20 time constants M / (d1 + 2 d2 u).
    const double dt = GENERATE(1.0 / 240.0, 1.0 / 60.0);
    auto s = submergedBox();
    const double m = s->mass, d1 = 100.0, d2 = 200.0, F = 300.0;
    s->action->setMarineHydrodynamics(diagonalModel({2 * m, 0, 0, 0, 0, 0}, {d1, 0, 0, 0, 0, 0}, {d2, 0, 0, 0, 0, 0}));
    const int n = int(std::lround(30.0 / dt));
    for (int i = 0; i < n; ++i) {
        s->body->applyCentralForce(btVector3(btScalar(F), 0, 0));
        s->step(1, dt);
    }
    const double expected = (-d1 + std::sqrt(d1 * d1 + 4 * d2 * F)) / (2 * d2);
    CHECK(expected == Approx(1.0));
    CHECK(s->bodyVelocity(dt)[0] == Approx(expected).epsilon(1e-4));
}

TEST_CASE("marine damping acts on the velocity relative to the water's current", "[bullet][marine]") {
    // A body at rest in a uniform current c with linear damping only: M du/dt = −d1 (u − c), u = c (1 − e^(−d1 t/M)).
    // Error bound as for the surge decay: (dt/2)|u'(0)| = (dt/2) d1 c / M.
    const double dt = 1.0 / 240.0, c = 0.5;
    auto s = submergedBox(c);
    const double m = s->mass, X = 1.5 * m, d1 = 200.0, M = m + X;
    s->action->setMarineHydrodynamics(diagonalModel({X, X, X, 0, 0, 0}, {d1, d1, d1, 0, 0, 0}, {}));
    const double bound = 0.5 * dt * d1 * c / M + 1e-4;
    double t = 0;
    for (const double target : {1.0, 3.0, 10.0}) {
        const int n = int(std::lround((target - t) / dt));
        s->step(n, dt);
        t += n * dt;
        const double expected = c * (1.0 - std::exp(-d1 * t / M));
        INFO("t = " << t);
        CHECK(std::abs(s->bodyVelocity(dt)[0] - expected) <= bound);
    }
    // Without the water's velocity the body stays at rest.
    auto still = submergedBox(c);
    btMarineHydrodynamics h = diagonalModel({X, X, X, 0, 0, 0}, {d1, d1, d1, 0, 0, 0}, {});
    h.useWaterVelocity = false;
    still->action->setMarineHydrodynamics(h);
    still->step(240, dt);
    CHECK(std::abs(still->bodyVelocity(dt)[0]) < 1e-4);
}

TEST_CASE("at the surface the marine coefficients are scaled by the submerged fraction", "[bullet][marine]") {
    // A box of half the water's density floats at half its height: submerged fraction φ = ½. Surge with linear damping
    // only, from u0: (m + φ X) du/dt = −φ d1 u, u = u0 e^(−φ d1 t / (m + φ X)); error bound (dt/2)|u'(0)| as above.
    // Without the scaling the full coefficients give another decay rate, which the same bound tells apart.
    const double dt = 1.0 / 240.0, u0 = 1.0;
    for (const bool scaled : {true, false}) {
        MarineScene s(btVector3(0.5f, 0.25f, 0.25f), 500.0, btVector3(0, 0, 0));
        const double m = s.mass, X = 2.0 * m, d1 = 150.0;
        btMarineHydrodynamics h = diagonalModel({X, X, X, 0, 0, 0}, {d1, 0, 0, 0, 0, 0}, {});
        h.scaleBySubmergedFraction = scaled;
        s.action->setMarineHydrodynamics(h);
        s.body->setLinearVelocity(btVector3(btScalar(u0), 0, 0));
        const double phi = scaled ? 0.5 : 1.0;
        const double M = m + phi * X, bound = 0.5 * dt * phi * d1 * u0 / M + 1e-4;
        s.step(240, dt);
        CHECK(s.action->getSubmergedFraction() == Approx(0.5).margin(2e-3));  // a start-up bob of 0.1 mm
        const double expected = u0 * std::exp(-phi * d1 * 1.0 / M);
        INFO("scaled " << scaled << "  u " << s.bodyVelocity(dt)[0] << "  closed form " << expected);
        CHECK(std::abs(s.bodyVelocity(dt)[0] - expected) <= bound);
    }
}

TEST_CASE("a fully submerged body accelerates with its apparent mass and inertia", "[bullet][marine]") {
    // No damping: a force F along a principal direction gives a = F / (m + M_A,ii) exactly (the implicit step is exact
    // for a constant force), a torque τ about a principal axis α = τ / (I + M_A,jj). One second, then compared to
    // float rounding. The body is yawed by 30°: the matrices are in its own axes.
    const double dt = 1.0 / 240.0;
    const btQuaternion yaw(btVector3(0, 1, 0), btScalar(0.5235987755982988));
    auto s = submergedBox(0.0, yaw);
    const double m = s->mass, X = 3.0 * m, Y = 5.0 * m, Nyaw = 4.0;
    s->action->setMarineHydrodynamics(diagonalModel({X, 2 * m, Y, 1.0, Nyaw, 2.0}, {}, {}));
    const btMatrix3x3 R = s->body->getWorldTransform().getBasis();
    const double F = 500.0, tau = 10.0;
    const int n = 240;
    SECTION("surge") {
        for (int i = 0; i < n; ++i) {
            s->body->applyCentralForce(R * btVector3(btScalar(F), 0, 0));
            s->step(1, dt);
        }
        CHECK(s->bodyVelocity(dt)[0] / (n * dt) == Approx(F / (m + X)).epsilon(1e-4));
        CHECK(std::abs(s->bodyVelocity(dt)[2]) < 1e-4);
    }
    SECTION("the body's z axis") {
        for (int i = 0; i < n; ++i) {
            s->body->applyCentralForce(R * btVector3(0, 0, btScalar(F)));
            s->step(1, dt);
        }
        CHECK(s->bodyVelocity(dt)[2] / (n * dt) == Approx(F / (m + Y)).epsilon(1e-4));
    }
    SECTION("turning about the vertical axis") {
        const double I = double(s->body->getLocalInertia().y());
        for (int i = 0; i < n; ++i) {
            s->body->applyTorque(btVector3(0, btScalar(tau), 0));
            s->step(1, dt);
        }
        CHECK(s->bodyVelocity(dt)[4] / (n * dt) == Approx(tau / (I + Nyaw)).epsilon(1e-4));
    }
}

TEST_CASE("marine coefficients given in Fossen's axes act along the body's matching axes", "[bullet][marine]") {
    // A datasheet in Fossen's body axes (x forward, y starboard, z down) on a body modelled x forward, y up, z
    // starboard: the reference frame's basis columns are (1,0,0), (0,0,1), (0,−1,0). Sway (Fossen y) is then the
    // body's z, heave (Fossen z) the body's −y.
    const double dt = 1.0 / 240.0;
    auto s = submergedBox();
    const double m = s->mass;
    btMarineHydrodynamics h = btMarineHydrodynamics::fromDerivatives({-1.0 * m, -3.0 * m, -7.0 * m, 0, 0, 0},
                                                                     {0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 0});
    h.referenceFrame.setBasis(btMatrix3x3(1, 0, 0, 0, 0, -1, 0, 1, 0));
    s->action->setMarineHydrodynamics(h);
    const double F = 400.0;
    for (int i = 0; i < 240; ++i) {
        s->body->applyCentralForce(btVector3(0, 0, btScalar(F)));  // starboard
        s->step(1, dt);
    }
    CHECK(s->bodyVelocity(dt)[2] == Approx(F / (m + 3.0 * m)).epsilon(1e-4));
    // The same added mass given about a point 1 m ahead of the centre of mass and moved with toParentFrame keeps the
    // kinetic energy of any motion: νᵀ M_G ν = ν_oᵀ M_o ν_o with ν_o the velocity of that point.
    std::array<double, 36> Mo = btMarineHydrodynamics::diagonalMatrix({100, 300, 700, 10, 20, 30});
    Mo[1] = Mo[6] = 15;  // a surge-sway coupling
    const btTransform bow(btQuaternion(btVector3(0, 1, 0), btScalar(0.3)), btVector3(1, 0, 0));
    const std::array<double, 36> Mg = btMarineHydrodynamics::toParentFrame(Mo, bow);
    const btVector3 v(0.3f, -0.2f, 0.5f), w(0.1f, 0.7f, -0.4f);
    const btVector3 vo = bow.getBasis().transpose() * (v + w.cross(bow.getOrigin()));
    const btVector3 wo = bow.getBasis().transpose() * w;
    const double nuG[6] = {v.x(), v.y(), v.z(), w.x(), w.y(), w.z()}, nuO[6] = {vo.x(), vo.y(), vo.z(), wo.x(), wo.y(), wo.z()};
    double eG = 0, eO = 0;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
            eG += nuG[i] * Mg[std::size_t(6 * i + j)] * nuG[j];
            eO += nuO[i] * Mo[std::size_t(6 * i + j)] * nuO[j];
        }
    CHECK(eG == Approx(eO).epsilon(1e-5));
}

TEST_CASE("the added mass's Coriolis forces turn a drifting body and keep its momentum and energy",
          "[bullet][marine]") {
    // A neutrally buoyant body in still water, no damping, surge and sway added masses unequal (0.5 m and 3 m),
    // drifting at 45° to its axes: the Munk moment −v × p (p = M_A v, not parallel to v) swings it about the vertical
    // axis. With no external force the world linear momentum m v + R M_A Rᵀ v is conserved, which the step keeps to
    // rounding (the added momentum is turned with the body). The kinetic energy ½ νᵀ(M_RB + M_A)ν is conserved by the
    // continuous equations; the step (Bullet turns the body with the start's ω, the Munk moment is taken at the end's
    // v, design.md 2.10) keeps it within a first-order oscillation: measured ±0.13 % over 10 s at 240 Hz and twice
    // that at 120 Hz, with no secular growth. Checked: excursion < 0.3 % at 240 Hz, the 120 Hz excursion 1.5–2.5 times
    // it (first order), the energy after 10 s within 0.1 % of the start. The Munk moment taken at the start's v
    // instead grows the energy by 12 % in 10 s.
    struct Run {
        double excursion = 0, finalDrift = 0, momentumDrift = 0, turned = 0;
    };
    auto run = [](double dt) {
        auto s = submergedBox();
        const double m = s->mass, X = 0.5 * m, Y = 3.0 * m;
        s->action->setMarineHydrodynamics(diagonalModel({X, 2 * m, Y, 5.0, 8.0, 5.0}, {}, {}));
        s->body->setLinearVelocity(btVector3(0.5f, 0, 0.5f));
        s->step(1, dt);
        auto momentum = [&]() -> btVector3 {
            const btMatrix3x3 R = s->body->getWorldTransform().getBasis();
            const btVector3 v = s->body->getLinearVelocity() + s->body->getGravity() * btScalar(dt);
            const btVector3 vb = R.transpose() * v;
            return v * btScalar(m) + R * btVector3(btScalar(X * vb.x()), btScalar(2 * m * vb.y()), btScalar(Y * vb.z()));
        };
        const double e0 = s->kineticEnergy(dt);
        const btVector3 p0 = momentum();
        Run r;
        const int n = int(std::lround(10.0 / dt));
        for (int i = 0; i < n; ++i) {
            s->step(1, dt);
            r.excursion = std::max(r.excursion, std::abs(s->kineticEnergy(dt) / e0 - 1.0));
            r.turned = std::max(r.turned, std::abs(double(s->body->getAngularVelocity().y())));
        }
        r.finalDrift = s->kineticEnergy(dt) / e0 - 1.0;
        r.momentumDrift = double((momentum() - p0).length() / p0.length());
        return r;
    };
    const Run fine = run(1.0 / 240.0), coarse = run(1.0 / 120.0);
    INFO("energy excursion " << fine.excursion << " (240 Hz), " << coarse.excursion << " (120 Hz); after 10 s "
                             << fine.finalDrift << "; momentum " << fine.momentumDrift << "; largest yaw rate "
                             << fine.turned << " rad/s");
    CHECK(fine.turned > 0.5);  // the Munk moment did swing it
    CHECK(fine.momentumDrift < 5e-5);  // float rounding over 2,400 steps (measured 4e-6)
    CHECK(coarse.momentumDrift < 5e-5);
    CHECK(fine.excursion < 3e-3);
    CHECK(coarse.excursion / fine.excursion > 1.5);
    CHECK(coarse.excursion / fine.excursion < 2.5);
    CHECK(std::abs(fine.finalDrift) < 1e-3);
}

TEST_CASE("a light floating body with ten times its mass added stays stable at 240 Hz for 60 s", "[bullet][marine]") {
    // A 3.2 kg box (density 100) heaving in its wall-sided range, spinning and drifting, M_A = 10 m on every linear
    // axis (unequal in surge and sway) and 10 I on every angular one, no damping. Applied explicitly (−M_A ν̇ from the
    // last step) this would multiply the acceleration by −10 every step. The energy ½ νᵀ(M_RB + M_A)ν + ½ ρ g A δ²
    // (the heave spring of a wall-sided box, δ the draft's excess) is conserved by the continuous equations: its
    // largest value over the last 5 s may not exceed that over the first 5 s by more than 2 %.
    const double dt = 1.0 / 240.0;
    const btVector3 half(0.2f, 0.1f, 0.2f);
    const double area = 0.4 * 0.4, density = 100.0;
    const double mass = density * 0.4 * 0.2 * 0.4, draft = mass / (kRho * area);
    MarineScene s(half, density, btVector3(0, btScalar(0.1 - draft - 0.012), 0));
    const btVector3 I = s.body->getLocalInertia();
    btMarineHydrodynamics h = diagonalModel({10 * mass, 12 * mass, 10 * mass, 10 * I.x(), 10 * I.y(), 10 * I.z()}, {}, {});
    h.scaleBySubmergedFraction = false;  // a constant added mass: the energy above is then conserved
    s.action->setMarineHydrodynamics(h);
    s.body->setLinearVelocity(btVector3(0.2f, 0, 0.1f));
    s.body->setAngularVelocity(btVector3(0, 1.0f, 0));
    auto energy = [&]() {
        const double delta = (0.1 - double(s.body->getCenterOfMassPosition().y())) - draft;
        return s.kineticEnergy(dt) + 0.5 * kRho * 9.81 * area * delta * delta;
    };
    double first = 0, last = 0, lowest = 1e9, highest = -1e9;
    const int n = int(std::lround(60.0 / dt));
    for (int i = 0; i < n; ++i) {
        s.step(1, dt);
        const double t = (i + 1) * dt, e = energy();
        REQUIRE(std::isfinite(e));
        if (t > 1.0 && t <= 6.0) first = std::max(first, e);
        if (t > 55.0) last = std::max(last, e);
        const double y = double(s.body->getCenterOfMassPosition().y());
        lowest = std::min(lowest, y);
        highest = std::max(highest, y);
    }
    INFO("energy max first 5 s " << first << " J, last 5 s " << last << " J; y in [" << lowest << ", " << highest << "]");
    CHECK(last <= 1.02 * first);
    CHECK(last >= 0.5 * first);  // nor vanishing: nothing here damps
    CHECK(highest - lowest < 0.05);  // the heave stays in its ±12 mm range (plus the spin's and drift's rounding)
}

TEST_CASE("bad marine input names the field and leaves the action unchanged", "[bullet][marine]") {
    auto s = submergedBox();
    auto rejects = [&](const btMarineHydrodynamics& h, const std::string& field) {
        INFO("expected a message naming " << field);
        try {
            s->action->setMarineHydrodynamics(h);
            FAIL("accepted");
        } catch (const std::invalid_argument& e) {
            CHECK(std::string(e.what()).find(field) != std::string::npos);
        }
        CHECK_FALSE(s->action->getMarineHydrodynamics().enabled);
    };
    const btMarineHydrodynamics good = diagonalModel({100, 100, 100, 1, 1, 1}, {10, 10, 10, 1, 1, 1}, {5, 5, 5, 1, 1, 1});
    btMarineHydrodynamics h = good;
    h.addedMass[2 * 6 + 3] = std::numeric_limits<double>::quiet_NaN();
    rejects(h, "addedMass[2][3]");
    h = good;
    h.addedMass[0 * 6 + 1] = 5;  // [1][0] stays 0
    rejects(h, "addedMass: not symmetric");
    h = good;
    h.addedMass[0 * 6 + 1] = h.addedMass[1 * 6 + 0] = 150;  // |coupling| above √(100·100)
    rejects(h, "addedMass: not positive semidefinite");
    h = good;
    h.linearDamping[0] = -10;  // Fossen's X_u copied without negating it
    rejects(h, "linearDamping[0][0]");
    h = good;
    h.linearDamping[0 * 6 + 5] = h.linearDamping[5 * 6 + 0] = 50;
    rejects(h, "linearDamping: not dissipative");
    h = good;
    h.quadraticDamping[1] = -5;
    rejects(h, "quadraticDamping[1]");
    h = good;
    h.quadraticDamping[4] = std::numeric_limits<double>::infinity();
    rejects(h, "quadraticDamping[4]");
    h = good;
    h.referenceFrame.setBasis(btMatrix3x3(1, 0, 0, 0, 1, 0, 0, 0, -1));  // a reflection
    rejects(h, "referenceFrame");
    // The scalar added mass of the settings and the matrix are one or the other.
    btBuoyancySettings withScalar = quietSettings();
    withScalar.addedMass = true;
    s->action->setSettings(withScalar);
    rejects(good, "addedMass");
    s->action->setSettings(quietSettings());
    s->action->setMarineHydrodynamics(good);
    CHECK(s->action->getMarineHydrodynamics().enabled);
    CHECK_THROWS_WITH(s->action->setSettings(withScalar), Catch::Contains("addedMass"));
    CHECK_FALSE(s->action->getSettings().addedMass);
}

TEST_CASE("marine hydrodynamics never write a non-finite velocity into the body", "[bullet][marine]") {
    // Finite but absurd coefficients whose products overflow: the step is refused, the body keeps finite values.
    buoyancy_test::ScopedFpTrapsOff overflowOnPurpose;  // (the CI's FPE run traps overflow)
    const double dt = 1.0 / 240.0;
    auto s = submergedBox();
    btMarineHydrodynamics h = diagonalModel({1e300, 1e300, 1e300, 1e300, 1e300, 1e300}, {1e308, 0, 0, 0, 0, 0},
                                            {1e308, 1e308, 1e308, 1e308, 1e308, 1e308});
    s->action->setMarineHydrodynamics(h);
    s->body->setLinearVelocity(btVector3(3, 1, 2));
    s->body->setAngularVelocity(btVector3(1, 2, 3));
    s->step(10, dt);
    const btVector3 v = s->body->getLinearVelocity(), w = s->body->getAngularVelocity();
    CHECK(std::isfinite(double(v.x())));
    CHECK(std::isfinite(double(v.y())));
    CHECK(std::isfinite(double(v.z())));
    CHECK(std::isfinite(double(w.x())));
    CHECK(std::isfinite(double(w.y())));
    CHECK(std::isfinite(double(w.z())));
}

TEST_CASE("marine hydrodynamics off leave the motion bit for bit as without them", "[bullet][marine]") {
    // A default btMarineHydrodynamics (enabled false) set on the action changes nothing: same state after 2 s.
    const double dt = 1.0 / 240.0;
    auto a = std::make_unique<MarineScene>(btVector3(0.3f, 0.2f, 0.25f), 600.0, btVector3(0, 0.3f, 0));
    auto b = std::make_unique<MarineScene>(btVector3(0.3f, 0.2f, 0.25f), 600.0, btVector3(0, 0.3f, 0));
    b->action->setMarineHydrodynamics(btMarineHydrodynamics());
    for (auto* s : {a.get(), b.get()}) {
        s->body->setAngularVelocity(btVector3(0.5f, 0.2f, 0));
        s->step(480, dt);
    }
    CHECK(a->body->getCenterOfMassPosition() == b->body->getCenterOfMassPosition());
    CHECK(a->body->getLinearVelocity() == b->body->getLinearVelocity());
    CHECK(a->body->getAngularVelocity() == b->body->getAngularVelocity());
}

TEST_CASE("the datasheet example of the integration guide reaches its closed-form surge speed", "[bullet][marine]") {
    // docs/integration.md, "Marine hydrodynamics": a BlueROV2 Heavy-like vehicle (illustrative coefficients) with
    // 50 N of forward thrust and its attitude held settles where 13.7 u + 141 u² = 50. Fresh water: it is 0.1 kg heavier
    // than its displacement and sinks slowly, which leaves the surge alone (the matrices are diagonal).
    const double dt = 1.0 / 240.0;
    MarineScene s(btVector3(0.23f, 0.065f, 0.112f), kRho, btVector3(0, -10, 0));
    s.body->setMassProps(btScalar(13.5), btVector3(0.26f, 0.37f, 0.23f));
    s.body->updateInertiaTensor();
    s.body->setAngularFactor(0);  // its attitude held, as the vehicle's attitude control would (see the guide)
    s.mass = 13.5;
    btMarineHydrodynamics rov = btMarineHydrodynamics::fromDerivatives(
        {-6.3567, -7.1206, -18.6863, -0.1858, -0.1348, -0.2215}, {-13.7, 0.0, -33.0, 0.0, -0.8, 0.0},
        {-141.0, -217.0, -190.0, -1.192, -0.470, -1.5});
    rov.referenceFrame.setBasis(btMatrix3x3(1, 0, 0, 0, 0, -1, 0, 1, 0));
    s.action->setMarineHydrodynamics(rov);
    for (int i = 0; i < 240 * 5; ++i) {
        s.body->applyCentralForce(s.body->getWorldTransform().getBasis() * btVector3(50, 0, 0));
        s.step(1, dt);
    }
    const double expected = (-13.7 + std::sqrt(13.7 * 13.7 + 4 * 141.0 * 50.0)) / (2 * 141.0);
    CHECK(expected == Approx(0.549).margin(0.001));
    CHECK(s.bodyVelocity(dt)[0] == Approx(expected).epsilon(1e-3));
    // Heave: Fossen's z is the body's −y, so sinking at w > 0 in Fossen's axes: 33 w + 190 w² = (m − ρ V) g.
    const double excess = (13.5 - kRho * 0.46 * 0.13 * 0.224) * 9.81;
    const double w = (-33.0 + std::sqrt(33.0 * 33.0 + 4 * 190.0 * excess)) / (2 * 190.0);
    CHECK(-s.bodyVelocity(dt)[1] == Approx(w).epsilon(2e-2));
}

TEST_CASE("scene bodies take a hydrodynamics block and bad values are errors naming the key", "[bullet][marine]") {
    auto scene = [](const std::string& hydro, const std::string& buoyancy = "") {
        return "{\"bodies\": [{\"shape\": {\"type\": \"box\", \"size\": [1, 0.5, 0.5]}, \"density\": 1000, "
               "\"position\": [0, -5, 0]" + (buoyancy.empty() ? "" : ", \"buoyancy\": " + buoyancy) +
               ", \"hydrodynamics\": " + hydro + "}]}";
    };
    const auto s = buoyancy::cli::parseScene(
        scene(R"({"added_mass": [500, 0, 0, 0, 0, 0], "linear_damping": [100, 0, 0, 0, 0, 0],
                  "quadratic_damping": [200, 0, 0, 0, 0, 0], "origin": [0.1, 0, 0]})"),
        "s.json", ".");
    REQUIRE(s.bodies.size() == 1);
    const btMarineHydrodynamics& h = s.bodies[0].hydrodynamics;
    CHECK(h.enabled);
    CHECK(h.addedMass[0] == 500);
    CHECK(h.linearDamping[0] == 100);
    CHECK(h.quadraticDamping[0] == 200);
    CHECK(double(h.referenceFrame.getOrigin().x()) == Approx(0.1));
    CHECK_FALSE(s.bodies[0].buoyancy.addedMass);  // the matrix replaces the scalar added mass
    // The world hands it to the body's action.
    const auto world = buoyancy::cli::buildSceneWorld(s, 10.0);
    REQUIRE(world->actions.size() == 1);
    CHECK(world->actions[0]->getMarineHydrodynamics().enabled);
    CHECK(world->actions[0]->getMarineHydrodynamics().addedMass[0] == 500);

    auto expectError = [&](const std::string& text, const std::string& inMessage) {
        try {
            buoyancy::cli::parseScene(text, "s.json", ".");
            FAIL("no error for " << text);
        } catch (const buoyancy::cli::UsageError& e) {
            INFO(e.what());
            CHECK(std::string(e.what()).find(inMessage) != std::string::npos);
        }
    };
    expectError(scene(R"({"added_mas": [1, 1, 1, 1, 1, 1]})"), "bodies[0].hydrodynamics");
    expectError(scene(R"({"added_mas": [1, 1, 1, 1, 1, 1]})"), "added_mas");
    expectError(scene(R"({"added_mass": [1, 2, 3]})"), "bodies[0].hydrodynamics.added_mass");
    expectError(scene(R"({"quadratic_damping": [1, -2, 3, 0, 0, 0]})"), "bodies[0].hydrodynamics.quadratic_damping[1]");
    expectError(scene(R"({"linear_damping": [-5, 0, 0, 0, 0, 0]})"), "linearDamping[0][0]");
    std::string asymmetric = "[";
    for (int k = 0; k < 36; ++k) asymmetric += (k ? "," : "") + std::string(k == 0 || k == 7 ? "100" : k == 1 ? "5" : "0");
    asymmetric += "]";
    expectError(scene("{\"added_mass\": " + asymmetric + "}"), "not symmetric");
    expectError(scene(R"({"added_mass": [1, 1, 1, 1, 1, 1]})", R"({"added_mass": true})"), "replaces buoyancy.added_mass");
}

TEST_CASE("marine hydrodynamics cost per body and substep (manual)", "[.timing]") {
    // Prints the time of a substep of one submerged box without and with the marine model (diagonal matrices, linear
    // damping, then linear and quadratic damping: the Newton iterations run every substep): no checks.
    const double dt = 1.0 / 240.0;
    for (const int marine : {0, 1, 2}) {
        auto s = submergedBox();
        if (marine)
            s->action->setMarineHydrodynamics(diagonalModel({500, 600, 700, 5, 6, 7}, {100, 100, 100, 1, 1, 1},
                                                            marine == 2 ? std::array<double, 6>{200, 200, 200, 2, 2, 2}
                                                                        : std::array<double, 6>{}));
        s->body->setLinearVelocity(btVector3(1, 0, 0.5f));
        s->body->setAngularVelocity(btVector3(0, 0.5f, 0));
        s->step(240, dt);
        const auto t0 = std::chrono::steady_clock::now();
        const int n = 24000;
        s->step(n, dt);
        const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / n;
        std::printf("marine %s: %.2f us per substep (Bullet and the whole action)\n",
                    marine == 0 ? "off" : marine == 1 ? "on, linear damping" : "on, linear and quadratic damping", us);
    }
}
