// Any up axis: the water frame (btWaterFrame) and the buoyancy of a world whose gravity points anywhere.
// Oracles: a rotated copy of a whole contact-free scene (gravity, water frame, bodies) must move as the Y-up scene
// rotated (Bullet's integration and ours are rotation-covariant: only rounding differs); Archimedes (a floating
// body's submerged volume is its mass / ρ whatever g is); free motion without gravity.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/bullet/btWaterFrame.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

using Catch::Matchers::Contains;
using buoyancy::toBullet;
using buoyancy::toEigen;

namespace {

constexpr bool kDouble = sizeof(btScalar) == sizeof(double);

// ---- the frame itself -------------------------------------------------------------------------------------------

bool rightHanded(const btWaterFrame& f) {
    return f.rotation().isUnitary(1e-12) && std::abs(f.rotation().determinant() - 1.0) < 1e-12 &&
           f.zAxis().isApprox(f.xAxis().cross(f.up()), 1e-12);
}

// ---- a contact-free scene and its rotated copy --------------------------------------------------------------------

/// A rigid map of the whole scene: world point p → Q p + o.
struct SceneMap {
    Eigen::Matrix3d Q = Eigen::Matrix3d::Identity();
    Eigen::Vector3d o = Eigen::Vector3d::Zero();
};

/// One body's state at an output time, mapped back through the scene map (so comparable with the Y-up run).
struct Sample {
    Eigen::Vector3d com;        ///< m
    Eigen::Matrix3d rotation;   ///< mesh (the shape's own axes) → (unmapped) world
    double submergedVolume;     ///< m³
};

/// Three bodies well apart (no contacts): a box dropped from 0.3 m above the water (heave, draft), a board heeled 20°
/// (roll decay), and the user's own btBoxShape body tipped about two axes with a spin (btBuoyancyAction on its
/// collision shape). The whole scene is mapped by `map`: gravity, water frame, poses and velocities.
struct MappedScene {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    SceneMap map;
    std::unique_ptr<btBuoyancyWorld> buoyancy;
    std::vector<std::unique_ptr<btBuoyantBody>> buoyant;
    std::unique_ptr<btBoxShape> ownShape;
    std::unique_ptr<btDefaultMotionState> ownMotion;
    std::unique_ptr<btRigidBody> own;
    std::vector<std::unique_ptr<btBuoyancyAction>> actions;
    std::vector<btRigidBody*> bodies;

