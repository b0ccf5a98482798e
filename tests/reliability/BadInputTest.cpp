// The bad-input catalogue (docs/bad-input.md): every way a mesh, shape, setting, body, world,
// time step or scene can be wrong, with the exact error it gets, and the check that nothing is
// half-applied (a rejected call leaves the object as it was). The broken mesh *files* of prepareMesh are
// catalogued in tests/mesh/MeshRepairTest.cpp; here are the in-memory cases and everything downstream.
// Expected messages are the documented contract (docs/bad-input.md), written by hand.

#include "reliability/ReliabilityHelpers.h"

#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"
#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

using namespace reliability_test;
using Catch::Matchers::Contains;
using Catch::Matchers::Equals;
using Catch::Matchers::StartsWith;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

/// The unit cube [0,1]³, outward (built by hand: 8 corners, 12 triangles).
buoyancy::TriangleMesh unitCube() {
    buoyancy::TriangleMesh m;
    for (int k = 0; k < 8; ++k) m.vertices.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads) {
        m.triangles.emplace_back(q[0], q[1], q[2]);
        m.triangles.emplace_back(q[0], q[2], q[3]);
    }
    return m;
}

btBuoyancySettings exactMesh() {
    btBuoyancySettings s;
    s.method = btBuoyancyMethod::ExactMesh;
    return s;
}

std::shared_ptr<const btBuoyancyShape> cubeShape() { return btBuoyancyShape::create(unitCube(), exactMesh()); }

/// Every field of btBuoyancySettings equal (no operator== in the library).
bool same(const btBuoyancySettings& a, const btBuoyancySettings& b) {
    return a.method == b.method && a.textureSize == b.textureSize && a.preferModelUvs == b.preferModelUvs &&
           a.dragCoefficient == b.dragCoefficient && a.skinFriction == b.skinFriction &&
           a.linearDamping == b.linearDamping && a.radiationDamping == b.radiationDamping && a.addedMass == b.addedMass &&
           a.addedMassCoefficient == b.addedMassCoefficient &&
           a.addedMassWaterplaneCoefficient == b.addedMassWaterplaneCoefficient && a.buoyancyEnabled == b.buoyancyEnabled;
}

/// Snapshot of everything a buoyant body's state is made of.
struct BodyState {
    btTransform transform;
    btVector3 v, w, invInertia;
    btScalar invMass;
    btTransform meshInCom;
    double mass;
    Eigen::Vector3d centre;
    Eigen::Matrix3d inertia;
};

BodyState snapshot(btBuoyantBody& b) {
    btRigidBody* r = b.getRigidBody();
    return {r->getWorldTransform(), r->getLinearVelocity(), r->getAngularVelocity(), r->getInvInertiaDiagLocal(),
            r->getInvMass(), b.getMeshInComFrame(), b.getMassProperties().mass, b.getMassProperties().centre,
            b.getMassProperties().inertia};
}

bool same(const btTransform& a, const btTransform& b) {
    for (int i = 0; i < 3; ++i)
        if (!(a.getBasis()[i] == b.getBasis()[i])) return false;
    return a.getOrigin() == b.getOrigin();
}

bool same(const BodyState& a, const BodyState& b) {
    return same(a.transform, b.transform) && a.v == b.v && a.w == b.w && a.invInertia == b.invInertia &&
           a.invMass == b.invMass && same(a.meshInCom, b.meshInCom) && a.mass == b.mass && a.centre == b.centre &&
           a.inertia == b.inertia;
}

/// A cube of density 500 half in the water, with its action, after `frames` frames.
struct OneCube {
    CheckedWorld w;
    std::size_t i;
    explicit OneCube(int frames = 10) {
        btBuoyantBodySettings body;
        body.density = 500;
        i = w.add(cubeShape(), body, makePose(btVector3(0, -0.5, 0)));
        w.step(frames);
    }
};

buoyancy::cli::Scene scene(const std::string& bodyJson, const std::string& top = "") {
    return buoyancy::cli::parseScene("{" + top + "\"bodies\": [" + bodyJson + "]}", "s.json", "/nonexistent");
}

const std::string kBox = "\"shape\": {\"type\": \"box\", \"size\": [1, 1, 1]}";

}  // namespace

