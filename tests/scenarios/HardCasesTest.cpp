// Hard cases (design.md 6 items 1–3): extreme density ratios and time steps, a 100:1 plank,
// drops, bodies starting submerged or above the water, a light body released deep, and a seeded property
// test over random poses, velocities and densities. Each must stay finite and bounded and end at rest
// (floating at its analytic draft, or on the ground when it sinks).
#include "oracles/BulletTestWorld.h"
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include "oracles/PolyhedralOracle.h"

#include <catch2/catch.hpp>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>

using namespace buoyancy_test;

namespace {

btBuoyancySettings exactMesh() {
    btBuoyancySettings bs;
    bs.method = btBuoyancyMethod::ExactMesh;
    return bs;
}

/// Free-fall speed after falling from height h, m/s: the bound on any speed reached by a body dropped
/// from h (drag and buoyancy only take energy away before it enters the water).
double fallSpeed(double h) { return std::sqrt(2 * 9.81 * std::max(h, 0.0)); }

}  // namespace

TEST_CASE("hard: density ratios 0.01 and 20", "[bullet][hard]") {
    const double c = 0.5;
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(c, c, c), exactMesh());
    SECTION("s = 0.01 floats at its draft") {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 10;
        w.add(shape, body, makePose(btVector3(0, 0.5, 0)), exactMesh());
        const Track tr = runTracked(w, 20, 4, 1.0 / 240);
        const double yTheory = c / 2 - 0.01 * c;
        std::printf("hard s=0.01: max speed %.3f m/s, max y %.3f, final y %.5f (theory %.5f), speed %.2e\n",
                    tr.maxSpeed, tr.maxY, tr.y, yTheory, tr.speed);
        REQUIRE(tr.finite);
        CHECK(tr.maxSpeed < fallSpeed(0.5 - yTheory) * 1.01 + 0.01);
        CHECK(tr.maxY <= 0.5 + 1e-6);
        CHECK(std::abs(tr.y - yTheory) < 0.005 * c);
        CHECK(tr.speed < 0.01);
    }
    SECTION("s = 20 sinks to the ground and stays") {
        BulletTestWorld w;
        w.addGround(-5);
        btBuoyantBodySettings body;
        body.density = 20000;
        w.add(shape, body, makePose(btVector3(0, 0.5, 0), btVector3(1, 1, 0), 30), exactMesh());
        const Track tr = runTracked(w, 15, 4, 1.0 / 240);
        // Oracle: fully submerged terminal velocity v_t = sqrt(2 (m − ρV) g / (ρ C_d A)) with A at most the
        // box's largest silhouette (√3 c² for a cube); free fall of 0.5 m before the water adds at most fallSpeed.
        const double m = w.body(0).getMass(), V = c * c * c;
        const double vtMin = std::sqrt(2 * (m - 1000 * V) * 9.81 / (1000 * 1.0 * std::sqrt(3.0) * c * c));
        std::printf("hard s=20: max speed %.3f m/s (terminal >= %.3f), final centre y %.4f (ground -5 + %.2f), speed %.2e\n",
                    tr.maxSpeed, vtMin, tr.y, c / 2, tr.speed);
        REQUIRE(tr.finite);
        CHECK(tr.maxSpeed < std::max(vtMin * 1.5, fallSpeed(5.5)));
        CHECK(tr.y > -5 + c / 2 - 0.02);
        CHECK(tr.y < -5 + c / 2 + 0.02);
        CHECK(tr.speed < 0.01);
    }
}

TEST_CASE("hard: time steps 1/30 to 1/1000 s", "[bullet][hard]") {
    const double a = 2, c = 0.4, b = 1, s = 0.5;
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(a, c, b), exactMesh());
    const double yTheory = c / 2 - s * c;
    for (double hz : {30.0, 60.0, 240.0, 1000.0}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000 * s;
        // Dropped from 0.5 m above its equilibrium with a 15° heel.
        w.add(shape, body, makePose(btVector3(0, btScalar(yTheory + 0.5), 0), btVector3(1, 0, 0.2), 15), exactMesh());
        const auto t0 = std::chrono::steady_clock::now();
        const Track tr = runTracked(w, 20, 1, 1.0 / hz);
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::printf("hard dt=1/%g: max speed %.3f, max y %.4f, min y %.4f, final y %.5f (theory %.5f), tilt %.3f deg, "
                    "speed %.2e, %.0f ms\n",
                    hz, tr.maxSpeed, tr.maxY, tr.minY, tr.y, yTheory, tiltDegrees(tr.last), tr.speed, ms);
        REQUIRE(tr.finite);
        CHECK(tr.maxSpeed < fallSpeed(0.5) + 1.0);
        CHECK(tr.maxY < yTheory + 0.5 + 1e-3);
        CHECK(std::abs(tr.y - yTheory) < 0.005 * c);
        CHECK(tiltDegrees(tr.last) < 1.0);
        CHECK(tr.speed < 0.01);
    }
}