    MappedScene(const SceneMap& m, const btWaterSurface& water, double g, const btBuoyancySettings& settings) : map(m) {
        world.setGravity(toBullet(m.Q * Eigen::Vector3d(0, -g, 0)));
        const btWaterFrame frame(m.o, Eigen::Vector3d(m.Q.col(1)), Eigen::Vector3d(m.Q.col(0)));
        buoyancy = std::make_unique<btBuoyancyWorld>(&world, &water, frame, 1000.0);
        auto place = [&](const Eigen::Vector3d& p, const Eigen::AngleAxisd& r) {
            Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
            t.linear() = m.Q * r.toRotationMatrix();
            t.translation() = m.Q * p + m.o;
            return toBullet(t);
        };
        btBuoyantBodySettings s;
        s.density = 500;  // s = 0.5
        buoyant.push_back(std::make_unique<btBuoyantBody>(btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.5, 0.8)), s,
                                                          place({-3, 0.3, 0}, Eigen::AngleAxisd(0.0, Eigen::Vector3d::UnitY()))));
        s.density = 400;  // s = 0.4, stable flat: heeled 20° it rolls back
        buoyant.push_back(std::make_unique<btBuoyantBody>(btBuoyancyShape::create(buoyancy::makeBoxMesh(1.2, 0.3, 0.8)), s,
                                                          place({0, -0.03, 0}, Eigen::AngleAxisd(0.35, Eigen::Vector3d::UnitX()))));
        for (auto& b : buoyant) {
            world.addRigidBody(b->getRigidBody());
            bodies.push_back(b->getRigidBody());
            actions.push_back(std::make_unique<btBuoyancyAction>(*b, buoyancy.get(), settings));
        }
        // The user's own body: a 0.6 × 0.4 × 0.6 m btBoxShape of 600 kg/m³, mass and inertia as Bullet computes them.
        ownShape = std::make_unique<btBoxShape>(btVector3(0.3f, 0.2f, 0.3f));
        const btScalar mass = btScalar(600 * 0.6 * 0.4 * 0.6);
        btVector3 inertia;
        ownShape->calculateLocalInertia(mass, inertia);
        ownMotion = std::make_unique<btDefaultMotionState>(
            place({3, 0.05, 0}, Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 0, 1).normalized())));
        own = std::make_unique<btRigidBody>(btRigidBody::btRigidBodyConstructionInfo(mass, ownMotion.get(), ownShape.get(), inertia));
        own->setAngularVelocity(toBullet(m.Q * Eigen::Vector3d(0, 0.8, 0)));
        own->setLinearVelocity(toBullet(m.Q * Eigen::Vector3d(0.2, 0, -0.1)));
        world.addRigidBody(own.get());
        bodies.push_back(own.get());
        actions.push_back(std::make_unique<btBuoyancyAction>(own.get(), buoyancy.get(), settings));
        for (auto& a : actions) world.addAction(a.get());
    }
    ~MappedScene() {
        for (auto& a : actions) world.removeAction(a.get());
        for (btRigidBody* b : bodies) world.removeRigidBody(b);
    }

    /// 10 s at 240 Hz (frames of 4 substeps); each body's state every 0.1 s, mapped back.
    std::vector<std::vector<Sample>> run() {
        std::vector<std::vector<Sample>> out;
        for (int frame = 0; frame <= 600; ++frame) {
            if (frame % 6 == 0) {
                std::vector<Sample> row;
                for (std::size_t i = 0; i < bodies.size(); ++i) {
                    const Eigen::Vector3d c = toEigen(bodies[i]->getCenterOfMassPosition());
                    const Eigen::Isometry3d t = toEigen(i < buoyant.size() ? buoyant[i]->getMeshWorldTransform()
                                                                           : bodies[i]->getCenterOfMassTransform());
                    row.push_back({map.Q.transpose() * (c - map.o), map.Q.transpose() * t.linear(),
                                   actions[i]->getLastResult().submergedVolume});
                }
                out.push_back(row);
            }
            if (frame < 600) world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
        }
        return out;
    }
};

struct Deviation {
    double position = 0;  ///< m
    double angle = 0;     ///< rad
    double volume = 0;    ///< m³
};

Deviation compare(const std::vector<std::vector<Sample>>& a, const std::vector<std::vector<Sample>>& b) {
    Deviation d;
    for (std::size_t k = 0; k < a.size(); ++k)
        for (std::size_t i = 0; i < a[k].size(); ++i) {
            d.position = std::max(d.position, (a[k][i].com - b[k][i].com).norm());
            d.angle = std::max(d.angle, Eigen::AngleAxisd(a[k][i].rotation.transpose() * b[k][i].rotation).angle());
            d.volume = std::max(d.volume, std::abs(a[k][i].submergedVolume - b[k][i].submergedVolume));
        }
    return d;
}

/// The rotations of the property test: exactly Z-up, an oblique one, and random ones (seeded), each with an origin.
std::vector<SceneMap> sceneMaps(int randomCount) {
    std::vector<SceneMap> maps;
    SceneMap zUp;  // +90° about x: y → z, so the default Z-up frame (x, up = z, −y)
    zUp.Q << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    maps.push_back(zUp);
    SceneMap oblique;
    oblique.Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    oblique.o = Eigen::Vector3d(1.5, -2.0, 0.25);
    maps.push_back(oblique);
    std::mt19937 rng(20240521);
    std::normal_distribution<double> n(0.0, 1.0);
    std::uniform_real_distribution<double> u(-5.0, 5.0);
    for (int i = 0; i < randomCount; ++i) {
        SceneMap m;
        m.Q = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
        m.o = Eigen::Vector3d(u(rng), u(rng), u(rng));
        maps.push_back(m);
    }
    return maps;
}

}  // namespace