// ---- meshes ---------------------------------------------------------------------------------------------

TEST_CASE("bad input: in-memory meshes rejected by prepareMesh", "[reliability][bad-input]") {
    buoyancy::TriangleMesh empty;
    CHECK_THROWS_WITH(buoyancy::prepareMesh(empty, "m.obj"), Equals("m.obj: no triangles"));

    buoyancy::TriangleMesh uvCount = unitCube();
    uvCount.corner_uvs.assign(5, Eigen::Vector2d(0.5, 0.5));
    CHECK_THROWS_WITH(buoyancy::prepareMesh(uvCount, "m.obj"), StartsWith("m.obj: corner UV count 5 is not 3 x "));

    buoyancy::TriangleMesh uvNaN = unitCube();
    uvNaN.corner_uvs.assign(36, Eigen::Vector2d(0.5, 0.5));
    uvNaN.corner_uvs[7].x() = kNaN;
    {
        ScopedFpTrapsOff nanOnPurpose;
        CHECK_THROWS_WITH(buoyancy::prepareMesh(uvNaN, "m.obj"), Equals("m.obj: non-finite texture coordinates"));
    }

    buoyancy::TriangleMesh index = unitCube();
    index.triangles[3][1] = 8;
    index.triangles[4][2] = -1;
    CHECK_THROWS_WITH(buoyancy::prepareMesh(index, "m.obj"), Equals("m.obj: vertex index out of range: 2 corners"));

    // Two copies of one triangle facing away from each other: closed, consistent, no volume.
    buoyancy::TriangleMesh flat;
    flat.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    flat.triangles = {{0, 1, 2}, {0, 2, 1}};
    CHECK_THROWS_WITH(buoyancy::prepareMesh(flat, "m.obj"),
                      Equals("m.obj: flat component: component 1 of 1 is a closed surface enclosing no volume"));

    buoyancy::TriangleMesh open = unitCube();
    open.triangles.pop_back();
    CHECK_THROWS_WITH(buoyancy::prepareMesh(open, "m.obj"), Equals("m.obj: open surface: 3 boundary edges"));
}

TEST_CASE("bad input: a mesh given to btBuoyancyShape::create without prepareMesh", "[reliability][bad-input]") {
    ScopedFpTrapsOff infOnPurpose;  // Eigen's allFinite() computes Inf − Inf
    // Regression: out-of-range indices were read out of bounds by the exact-mesh face samples.
    for (btBuoyancyMethod method : {btBuoyancyMethod::ExactMesh, btBuoyancyMethod::ExactCoverage}) {
        btBuoyancySettings s;
        s.method = method;
        s.textureSize = 32;
        buoyancy::TriangleMesh m = unitCube();
        m.triangles[0][2] = 9;
        CHECK_THROWS_WITH(btBuoyancyShape::create(m, s),
                          Equals("mesh: triangle 0 has vertex index 9 out of range (8 vertices)"));
        m = unitCube();
        m.triangles[11][0] = -3;
        CHECK_THROWS_WITH(btBuoyancyShape::create(m, s),
                          Equals("mesh: triangle 11 has vertex index -3 out of range (8 vertices)"));
        m = unitCube();
        m.vertices.clear();
        CHECK_THROWS_WITH(btBuoyancyShape::create(m, s),
                          Equals("mesh: triangle 0 has vertex index 0 out of range (0 vertices)"));
        m = unitCube();
        m.vertices[5].y() = kInf;
        CHECK_THROWS_WITH(btBuoyancyShape::create(m, s), Equals("mesh: vertex 5 is not finite"));
        CHECK_THROWS_WITH(btBuoyancyShape::create(buoyancy::TriangleMesh(), s), Equals("mesh: no triangles"));
    }
    // Inside-out: create runs prepareMesh's checks, which turn a closed inside-out component outward (with a
    // warning), as the command line does: the unit cube's volume is +1 by either method.
    buoyancy::TriangleMesh inverted = unitCube();
    for (auto& t : inverted.triangles) std::swap(t[1], t[2]);
    const auto outward = btBuoyancyShape::create(inverted, exactMesh());
    CHECK(outward->getVolume() == Approx(1.0).epsilon(1e-12));
    CHECK_FALSE(outward->getMeshWarnings().empty());
    btBuoyancySettings sampled;
    sampled.method = btBuoyancyMethod::ExactCoverage;
    sampled.textureSize = 64;
    CHECK(btBuoyancyShape::create(inverted, sampled)->getVolume() == Approx(1.0).epsilon(1e-3));
    // Open: one face missing is refused with the command line's message.
    buoyancy::TriangleMesh open = unitCube();
    open.triangles.resize(10);
    CHECK_THROWS_WITH(btBuoyancyShape::create(open, exactMesh()), StartsWith("mesh: open surface"));
}