TEST_CASE("hard: a 100:1 plank", "[bullet][hard]") {
    const double a = 5, c = 0.05, b = 0.5, s = 0.6;
    auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(a, c, b), exactMesh());
    BulletTestWorld w;
    btBuoyantBodySettings body;
    body.density = 1000 * s;
    w.add(shape, body, makePose(btVector3(0, 0.5, 0), btVector3(0.3, 0, 1), 10), exactMesh());
    const Track tr = runTracked(w, 20, 4, 1.0 / 240);
    const double yTheory = c / 2 - s * c;
    std::printf("hard plank 100:1: max speed %.3f, max omega %.3f, final y %.5f (theory %.5f), tilt %.3f deg, speed %.2e\n",
                tr.maxSpeed, tr.maxOmega, tr.y, yTheory, tiltDegrees(tr.last), tr.speed);
    REQUIRE(tr.finite);
    CHECK(tr.maxSpeed < fallSpeed(0.5 + a / 2) + 0.5);
    CHECK(std::abs(tr.y - yTheory) < 0.005 * b);  // 0.5 % of its width: 2.5 mm (height is only 5 cm)
    CHECK(tiltDegrees(tr.last) < 1.0);
    CHECK(tr.speed < 0.01);
}

TEST_CASE("hard: dropped from 10 m, started above and fully under the water", "[bullet][hard]") {
    const double R = 0.3, s = 0.5;
    const auto mesh = buoyancy::makeSphereMesh(R, 32, 16);
    auto shape = btBuoyancyShape::create(mesh, exactMesh());
    for (double y0 : {10.0, 1.0, -3.0}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000 * s;
        w.add(shape, body, makePose(btVector3(0, btScalar(y0), 0)), exactMesh());
        const Track tr = runTracked(w, 20, 4, 1.0 / 240, 0, -0.5 * R);
        std::printf("hard start y=%.1f: max speed %.3f (free fall %.3f), min y %.3f, max y after entering %.3f, "
                    "final y %.5f, speed %.2e\n",
                    y0, tr.maxSpeed, fallSpeed(y0), tr.minY, tr.maxYAfter, tr.y, tr.speed);
        REQUIRE(tr.finite);
        // Nothing gains energy: speed below free fall from the start (plus 1 %), never higher than its start
        // height, and (dropped) it does not bounce back to where it came from.
        if (y0 > 0) CHECK(tr.maxSpeed < 1.01 * fallSpeed(y0 + R) + 0.05);
        else CHECK(tr.maxSpeed < 1.01 * std::sqrt(2 * 9.81 * (1 / s - 1) * (R - y0)));  // buoyancy work, no drag
        CHECK(tr.maxY < std::max(y0, R) + 1e-3);
        if (y0 > 0) CHECK(tr.maxYAfter < 0.5 * y0);
        // Rest at the draft: s = 0.5 puts the centre on the water line (mesh volume symmetric about it).
        CHECK(std::abs(tr.y) < 0.005 * 2 * R);
        CHECK(tr.speed < 0.01);
    }
}