TEST_CASE("btWaterFrame: the default frame of a gravity, right-handed, +x first whenever up is perpendicular to x",
          "[bullet][upaxis]") {
    const btWaterFrame yUp = btWaterFrame::fromGravity(Eigen::Vector3d(0, -9.81, 0));
    CHECK(yUp.isIdentity());  // a +y-up world keeps its (x, z): the maps are skipped
    const btWaterFrame zUp = btWaterFrame::fromGravity(Eigen::Vector3d(0, 0, -9.81));
    CHECK(zUp.xAxis() == Eigen::Vector3d::UnitX());
    CHECK(zUp.up() == Eigen::Vector3d::UnitZ());
    CHECK(zUp.zAxis() == -Eigen::Vector3d::UnitY());
    CHECK_FALSE(zUp.isIdentity());
    const btWaterFrame down = btWaterFrame::fromGravity(Eigen::Vector3d(0, 0, 3.7));  // up −z
    CHECK(down.xAxis() == Eigen::Vector3d::UnitX());
    CHECK(down.zAxis() == Eigen::Vector3d::UnitY());
    const btWaterFrame xUp = btWaterFrame::fromGravity(Eigen::Vector3d(-9.81, 0, 0));  // up +x: +y first
    CHECK(xUp.xAxis() == Eigen::Vector3d::UnitY());
    for (const Eigen::Vector3d& g : {Eigen::Vector3d(1, -2, 3), Eigen::Vector3d(-5, 1, 0.1), Eigen::Vector3d(0, 3, 4)}) {
        const btWaterFrame f = btWaterFrame::fromGravity(g);
        CHECK(rightHanded(f));
        CHECK(f.angleToGravity(g) < 1e-15);
        CHECK(std::abs(f.xAxis().dot(f.up())) < 1e-15);
    }
    for (const btWaterFrame& f : {yUp, zUp, down, xUp}) CHECK(rightHanded(f));
    // The maps invert each other; a pose's water coordinates are the world's seen from the frame.
    const btWaterFrame f(Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0, 1, 1), Eigen::Vector3d(2, 0, 0));
    const Eigen::Vector3d p(0.3, -1.7, 4.2);
    CHECK((f.toWorldPoint(f.toWaterPoint(p)) - p).norm() < 1e-14);
    CHECK(f.toWaterPoint(f.origin() + 2.5 * f.up()).isApprox(Eigen::Vector3d(0, 2.5, 0)));
    CHECK(toEigen(f.getTransform() * toBullet(Eigen::Vector3d(0, 1, 0))).isApprox(f.toWorldPoint(Eigen::Vector3d(0, 1, 0)),
                                                                                 kDouble ? 1e-12 : 1e-6));
}

TEST_CASE("btWaterFrame: bad vectors are refused with a message naming them", "[bullet][upaxis]") {
    const Eigen::Vector3d o = Eigen::Vector3d::Zero();
    CHECK_THROWS_WITH(btWaterFrame(o, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)),
                      Contains("up (0, 0, 0): must be a finite, non-zero vector"));
    CHECK_THROWS_WITH(btWaterFrame(o, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 0)),
                      Contains("x axis (0, 0, 0): must be a finite, non-zero vector"));
    CHECK_THROWS_WITH(btWaterFrame(o, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0.01, 0)),
                      Contains("x axis (1, 0.01, 0) is not perpendicular to up (0, 1, 0)"));
    CHECK_THROWS_WITH(btWaterFrame(Eigen::Vector3d(NAN, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, 0)),
                      Contains("origin"));
    CHECK_THROWS_WITH(btWaterFrame::fromGravity(Eigen::Vector3d::Zero()), Contains("gravity (0, 0, 0) m/s^2 has no direction"));
    CHECK_NOTHROW(btWaterFrame(o, Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 1e-7, 0)));  // within 1e-6 rad
}