TEST_CASE("bad input: primitive mesh sizes", "[reliability][bad-input]") {
    CHECK_THROWS_WITH(buoyancy::makeBoxMesh(1, 0, 1), StartsWith("primitive mesh: "));
    CHECK_THROWS_WITH(buoyancy::makeBoxMesh(1, -1, 1), StartsWith("primitive mesh: "));
    ScopedFpTrapsOff nanOnPurpose;
    CHECK_THROWS_WITH(buoyancy::makeSphereMesh(kNaN), StartsWith("primitive mesh: "));
    CHECK_THROWS_WITH(buoyancy::makeCylinderMesh(1, kInf), StartsWith("primitive mesh: "));
    CHECK_THROWS_WITH(buoyancy::makeTorusMesh(1, 2), Equals("primitive mesh: torus minor radius must be smaller than the major radius"));
}

// ---- buoyancy settings ----------------------------------------------------------------------------------

TEST_CASE("bad input: buoyancy settings, rejected everywhere and never half-applied", "[reliability][bad-input]") {
    struct Case {
        const char* what;
        void (*spoil)(btBuoyancySettings&);
        const char* message;
    };
    const Case cases[] = {
        {"texture -1", [](btBuoyancySettings& s) { s.textureSize = -1; },
         "textureSize: must be 0 (default) or in 1..16384 (got -1)"},
        {"texture 1e6", [](btBuoyancySettings& s) { s.textureSize = 1000000; },
         "textureSize: must be 0 (default) or in 1..16384 (got 1000000)"},
        {"texture 16385", [](btBuoyancySettings& s) { s.textureSize = 16385; },
         "textureSize: must be 0 (default) or in 1..16384 (got 16385)"},
        {"negative drag", [](btBuoyancySettings& s) { s.dragCoefficient = -1; },
         "dragCoefficient: must be a finite number >= 0 (got -1.000000)"},
        {"NaN drag", [](btBuoyancySettings& s) { s.dragCoefficient = kNaN; },
         "dragCoefficient: must be a finite number >= 0 (got nan)"},
        {"infinite skin friction", [](btBuoyancySettings& s) { s.skinFriction = kInf; },
         "skinFriction: must be a finite number >= 0 (got inf)"},
        {"negative damping", [](btBuoyancySettings& s) { s.linearDamping = -0.5; },
         "linearDamping: must be a finite number >= 0 (got -0.500000)"},
        {"damping above 100 m/s", [](btBuoyancySettings& s) { s.linearDamping = 101; },
         "linearDamping: must be in 0..100 m/s (got 101.000000)"},
        {"negative radiation damping", [](btBuoyancySettings& s) { s.radiationDamping = -0.1; },
         "radiationDamping: must be a finite number >= 0 (got -0.100000)"},
        {"NaN radiation damping", [](btBuoyancySettings& s) { s.radiationDamping = kNaN; },
         "radiationDamping: must be a finite number >= 0 (got nan)"},
        {"radiation damping above 10", [](btBuoyancySettings& s) { s.radiationDamping = 11; },
         "radiationDamping: must be in 0..10 (got 11.000000)"},
        {"negative added mass", [](btBuoyancySettings& s) { s.addedMassCoefficient = -2; },
         "addedMassCoefficient: must be a finite number >= 0 (got -2.000000)"},
        {"NaN waterplane added mass", [](btBuoyancySettings& s) { s.addedMassWaterplaneCoefficient = kNaN; },
         "addedMassWaterplaneCoefficient: must be a finite number >= 0 (got nan)"},
        {"method out of the enum", [](btBuoyancySettings& s) { s.method = static_cast<btBuoyancyMethod>(42); },
         "method: not a btBuoyancyMethod value"},
    };
    OneCube c;
    btBuoyancySettings good;
    good.dragCoefficient = 0.7;
    c.w.action(c.i).setSettings(good);
    ScopedFpTrapsOff nanOnPurpose;  // the NaN cases compare a NaN
    for (const Case& k : cases) {
        INFO(k.what);
        btBuoyancySettings bad = good;
        k.spoil(bad);
        CHECK_THROWS_WITH(bad.validate(), Equals(k.message));
        CHECK_THROWS_WITH(btBuoyancyShape::create(unitCube(), bad), Equals(k.message));
        const std::size_t registered = c.w.water().getActions().size();
        CHECK_THROWS_WITH(btBuoyancyAction(c.w.body(c.i), &c.w.water(), bad), Equals(k.message));
        CHECK(c.w.water().getActions().size() == registered);  // the failed action did not register
        CHECK_THROWS_WITH(c.w.action(c.i).setSettings(bad), Equals(k.message));
        CHECK(same(c.w.action(c.i).getSettings(), good));
    }
    CHECK_THROWS_WITH(btBuoyancyMethodFromName("fast"),
                      Equals("method: unknown value \"fast\" (expected default, texel-centre, exact-coverage or exact-mesh)"));
}