TEST_CASE("hard: a light body released 5 m deep rises and is not flung (design.md 6.1-2)", "[bullet][hard]") {
    const double R = 0.3;
    const auto mesh = buoyancy::makeSphereMesh(R, 32, 16);
    auto shape = btBuoyancyShape::create(mesh, exactMesh());
    const double V = oracleDryMoments(mesh.vertices, mesh.triangles).volume;
    for (double s : {0.2, 0.05}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 1000 * s;
        w.add(shape, body, makePose(btVector3(0, -5, 0)), exactMesh());
        const Track tr = runTracked(w, 25, 4, 1.0 / 240, 0, -1e300, -R);
        // Energy bound on the jump (any correct model is below it; a launched body is far above): the rise
        // speed never exceeds the terminal velocity v_t = sqrt(2 (ρV − m) g / (ρ C_d A)) (drag C_d = 1 on
        // the silhouette πR²); while emerging, buoyancy does at most ∫ρ g V_sub dy = ρ g V R of work (the
        // mean of a sphere's submerged volume over its emergence is V/2) against m g 2R. So the centre
        // rises at most v_t²/(2g) + R (ρV/m − 1) above the water line.
        const double m = w.body(0).getMass();
        const double vt = std::sqrt(2 * (1000 * V - m) * 9.81 / (1000 * 1.0 * M_PI * R * R));
        const double bound = vt * vt / (2 * 9.81) + R * (1000 * V / m - 1);
        // At rest: centre at the draft of the mesh's own volume (bisection on the oracle's exact cap).
        const double level = oracleEquilibriumLevel(mesh.vertices, mesh.triangles, tr.last, m / 1000.0);
        // Speed: at most v_t while fully submerged; at most sqrt(v_t² + 2 g R (ρV/m − 2)) while emerging
        // (the same work bound; the dry top half feels no drag, so it may exceed v_t there).
        const double vEmerge = std::sqrt(vt * vt + 2 * 9.81 * R * (1000 * V / m - 2));
        std::printf("hard deep s=%.2f: max speed submerged %.3f (v_t %.3f), overall %.3f (bound %.3f), max centre y %.3f "
                    "(bound %.3f), final y %.5f, oracle level error %.2e m, speed %.2e\n",
                    s, tr.maxSpeedBelow, vt, tr.maxSpeed, vEmerge, tr.maxY, bound, tr.y, level, tr.speed);
        REQUIRE(tr.finite);
        CHECK(tr.maxSpeedBelow < 1.02 * vt);
        CHECK(tr.maxSpeed < vEmerge);
        CHECK(tr.maxY < bound);
        CHECK(std::abs(level) < 0.005 * 2 * R);
        CHECK(tr.speed < 0.01);
    }
}