TEST_CASE("any up axis: a rotated scene moves as the Y-up scene rotated (property test, flat water)",
          "[bullet][upaxis]") {
    // Draft, heave and roll decay of three bodies over 10 s, the Y-up run against the same scene mapped by exactly
    // Z-up, an oblique and three random rotations (with origins up to 5 m away). Bullet's integration and the
    // buoyancy are rotation-covariant, so only rounding differs. The bar in double: 1e-6 m and 1e-6 rad. In float
    // the rounding of a pose (6e-8 relative, at coordinates up to 8 m after the shift: 5e-7 m; an orientation to
    // 6e-8 rad) enters each of the 2400 substeps; as a random walk that is 2.5e-5 m, and a heeled body turns a
    // position error into an attitude error over its beam. Measured worst: 1.5e-5 m, 9.3e-5 rad (2.3e-6 m³). The bar,
    // 5e-4 m, 5e-4 rad and 5e-4 m³, leaves a factor 5 for other compilers and CPUs.
    const double barPosition = kDouble ? 1e-6 : 5e-4, barAngle = kDouble ? 1e-6 : 5e-4;
    btFlatWaterSurface water(0.0);
    const btBuoyancySettings settings;  // library defaults (drag, added mass, temporal level of detail)
    const auto reference = MappedScene(SceneMap(), water, 9.81, settings).run();
    CHECK(reference.back()[0].com.y() < reference.front()[0].com.y());                           // the box came down
    // The Y-up run itself: the box came down to its draft (still heaving by ±0.005 m at 10 s: V within 2 %), the board's
    // 20° heel decayed (it sleeps flat at its draft, centre 0.15 − 0.12 m above the water), the own box settled upright.
    auto tilt = [](const Sample& s) { return std::acos(std::min(1.0, s.rotation(1, 1))); };
    CHECK(reference.back()[0].submergedVolume == Approx(0.2).epsilon(0.02));
    CHECK(tilt(reference.front()[1]) == Approx(0.35));
    CHECK(tilt(reference.back()[1]) < 1e-3);
    CHECK(reference.back()[1].com.y() == Approx(0.03).margin(1e-3));
    CHECK(tilt(reference.back()[2]) < 0.01);
    for (const SceneMap& m : sceneMaps(3)) {
        const Deviation d = compare(reference, MappedScene(m, water, 9.81, settings).run());
        INFO("rotation " << Eigen::AngleAxisd(m.Q).angle() << " rad about " << Eigen::AngleAxisd(m.Q).axis().transpose()
                         << ", origin " << m.o.transpose() << ": deviation " << d.position << " m, " << d.angle
                         << " rad, " << d.volume << " m^3");
        CHECK(d.position <= barPosition);
        CHECK(d.angle <= barAngle);
        CHECK(d.volume <= (kDouble ? 1e-6 : 5e-4));
    }
}