TEST_CASE("bad input: texture sizes 0 and 1", "[reliability][bad-input]") {
    btBuoyancySettings s;
    s.method = btBuoyancyMethod::ExactCoverage;
    s.textureSize = 0;  // 0 is "the library default", not an error
    auto shape = btBuoyancyShape::create(unitCube(), s);
    CHECK(shape->getTextureSize() > 1);
    // One texel cannot hold the six charts of a cube with a texel of gap between charts.
    s.textureSize = 1;
    CHECK_THROWS_WITH(btBuoyancyShape::create(unitCube(), s), StartsWith("generateAtlas: "));
}

// ---- body settings ---------------------------------------------------------------------------------------

TEST_CASE("bad input: body settings and poses rejected by btBuoyantBody", "[reliability][bad-input]") {
    struct Case {
        const char* what;
        void (*spoil)(btBuoyantBodySettings&);
        const char* message;
    };
    const Case cases[] = {
        {"negative density", [](btBuoyantBodySettings& s) { s.density = -1; },
         "density: must be a finite number > 0.000000 (got -1.000000)"},
        {"zero density", [](btBuoyantBodySettings& s) { s.density = 0; },
         "density: must be a finite number > 0.000000 (got 0.000000)"},
        {"NaN density", [](btBuoyantBodySettings& s) { s.density = kNaN; },
         "density: must be a finite number > 0.000000 (got nan)"},
        {"negative mass", [](btBuoyantBodySettings& s) { s.mass = -3; },
         "mass: must be a finite number >= 0.000000 (got -3.000000)"},
        {"zero shell thickness", [](btBuoyantBodySettings& s) { s.massModel = btBuoyantMassModel::Shell; s.shellThickness = 0; },
         "shellThickness: must be a finite number > 0.000000 (got 0.000000)"},
        {"zero ballast", [](btBuoyantBodySettings& s) { s.ballast.push_back({Eigen::Vector3d::Zero(), 0.0}); },
         "ballast[0].mass: must be a finite number > 0.000000 (got 0.000000)"},
        {"NaN ballast position", [](btBuoyantBodySettings& s) { s.ballast.push_back({Eigen::Vector3d(0, kNaN, 0), 1.0}); },
         "ballast[0].position: must be finite"},
        {"negative friction", [](btBuoyantBodySettings& s) { s.friction = -0.1; },
         "friction: must be a finite number >= 0.000000 (got -0.100000)"},
        {"negative restitution", [](btBuoyantBodySettings& s) { s.restitution = -1; },
         "restitution: must be a finite number >= 0.000000 (got -1.000000)"},
        {"NaN margin", [](btBuoyantBodySettings& s) { s.collisionMargin = kNaN; },
         "collisionMargin: must be a finite number >= 0.000000 (got nan)"},
        {"negative sleeping threshold", [](btBuoyantBodySettings& s) { s.linearSleepingThreshold = -1; },
         "linearSleepingThreshold: must be a finite number >= 0.000000 (got -1.000000)"},
        {"mass model out of the enum", [](btBuoyantBodySettings& s) { s.massModel = static_cast<btBuoyantMassModel>(7); },
         "massModel: not a btBuoyantMassModel value"},
    };
    auto shape = cubeShape();
    ScopedFpTrapsOff nanOnPurpose;
    for (const Case& k : cases) {
        INFO(k.what);
        btBuoyantBodySettings bad;
        k.spoil(bad);
        CHECK_THROWS_WITH(bad.validate(), Equals(k.message));
        CHECK_THROWS_WITH(btBuoyantBody(shape, bad, makePose(btVector3(0, 0, 0))), Equals(k.message));
        CHECK_THROWS_WITH(btBuoyantBodyMassProperties(*shape, bad), Equals(k.message));
    }
    CHECK_THROWS_WITH(btBuoyantBody(nullptr, btBuoyantBodySettings(), makePose(btVector3(0, 0, 0))), Equals("shape: null"));

    // Regression: a NaN or scaled pose went straight into the btRigidBody.
    btTransform nanPose = makePose(btVector3(0, 0, 0));
    nanPose.getOrigin().setY(btScalar(kNaN));
    CHECK_THROWS_WITH(btBuoyantBody(shape, btBuoyantBodySettings(), nanPose),
                      Equals("meshWorldTransform: must be finite with an orthonormal rotation"));
    btTransform nanRotation = makePose(btVector3(0, 0, 0));
    nanRotation.getBasis()[1][2] = btScalar(kNaN);
    CHECK_THROWS_WITH(btBuoyantBody(shape, btBuoyantBodySettings(), nanRotation),
                      Equals("meshWorldTransform: must be finite with an orthonormal rotation"));
    btTransform scaled = makePose(btVector3(0, 0, 0));
    scaled.setBasis(scaled.getBasis().scaled(btVector3(2, 2, 2)));
    CHECK_THROWS_WITH(btBuoyantBody(shape, btBuoyantBodySettings(), scaled),
                      Equals("meshWorldTransform: must be finite with an orthonormal rotation"));
}