namespace {

/// The property test's seabed: a static box whose top face is y = top (friction 0.8, rolling 0.1,
/// spinning 0.05 as BulletTestWorld::addGround), with Bullet's polyhedral features, so that a body whose hull
/// also has them (usePolyhedralContacts) touches it through polyhedral contact clipping: the contact
/// manifold holds the whole touching face, leading edge included. Against a btStaticPlaneShape, Bullet 3.24
/// makes one new contact point per substep at the deepest vertex (plus ±1.8° perturbed copies): a polygonal
/// prism rolling ~0.7 of a facet per substep (16 facets, 8 rad/s, 30 Hz) gets its next edge found only when
/// that edge is already under its centre and 4–6 cm into the ground, so the edge-over impact (the loss that
/// stops a rolling polygon, ~10 % of the energy per edge for 16 sides) never happens, and the push-out plus
/// the support left on trailing points feed it: Bullet alone, no water, drives such a cylinder from 0.5 to
/// 2.1 m/s. On this seabed it stops within seconds at 30 Hz (measurements: the comment above the long test).
/// 40 m × 40 m: no body of the long run goes farther than 9.7 m from the origin, and a 400 m box cost
/// precision (float): a cylinder at 240 Hz went 4.5 cm into it instead of 0.1 cm.
class PolyhedralSeabed {
public:
    PolyhedralSeabed(BulletTestWorld& w, double top) : m_world(w.world()), m_shape(btVector3(20, 1, 20)) {
        m_shape.initializePolyhedralFeatures();
        btRigidBody::btRigidBodyConstructionInfo info(0, nullptr, &m_shape);
        info.m_friction = 0.8;
        info.m_rollingFriction = 0.1;
        info.m_spinningFriction = 0.05;
        info.m_startWorldTransform.setOrigin(btVector3(0, btScalar(top - 1), 0));
        m_body = std::make_unique<btRigidBody>(info);
        m_world.addRigidBody(m_body.get());
    }
    ~PolyhedralSeabed() { m_world.removeRigidBody(m_body.get()); }
    PolyhedralSeabed(const PolyhedralSeabed&) = delete;
    PolyhedralSeabed& operator=(const PolyhedralSeabed&) = delete;

private:
    btDiscreteDynamicsWorld& m_world;
    btBoxShape m_shape;
    std::unique_ptr<btRigidBody> m_body;
};

/// Give the convex hulls of a body's compound shape Bullet's polyhedral features (contact clipping against
/// other polyhedral shapes, see PolyhedralSeabed).
void usePolyhedralContacts(btRigidBody* body) {
    auto* compound = dynamic_cast<btCompoundShape*>(body->getCollisionShape());
    for (int i = 0; compound && i < compound->getNumChildShapes(); ++i)
        if (auto* hull = dynamic_cast<btPolyhedralConvexShape*>(compound->getChildShape(i)))
            hull->initializePolyhedralFeatures();
}

/// One random case of the property test; returns false (and prints it) when a property fails.
struct CaseResult {
    bool finite, bounded, rest;
    double speed, maxSpeed;
};

CaseResult randomCase(std::mt19937& rng, const std::vector<std::shared_ptr<const btBuoyancyShape>>& shapes,
                      const std::vector<double>& halfHeights, const std::vector<double>& hzChoices, double seconds,
                      int index) {
    std::uniform_real_distribution<double> U(0, 1);
    const std::size_t k = std::min(shapes.size() - 1, std::size_t(U(rng) * shapes.size()));
    // Density ratio log-uniform in [0.01, 20] (the hard cases' extremes).
    const double s = std::exp(std::log(0.01) + U(rng) * (std::log(20.0) - std::log(0.01)));
    const btVector3 p(btScalar(U(rng) * 2 - 1), btScalar(-3 + 6 * U(rng)), btScalar(U(rng) * 2 - 1));
    const btVector3 axis(btScalar(U(rng) - 0.5), btScalar(U(rng) - 0.5), btScalar(U(rng) - 0.5) + btScalar(1e-3));
    const double deg = 360 * U(rng);
    const btVector3 v(btScalar(8 * U(rng) - 4), btScalar(8 * U(rng) - 4), btScalar(8 * U(rng) - 4));
    const btVector3 om(btScalar(10 * U(rng) - 5), btScalar(10 * U(rng) - 5), btScalar(10 * U(rng) - 5));
    const std::size_t nHz = hzChoices.size();
    const double hz = hzChoices[std::min(nHz - 1, std::size_t(U(rng) * nHz))];

    BulletTestWorld w;
    const PolyhedralSeabed seabed(w, -4);  // not a plane: see PolyhedralSeabed
    btBuoyantBodySettings body;
    body.density = 1000 * s;
    btBuoyancySettings bs;  // library defaults: drag, linear damping, added mass on
    w.add(shapes[k], body, makePose(p, axis, deg), bs);
    usePolyhedralContacts(w.rigid(0));
    w.rigid(0)->setLinearVelocity(v);
    w.rigid(0)->setAngularVelocity(om);
    // Bounds: the initial mechanical energy plus the buoyancy work available (lifting the whole volume from
    // the ground to the surface) caps the speed at sqrt(v0² + ω-energy + 2 g (4 + 3)/s) loosely; use a
    // generous physical cap: sqrt(|v0|² + (R|ω0|)² + 2 g 7 (1 + 1/s)).
    const double Rb = halfHeights[k];
    const double vcap = std::sqrt(double(v.length2()) + Rb * Rb * double(om.length2()) + 2 * 9.81 * 7 * (1 + 1 / s));
    const Track tr = runTracked(w, seconds, std::max(1, int(hz / 60)), 1.0 / hz);
    (void)index;
    // Ground penetration: a discrete-time solver only sees a contact after the substep that made it, so a
    // point arriving at speed v can be up to v·dt inside the seabed for a step before Bullet pushes it out;
    // no point of the body moves faster than |v_COM| + |ω| R. More than that (+ the 5 mm collision margin)
    // means the contact failed.
    const double penetrationBound = (tr.maxSpeed + tr.maxOmega * Rb) / hz + 0.005;
    CaseResult r{tr.finite, tr.finite && tr.maxSpeed < vcap && tr.maxY < 3 + vcap * vcap / (2 * 9.81) + Rb &&
                                tr.minLowest > -4 - penetrationBound,
                 tr.finite && tr.omega < 0.5 && (tr.speed < 0.05 || (std::abs(1 - s) < 0.1 && tr.speed < 0.2)),
                 tr.speed, tr.maxSpeed};
    // (Near-neutral bodies, |1 − s| < 0.1, may still be sinking or rising at their small terminal speed.)
    if (!r.finite || !r.bounded || !r.rest)
        std::printf("property case %d FAILED: shape %zu s=%.4f p=(%.2f %.2f %.2f) v=(%.2f %.2f %.2f) w=(%.2f %.2f %.2f) "
                    "%g Hz: finite %d, max speed %.3f (cap %.3f), y range [%.3f, %.3f], lowest point %.3f (bound %.3f), "
                    "end speed %.3g omega %.3g\n",
                    index, k, s, double(p.x()), double(p.y()), double(p.z()), double(v.x()), double(v.y()),
                    double(v.z()), double(om.x()), double(om.y()), double(om.z()), hz, int(tr.finite), tr.maxSpeed,
                    vcap, tr.minY, tr.maxY, tr.minLowest, -4 - penetrationBound, tr.speed, tr.omega);
    return r;
}

void propertyTest(int cases, std::uint32_t seed, const std::vector<double>& hzChoices, double seconds) {
    std::vector<std::shared_ptr<const btBuoyancyShape>> shapes;
    std::vector<double> radii;
    const btBuoyancySettings bs;
    shapes.push_back(btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.4, 0.6), bs));
    radii.push_back(0.6);
    shapes.push_back(btBuoyancyShape::create(buoyancy::makeBoxMesh(0.3, 0.3, 0.3), bs));
    radii.push_back(0.26);
    shapes.push_back(btBuoyancyShape::create(buoyancy::makeSphereMesh(0.4, 16, 8), bs));
    radii.push_back(0.4);
    shapes.push_back(btBuoyancyShape::create(buoyancy::makeCylinderMesh(0.25, 1.2, 16), bs));
    radii.push_back(0.65);
    std::mt19937 rng(seed);
    int notFinite = 0, unbounded = 0, notRest = 0;
    double worstEnd = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int i = 0; i < cases; ++i) {
        const CaseResult r = randomCase(rng, shapes, radii, hzChoices, seconds, i);
        notFinite += !r.finite;
        unbounded += !r.bounded;
        notRest += !r.rest;
        if (r.finite) worstEnd = std::max(worstEnd, r.speed);
    }
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("property test: %d cases (seed %u): %d non-finite, %d unbounded, %d not at rest; worst final speed "
                "%.3g m/s; %.2f s\n",
                cases, seed, notFinite, unbounded, notRest, worstEnd, sec);
    CHECK(notFinite == 0);
    CHECK(unbounded == 0);
    CHECK(notRest == 0);
}

}  // namespace