TEST_CASE("any up axis: Gerstner waves in a Z-up and an oblique frame move as in the Y-up frame", "[bullet][upaxis]") {
    // The wave's direction is in the frame's horizontal axes: the same surface object serves every frame.
    btGerstnerWave wave;
    wave.amplitude = 0.15;
    wave.wavelength = 12.0;
    wave.directionX = 0.6;
    wave.directionZ = 0.8;
    wave.steepness = 0.5;
    const btGerstnerWaterSurface water({wave}, 0.0, 9.81);
    btBuoyancySettings settings;
    // The water's acceleration (queried in the water frame, applied in the world's) with added mass, and with the
    // Froude–Krylov force too.
    settings.waterAcceleration = GENERATE(btWaterAccelerationForce::AddedMass,
                                          btWaterAccelerationForce::AddedMassAndFroudeKrylov);
    const auto reference = MappedScene(SceneMap(), water, 9.81, settings).run();
    const double barPosition = kDouble ? 1e-6 : 5e-4, barAngle = kDouble ? 1e-6 : 5e-4;  // as the flat-water test
    const auto maps = sceneMaps(0);
    for (const SceneMap& m : maps) {
        const Deviation d = compare(reference, MappedScene(m, water, 9.81, settings).run());
        INFO("deviation " << d.position << " m, " << d.angle << " rad");
        CHECK(d.position <= barPosition);
        CHECK(d.angle <= barAngle);
    }
}

namespace {
/// A Z-up world with a board of 1 × 0.8 × 0.4 m (0.4 m tall along up) at density 400 kg/m³ (s = 0.4).
struct ZUpBoard {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btFlatWaterSurface water{0.0};
    std::unique_ptr<btBuoyancyWorld> buoyancy;
    std::unique_ptr<btBuoyantBody> body;
    std::unique_ptr<btBuoyancyAction> action;
    /// Gravity `g` (world); the board's up is −ĝ, its centre `start` m above the water along up.
    ZUpBoard(const Eigen::Vector3d& g, double start) {
        world.setGravity(toBullet(g));
        buoyancy = std::make_unique<btBuoyancyWorld>(&world, &water, 1000.0);
        const Eigen::Vector3d up = g.norm() > 0 ? Eigen::Vector3d(-g.normalized()) : Eigen::Vector3d::UnitZ();
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear() = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), up).toRotationMatrix();
        pose.translation() = start * up;
        btBuoyantBodySettings s;
        s.density = 400;
        body = std::make_unique<btBuoyantBody>(btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.8, 0.4)), s,
                                               toBullet(pose));
        world.addRigidBody(body->getRigidBody());
        action = std::make_unique<btBuoyancyAction>(*body, buoyancy.get());
        world.addAction(action.get());
    }
    ~ZUpBoard() {
        world.removeAction(action.get());
        world.removeRigidBody(body->getRigidBody());
    }
    void run(double seconds) {
        for (int i = 0; i < int(seconds * 60); ++i) world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
    }
    double heightAlongUp() const {
        return buoyancy->getWaterFrame().toWaterPoint(toEigen(body->getRigidBody()->getCenterOfMassPosition())).y();
    }
};
}  // namespace

TEST_CASE("any up axis: Z-up Earth and Moon, an oblique gravity: the board floats at its Archimedes draft",
          "[bullet][upaxis]") {
    // Archimedes: V_sub = m / ρ = 0.4 of the board whatever g; centre 0.2 − 0.16 = 0.04 m above the water along up.
    for (const Eigen::Vector3d& g : {Eigen::Vector3d(0, 0, -9.81), Eigen::Vector3d(0, 0, -1.62),
                                     Eigen::Vector3d(Eigen::Vector3d(3, -4, 12) * (9.81 / 13.0))}) {
        ZUpBoard b(g, 0.1);
        b.run(30.0);
        INFO("gravity " << g.transpose());
        const btBuoyancyResult& r = b.action->getLastResult();
        CHECK(r.status == btBuoyancyStatus::Ok);
        CHECK(r.submergedVolume / 0.32 == Approx(0.4).margin(0.004));
        CHECK(b.heightAlongUp() == Approx(0.04).margin(2e-3));
        // The buoyancy force is along up (world), its size the weight.
        const Eigen::Vector3d f = toEigen(r.buoyancyForce);
        CHECK(f.normalized().dot(-g.normalized()) > 1 - 1e-6);
        CHECK(f.norm() == Approx(1000 * 0.128 * g.norm()).epsilon(0.01));
    }
}