TEST_CASE("bad input: updateMassProperties leaves the body as it was", "[reliability][bad-input]") {
    OneCube c;
    btBuoyantBody& b = c.w.body(c.i);
    const BodyState before = snapshot(b);
    const Eigen::Matrix3d I = Eigen::Matrix3d::Identity() * 10;
    const char* bad = "mass properties: mass must be > 0 and everything finite";
    {
        ScopedFpTrapsOff nanOnPurpose;
        CHECK_THROWS_WITH(b.updateMassProperties(0, Eigen::Vector3d::Zero(), I), Equals(bad));
        CHECK_THROWS_WITH(b.updateMassProperties(-5, Eigen::Vector3d::Zero(), I), Equals(bad));
        CHECK_THROWS_WITH(b.updateMassProperties(kNaN, Eigen::Vector3d::Zero(), I), Equals(bad));
        CHECK_THROWS_WITH(b.updateMassProperties(100, Eigen::Vector3d(kNaN, 0, 0), I), Equals(bad));
        Eigen::Matrix3d nanI = I;
        nanI(0, 1) = kInf;
        CHECK_THROWS_WITH(b.updateMassProperties(100, Eigen::Vector3d::Zero(), nanI), Equals(bad));
    }
    // Regression: a negative-definite inertia was clamped to a tiny positive one silently.
    CHECK_THROWS_WITH(b.updateMassProperties(100, Eigen::Vector3d::Zero(), -I),
                      Equals("inertia: not positive semi-definite (smallest principal moment -10)"));
    CHECK(same(snapshot(b), before));

    // A fixed body has no mass to update.
    btBuoyantBodySettings fixed;
    fixed.fixed = true;
    btBuoyantBody f(cubeShape(), fixed, makePose(btVector3(0, 0, 0)));
    CHECK_THROWS_WITH(f.updateMassProperties(1, Eigen::Vector3d::Zero(), I),
                      Equals("updateMassProperties: the body is fixed"));
}