TEST_CASE("property: random poses, velocities and densities stay finite, bounded and come to rest",
          "[bullet][hard][property][slow]") {
    // 20 s: on a plane seabed heavy cylinders thrown spinning needed ~30 s to stop rolling (40 s was used);
    // on the polyhedral seabed all 200 are at rest after 15 s.
    propertyTest(200, 12345u, {60.0}, 20.0);
}

// Long run (scripts/long-tests.sh): dt ∈ {1/30, 1/60, 1/120, 1/240}, 20 s, seed 987654. Before the
// seabed fixes (one contact point per convex-vs-plane pair, COM-height bound): in the first 1020 cases 34
// failed (18 0.3 m cubes spinning on the seabed at 30 Hz, 13 cylinders rolling, 3 below the loose COM bound).
// With several contact points per plane contact and the penetration bound (|v| + |ω| R)·dt: 3000 cases,
// 0 non-finite, 1 unbounded, 47 not at rest (43 sunk cylinders rolling on the seabed at a constant speed,
// 36 of them at 30 Hz; 4 cubes at 30 Hz, light floating ones at s ≈ 0.011 still tumbling).
// What kept the cylinders rolling is Bullet's convex-vs-plane contact, not the buoyancy action. Without water
// (no action; gravity set to the net weight), a 16-sided cylinder (R 0.25 m, s = 10) rolling on the
// btStaticPlaneShape seabed at 30 Hz speeds up from 0.5 to 2.1 m/s (kinetic energy 440 J -> 7.6 kJ in 20 s;
// at 60 Hz it keeps 0.42 m/s, at 240 Hz it stops in 8 s). The contact solves only take kinetic energy away
// (121 kJ in 20 s; +39 J in the few substeps that add any), but each substep the plane algorithm adds one
// point, at the deepest vertex, which at 0.27 rad per substep (0.7 of a facet) is found already under the
// centre and 4–6 cm deep: the leading edge never has a point before it lands, so there is no edge-over
// impact, and the normal impulses, on average 0.5 cm behind the centre (0.5 cm ahead on the seabed below),
// turn each substep's gravity kick into rolling: +8,400 N m s of angular impulse along the spin in 20 s
// (+430 at 240 Hz). The action adds a constant force (closed form, no torque, when submerged) and drag, which took
// energy away in every substep (case 429: -13.2 kJ from 5 to 20 s); the cylinder rolled on where drag
// balanced Bullet's gain (0.3-1.5 m/s). With any one of drag, linear damping, added mass, the drag
// stability scale, drag at the predicted velocity, the priming kick, the sleeping-threshold switch, split
// impulse or warm starting turned off, it still rolled. The seabed's rolling friction does nothing here:
// Bullet 3.24 caps each contact's rolling-friction impulse at the coefficient itself (μ_r N m s per substep,
// whatever the normal impulse): 0.05 × ~3 contacts × 30 Hz ≈ 5 N m against a 2.3 t cylinder.
// So the seabed here is a polyhedral box and the hull has polyhedral features (PolyhedralSeabed): contact
// clipping keeps the touching face, the leading edge gets a point before it lands, and without water the
// same cylinder stops in 5 s at 30 Hz (its energy falls ×0.3 per second; the edge-impact loss of a
// 16-gon, angular momentum kept about the new edge, gives ((1/2 + cos 22.5°)/1.5)² = 0.90 per edge, ×0.2
// per second at 6 rad/s). With it the cylinders come to rest.
// The light floating bodies at game time steps, 0.3 m cubes at s ≈ 0.011 at 30 Hz (draft 3.4 mm: heave ω·dt ≈ 1.5 with
// added mass, roll ω·dt ≈ 1.2 with none, design.md 2.7), also come to rest at the defaults, whose wave-radiation
// damping scales with the body and fades with depth (design.md 2.6): 3000 cases, 0 non-finite, 0 unbounded, 0 not at
// rest in both precisions (worst final speed 0.195 m/s with the waterplane's heave added mass, design.md 2.7; 0.109 m/s
// with the volume rule alone), about 50 s on one core.
TEST_CASE("property (long): thousands of random cases", "[bullet][hard][property][long]") {
    propertyTest(3000, 987654u, {30.0, 60.0, 120.0, 240.0}, 20.0);
}