TEST_CASE("any up axis: zero gravity in a Z-up frame gives no buoyancy and no NaN, gravity turned later is reported",
          "[bullet][upaxis]") {
    SECTION("zero gravity") {
        ZUpBoard b(Eigen::Vector3d::Zero(), -0.1);
        b.body->getRigidBody()->setLinearVelocity(btVector3(0.5f, 0, 0));
        CHECK_NOTHROW(b.run(2.0));
        const btBuoyancyResult& r = b.action->getLastResult();
        CHECK(r.status == btBuoyancyStatus::NoGravity);
        CHECK_FALSE(r.applied);
        const btVector3 v = b.body->getRigidBody()->getLinearVelocity();
        CHECK(std::isfinite(double(b.body->getRigidBody()->getCenterOfMassPosition().x())));
        CHECK(double(v.x()) == Approx(0.5).epsilon(1e-4));
        // Gravity switched on along −z: the frame is derived from it then, and the board floats.
        b.world.setGravity(btVector3(0, 0, -9.81f));
        b.body->getRigidBody()->setLinearVelocity(btVector3(0, 0, 0));
        b.run(30.0);
        CHECK(b.buoyancy->getWaterFrame().up() == Eigen::Vector3d::UnitZ());
        CHECK(b.action->getLastResult().submergedVolume / 0.32 == Approx(0.4).margin(0.004));
    }
    SECTION("gravity turned from −z to −y at run time: no buoyancy, a status naming both vectors, no exception") {
        ZUpBoard b(Eigen::Vector3d(0, 0, -9.81), 0.1);
        b.run(1.0);
        CHECK(b.action->getLastResult().applied);
        b.world.setGravity(btVector3(0, -9.81f, 0));
        CHECK_NOTHROW(b.run(0.5));
        CHECK(b.action->getLastResult().status == btBuoyancyStatus::GravityNotAlongWaterUp);
        CHECK_FALSE(b.action->getLastResult().applied);
        CHECK_THAT(b.buoyancy->getGravityStatusMessage(),
                   Contains("gravity (0, -9.81, 0) m/s^2 does not point down the water frame's up axis (0, 0, 1)"));
        b.world.setGravity(btVector3(0, 0, -9.81f));
        b.run(0.5);
        CHECK(b.action->getLastResult().status == btBuoyancyStatus::Ok);
    }
}

TEST_CASE("any up axis: setWaterFrame refuses an up against the world's gravity and keeps the frame",
          "[bullet][upaxis]") {
    ZUpBoard b(Eigen::Vector3d(0, 0, -9.81), 0.1);
    const btWaterFrame before = b.buoyancy->getWaterFrame();
    CHECK_THROWS_WITH(b.buoyancy->setWaterFrame(btWaterFrame()),
                      Contains("water frame's up (0, 1, 0) is not antiparallel to the world's gravity (0, 0, -9.81)"));
    CHECK(b.buoyancy->getWaterFrame().up() == before.up());
    // 1e-6 rad is the tolerance: 2e-6 rad off is refused, 5e-7 rad accepted.
    CHECK_THROWS(b.buoyancy->setWaterFrame(btWaterFrame(Eigen::Vector3d::Zero(), Eigen::Vector3d(2e-6, 0, 1),
                                                        Eigen::Vector3d(1, 0, -2e-6))));
    CHECK_NOTHROW(b.buoyancy->setWaterFrame(btWaterFrame(Eigen::Vector3d::Zero(), Eigen::Vector3d(5e-7, 0, 1),
                                                         Eigen::Vector3d(1, 0, -5e-7))));
    // An explicit frame with its origin 1 m up: the water (height 0 in the frame) is the plane z = 1.
    b.buoyancy->setWaterFrame(btWaterFrame(Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 1, 0)));
    b.run(30.0);
    CHECK(double(b.body->getRigidBody()->getCenterOfMassPosition().z()) == Approx(1.04).margin(2e-3));
}