// ---- world ------------------------------------------------------------------------------------------------

TEST_CASE("bad input: buoyancy world parameters", "[reliability][bad-input]") {
    btFlatWaterSurface water;
    CHECK_THROWS_WITH(btBuoyancyWorld(&water, 0.0), Equals("fluidDensity: must be a finite number > 0 (got 0.000000)"));
    CHECK_THROWS_WITH(btBuoyancyWorld(&water, -1000.0), Equals("fluidDensity: must be a finite number > 0 (got -1000.000000)"));
    CHECK_THROWS_WITH(btBuoyancyWorld(&water, 1000.0, -9.81), Equals("gravity: must be a finite number >= 0 (got -9.810000)"));
    btBuoyancyWorld w(&water, 1025.0, 9.81);
    ScopedFpTrapsOff nanOnPurpose;
    CHECK_THROWS_WITH(w.setFluidDensity(kNaN), Equals("fluidDensity: must be a finite number > 0 (got nan)"));
    CHECK_THROWS_WITH(w.setGravity(kInf), Equals("gravity: must be a finite number >= 0 (got inf)"));
    CHECK(w.getFluidDensity() == 1025.0);
    CHECK(w.getGravity() == 9.81);
}

TEST_CASE("bad input: action with null arguments", "[reliability][bad-input]") {
    btFlatWaterSurface water;
    btBuoyancyWorld w(&water);
    btBuoyantBody b(cubeShape(), btBuoyantBodySettings(), makePose(btVector3(0, 0, 0)));
    CHECK_THROWS_WITH(btBuoyancyAction(nullptr, cubeShape(), &w), Equals("body: null"));
    CHECK_THROWS_WITH(btBuoyancyAction(b.getRigidBody(), nullptr, &w), Equals("shape: null"));
    CHECK_THROWS_WITH(btBuoyancyAction(b.getRigidBody(), cubeShape(), nullptr), Equals("world: null"));
    CHECK(w.getActions().empty());
}

// ---- time steps and misuse while running ----------------------------------------------------------------

TEST_CASE("bad input: zero, negative, NaN and infinite time steps apply nothing", "[reliability][bad-input]") {
    OneCube c;
    btBuoyancyAction& a = c.w.action(c.i);
    const double t0 = c.w.water().getTime();
    const BodyState before = snapshot(c.w.body(c.i));
    ScopedFpTrapsOff nanOnPurpose;
    for (double dt : {0.0, -1.0 / 240.0, kNaN, kInf}) {
        INFO("dt = " << dt);
        a.updateAction(&c.w.world(), btScalar(dt));
        CHECK_FALSE(a.getLastResult().applied);
        CHECK(same(snapshot(c.w.body(c.i)), before));
        // Regression: the water clock advanced by dt first, so a NaN dt made it NaN for good.
        CHECK(c.w.water().getTime() == t0);
    }
    // Bullet itself runs no substep for a zero frame time.
    c.w.world().stepSimulation(0, 4, btScalar(1.0 / 240.0));
    CHECK(same(snapshot(c.w.body(c.i)), before));
    CHECK(c.w.firstViolation().empty());
}

TEST_CASE("bad input: body removed from the world while its action remains", "[reliability][bad-input]") {
    CheckedWorld w;
    btBuoyantBodySettings body;
    body.density = 500;
    const std::size_t removed = w.add(cubeShape(), body, makePose(btVector3(0, -0.5, 0)));
    const std::size_t other = w.add(cubeShape(), body, makePose(btVector3(5, -0.5, 0)));
    w.step(5);
    w.world().removeRigidBody(w.rigid(removed));  // the action stays in the world
    const BodyState before = snapshot(w.body(removed));
    w.step(20);
    CHECK_FALSE(w.action(removed).getLastResult().applied);
    CHECK(same(snapshot(w.body(removed)), before));  // nothing applied to a body outside the world
    CHECK(w.action(other).getLastResult().applied);   // the others go on
    w.world().addRigidBody(w.rigid(removed));
    w.step(2);
    CHECK(w.action(removed).getLastResult().applied);
    CHECK(w.firstViolation().empty());
    CHECK(w.rejectedTotal() == 0);
}