// A shallow-draft light body must still feel sideways drag (design.md 6 item 10): drag samples wet by a
// ramp over their vertical extent, not all-or-nothing by their centre (which left a 1 x 0.4 x 0.6 box at
// s = 0.03 drifting at 0.13-0.22 m/s after 15 s).
TEST_CASE("a shallow-draft light box pushed sideways comes to rest", "[bullet][hard]") {
    SECTION("1 x 0.4 x 0.6 box at s = 0.03 pushed at 1 m/s") {
        auto shape = btBuoyancyShape::create(buoyancy::makeBoxMesh(1.0, 0.4, 0.6), btBuoyancySettings());
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 30;
        w.add(shape, body, makePose(btVector3(0, btScalar(0.2 - 0.03 * 0.4), 0)), btBuoyancySettings());
        w.rigid(0)->setLinearVelocity(btVector3(1, 0, 0));
        // 25 s: once the quadratic drag has slowed it, the sway decays through the linear (radiation) damping, whose
        // coefficient scales with the body (β g / ω_n ≈ 0.13 m/s for this light box, design.md 2.6): e-folding
        // in ≈ 6 s over its 1.2 cm-deep sides.
        const Track tr = runTracked(w, 25, 1, 1.0 / 60);
        std::printf("shallow light box pushed sideways: mean speed over the last second %.4f m/s, x %.2f m\n", tr.speed,
                    double(w.rigid(0)->getCenterOfMassPosition().x()));
        REQUIRE(tr.finite);
        CHECK(tr.speed < 0.01);
    }
    SECTION("a 7 cm box at s = 0.01 and 60 Hz (s c ~ g dt^2 / 4, design.md 2.7)") {
        const double cs = 0.07;
        auto small = btBuoyancyShape::create(buoyancy::makeBoxMesh(cs, cs, cs), exactMesh());
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 10;
        w.add(small, body, makePose(btVector3(0, 0.1, 0), btVector3(1, 0, 1), 20), exactMesh());
        const Track tr = runTracked(w, 20, 1, 1.0 / 60);
        std::printf("hard 7 cm s=0.01 @60Hz: max speed %.3f m/s, max y %.3f, final y %.5f, speed %.2e\n", tr.maxSpeed,
                    tr.maxY, tr.y, tr.speed);
        REQUIRE(tr.finite);
        CHECK(tr.maxSpeed < 5.0);
        CHECK(tr.maxY < 0.2);
        CHECK(tr.y > 0 - 1e-3);  // floats (its centre can only be above the water line at s = 0.01)
        CHECK(tr.y < cs);
        CHECK(tr.speed < 0.02);
    }
}