TEST_CASE("bad input: NaN pose or absurd velocity never reaches the body through the action", "[reliability][bad-input]") {
    ScopedFpTrapsOff nanOnPurpose;
    SECTION("NaN in the body's transform") {
        // Regression: clippedHydrostatics threw invalid_argument out of updateAction, i.e. through
        // Bullet's stepSimulation into the game.
        OneCube c;
        btRigidBody* r = c.w.rigid(c.i);
        btTransform t = r->getWorldTransform();
        t.getOrigin().setY(btScalar(kNaN));
        r->setWorldTransform(t);
        const btVector3 v = r->getLinearVelocity(), w = r->getAngularVelocity();
        c.w.action(c.i).updateAction(&c.w.world(), btScalar(1.0 / 240.0));
        CHECK_FALSE(c.w.action(c.i).getLastResult().applied);
        CHECK(c.w.action(c.i).getRejectedCount() == 1);
        CHECK(r->getLinearVelocity() == v);
        CHECK(r->getAngularVelocity() == w);
    }
    SECTION("NaN in the mesh-in-COM frame of a plain rigid body") {
        CheckedWorld w;
        btBoxShape box(btVector3(0.5, 0.5, 0.5));
        btVector3 inertia;
        box.calculateLocalInertia(500, inertia);
        btRigidBody r(btRigidBody::btRigidBodyConstructionInfo(500, nullptr, &box, inertia));
        r.setWorldTransform(makePose(btVector3(0, 0, 0)));
        w.world().addRigidBody(&r);
        btTransform meshInCom = makePose(btVector3(-0.5, -0.5, -0.5));
        btBuoyancyAction a(&r, cubeShape(), &w.water(), btBuoyancySettings(), meshInCom);
        meshInCom.getBasis()[0][0] = btScalar(kNaN);
        a.setMeshInComFrame(meshInCom);
        const btVector3 v = r.getLinearVelocity();
        a.updateAction(&w.world(), btScalar(1.0 / 240.0));
        CHECK_FALSE(a.getLastResult().applied);
        CHECK(a.getRejectedCount() == 1);
        CHECK(r.getLinearVelocity() == v);
        w.world().removeRigidBody(&r);
    }
    SECTION("a velocity near the largest btScalar") {
        // Regression: the drag impulse was checked in double, then rounded to float: Inf.
        OneCube c;
        btRigidBody* r = c.w.rigid(c.i);
        const btScalar big = std::numeric_limits<btScalar>::max() / btScalar(4);
        r->setLinearVelocity(btVector3(0, -big, 0));
        c.w.action(c.i).updateAction(&c.w.world(), btScalar(1.0 / 240.0));
        CHECK(btBuoyancyCheckBody(*r).empty());
    }
}

TEST_CASE("bad input: no water surface means no buoyancy, not a crash", "[reliability][bad-input]") {
    OneCube c;
    c.w.water().setWater(nullptr);
    c.w.step(5);
    CHECK_FALSE(c.w.action(c.i).getLastResult().applied);
    CHECK(c.w.firstViolation().empty());
}

// ---- scene files ------------------------------------------------------------------------------------------

TEST_CASE("bad input: scene files name the file and the key", "[reliability][bad-input]") {
    using buoyancy::cli::UsageError;
    const std::string body = "{" + kBox + ", \"density\": 500}";
    CHECK_THROWS_WITH(scene(body, "\"dt\": 0, "), Equals("s.json: dt: value 0 out of range [1e-06, 1]"));
    CHECK_THROWS_WITH(scene(body, "\"dt\": -0.01, "), Equals("s.json: dt: value -0.01 out of range [1e-06, 1]"));
    CHECK_THROWS_WITH(scene(body, "\"substeps_per_frame\": 0, "),
                      Equals("s.json: substeps_per_frame: value 0 out of range [1, 1000]"));
    CHECK_THROWS_WITH(scene(body, "\"gravity\": [0, 0, -9.81], \"water\": {\"frame\": {\"up\": [0, 1, 0]}}, "),
                      Equals("s.json: water.frame.up: (0, 1, 0) is not antiparallel to the scene's gravity (0, 0, -9.81) "
                             "m/s^2 (1.5708 rad apart, 1e-6 allowed): the water is a height field along up = -gravity"));
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": -5}"),
                      Equals("s.json: bodies[0].density: value -5 out of range (0, 1e+06]"));
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 0}"),
                      Equals("s.json: bodies[0].density: value 0 out of range (0, 1e+06]"));
    CHECK_THROWS_WITH(scene("{" + kBox + "}"), Equals("s.json: bodies[0]: missing \"density\" or \"mass\""));
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"buoyancy\": {\"texture\": 0}}"),
                      Equals("s.json: bodies[0].buoyancy.texture: value 0 out of range [1, 16384]"));
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"buoyancy\": {\"texture\": 1000000}}"),
                      Equals("s.json: bodies[0].buoyancy.texture: value 1000000 out of range [1, 16384]"));
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"buoyancy\": {\"drag_coefficient\": -1}}"),
                      Equals("s.json: bodies[0].buoyancy.drag_coefficient: value -1 out of range [0, 100]"));
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"buoyancy\": {\"water_patch_nodes_per_wavelength\": -2}}"),
                      Equals("s.json: bodies[0].buoyancy.water_patch_nodes_per_wavelength: value -2 out of range [0, 1000]"));
    CHECK(scene("{" + kBox + ", \"density\": 500, \"buoyancy\": {\"water_patch_nodes_per_wavelength\": 24}}")
              .bodies[0].buoyancy.waterPatchNodesPerWavelength == 24.0);
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"buoyancy\": {\"hydrostatics_interval\": 17}}"),
                      Equals("s.json: bodies[0].buoyancy.hydrostatics_interval: value 17 out of range [0, 16]"));
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"buoyancy\": {\"hydrostatics_reuse_tolerance\": 0}}"),
                      Equals("s.json: bodies[0].buoyancy.hydrostatics_reuse_tolerance: value 0 out of range (0, 1]"));
    const auto temporal = scene("{" + kBox + ", \"density\": 500, \"buoyancy\": {\"hydrostatics_interval\": 4, "
                                "\"hydrostatics_reuse_tolerance\": 0.01}}");
    CHECK(temporal.bodies[0].buoyancy.hydrostaticsInterval == 4);
    CHECK(temporal.bodies[0].buoyancy.hydrostaticsReuseTolerance == 0.01);
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"rotation\": {\"axis\": [0, 0, 0], \"degrees\": 30}}"),
                      Equals("s.json: bodies[0].rotation.axis: zero axis"));
    // JSON has no NaN; a number too large for a double is the closest thing.
    // Regression (found by fuzz_scene_json): nlohmann throws out_of_range, not parse_error, for it
    // and the CLI died in std::terminate.
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"position\": [1e400, 0, 0]}"),
                      Equals("s.json: invalid JSON: [json.exception.out_of_range.406] number overflow parsing '1e400'"));
    CHECK_THROWS_WITH(scene("{\"shape\": {\"type\": \"box\", \"size\": [1, 0, 1]}, \"density\": 500}"),
                      Equals("s.json: bodies[0].shape.size[1]: value 0 out of range (0, 1e+06]"));
    CHECK_THROWS_WITH(scene("{\"shape\": {\"type\": \"mesh\", \"file\": \"boat.obj\"}, \"density\": 500}"),
                      Equals("s.json: bodies[0].shape.file: no such file: /nonexistent/boat.obj"));
    CHECK_THROWS_WITH(scene("{" + kBox + ", \"density\": 500, \"colour\": \"red\"}"),
                      Equals("s.json: bodies[0].colour: unknown key"));
    const std::string named = "{\"name\": \"a\", " + kBox + ", \"density\": 500}";
    CHECK_THROWS_WITH(scene(named + ", " + named), Equals("s.json: bodies[1].name: duplicate name \"a\""));
    CHECK_THROWS_WITH(buoyancy::cli::parseScene("{\"bodies\": [", "s.json", "."), StartsWith("s.json: invalid JSON: "));
    CHECK_THROWS_AS(scene(body, "\"dt\": \"fast\", "), UsageError);
}
