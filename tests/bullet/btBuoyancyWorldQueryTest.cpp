// World queries for game logic without a body (btBuoyancyWorld::queryWater) and the debug drawing of the water
// surfaces (btBuoyancyWorld::debugDrawWater), in a y-up and a Z-up world, with one unbounded water and with water
// bodies. Oracles: flat water's level (height, depth, normal up, velocity its current); Gerstner waves evaluated in
// the test from the wave formula of btGerstnerWaterSurface.h (the rest position found by a fixed-point iteration in
// long double, the normal from the parametric surface's tangents, the orbital velocity from its time derivative);
// the water frame's documented axes for a Z-up world (x̂ = +x, ẑ = x̂ × up = −y).
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

using Catch::Matchers::Contains;

namespace {

constexpr double kGravity = 9.81;  ///< m/s²
constexpr long double kPi = 3.14159265358979323846264338327950288L;

/// Tolerance of a btScalar result of size `scale`, m: float builds round to 1e-7 relative.
double tol(double scale) { return (sizeof(btScalar) == 4 ? 2e-5 : 1e-9) * (1.0 + std::abs(scale)); }

btDynamicsWorld* withGravity(btDynamicsWorld* world, const btVector3& gravity) {
    world->setGravity(gravity);
    return world;
}

struct QueryWorld {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher{&config};
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
    btBuoyancyWorld buoyancy;
    explicit QueryWorld(const btWaterSurface* water, const btVector3& gravity = btVector3(0, btScalar(-kGravity), 0))
        : buoyancy(withGravity(&world, gravity), water) {}
};

/// The Gerstner waves of the tests, evaluated from btGerstnerWaterSurface.h's formula in long double:
///   x = x₀ − Σ Q A d sin θ,  y = h + Σ A cos θ,  θ = k d·x₀ − ω t + φ,  ω² = g k.
struct WaveFormula {
    std::vector<btGerstnerWave> waves;
    double h = 0;
    /// The rest position x₀ of the particle at horizontal position (x, z): the fixed point of
    /// x₀ = x + Σ Q A d sin θ(x₀) (a contraction while Σ Q A k < 1).
    void rest(long double x, long double z, long double t, long double& x0, long double& z0) const {
        x0 = x;
        z0 = z;
        for (int it = 0; it < 400; ++it) {
            long double nx = x, nz = z;
            for (const btGerstnerWave& w : waves) {
                const long double dn = std::sqrt((long double)w.directionX * w.directionX + (long double)w.directionZ * w.directionZ);
                const long double dx = w.directionX / dn, dz = w.directionZ / dn;
                const long double k = 2 * kPi / w.wavelength, omega = std::sqrt((long double)kGravity * k);
                const long double theta = k * (dx * x0 + dz * z0) - omega * t + w.phase;
                nx += w.steepness * w.amplitude * dx * std::sin(theta);
                nz += w.steepness * w.amplitude * dz * std::sin(theta);
            }
            x0 = nx;
            z0 = nz;
        }
    }
    /// Height, upward unit normal and orbital velocity at water coordinates (x, y, z) (y: where the velocity is
    /// wanted), at time t: the normal is Tz × Tx of the parametric surface's tangents ∂P/∂z₀, ∂P/∂x₀; the velocity
    /// ∂P/∂t scaled by e^{k min(0, y − h)}.
    void at(double x, double y, double z, double t, double& height, Eigen::Vector3d& normal, Eigen::Vector3d& velocity) const {
        long double x0 = 0, z0 = 0;
        rest(x, z, t, x0, z0);
        long double H = h, tx[3] = {1, 0, 0}, tz[3] = {0, 0, 1}, v[3] = {0, 0, 0};
        for (const btGerstnerWave& w : waves) {
            const long double dn = std::sqrt((long double)w.directionX * w.directionX + (long double)w.directionZ * w.directionZ);
            const long double dx = w.directionX / dn, dz = w.directionZ / dn;
            const long double k = 2 * kPi / w.wavelength, omega = std::sqrt((long double)kGravity * k);
            const long double theta = k * (dx * x0 + dz * z0) - omega * t + w.phase;
            const long double a = w.amplitude, qa = w.steepness * w.amplitude, c = std::cos(theta), s = std::sin(theta);
            H += a * c;
            tx[0] -= qa * k * dx * dx * c;
            tx[1] -= a * k * dx * s;
            tx[2] -= qa * k * dx * dz * c;
            tz[0] -= qa * k * dx * dz * c;
            tz[1] -= a * k * dz * s;
            tz[2] -= qa * k * dz * dz * c;
            const long double decay = std::exp(k * std::min((long double)y - h, (long double)0));
            v[0] += qa * omega * dx * c * decay;
            v[1] += a * omega * s * decay;
            v[2] += qa * omega * dz * c * decay;
        }
        height = double(H);
        const Eigen::Vector3d Tx{double(tx[0]), double(tx[1]), double(tx[2])};
        const Eigen::Vector3d Tz{double(tz[0]), double(tz[1]), double(tz[2])};
        normal = Tz.cross(Tx).normalized();
        velocity = Eigen::Vector3d(double(v[0]), double(v[1]), double(v[2]));
    }
};

Eigen::Vector3d toEigen(const btVector3& v) { return Eigen::Vector3d(double(v.x()), double(v.y()), double(v.z())); }

/// A btIDebugDraw that keeps every line.
struct LineRecorder : btIDebugDraw {
    struct Line {
        btVector3 from, to, colour;
    };
    std::vector<Line> lines;
    int mode = DBG_DrawWireframe;
    void drawLine(const btVector3& from, const btVector3& to, const btVector3& colour) override {
        lines.push_back(Line{from, to, colour});
    }
    void drawContactPoint(const btVector3&, const btVector3&, btScalar, int, const btVector3&) override {}
    void reportErrorWarning(const char*) override {}
    void draw3dText(const btVector3&, const char*) override {}
    void setDebugMode(int m) override { mode = m; }
    int getDebugMode() const override { return mode; }
};

}  // namespace

TEST_CASE("water queries: flat unbounded water in a y-up world", "[bullet][queries]") {
    // Level 0.4 m, a uniform current (0.3, 0, -0.2) m/s.
    btFlatWaterSurface water(0.4, 0.3, -0.2);
    QueryWorld w(&water);
    const btWaterQueryResult under = w.buoyancy.queryWater(btVector3(2, btScalar(-0.3), 5));
    CHECK(under.hasWater);
    CHECK(under.inWater);
    CHECK(under.waterBody == -1);
    CHECK(std::string(under.waterBodyName).empty());
    CHECK(double(under.surfaceHeight) == Approx(0.4).margin(tol(0.4)));
    CHECK(double(under.depth) == Approx(0.7).margin(tol(1)));
    CHECK((toEigen(under.surfacePoint) - Eigen::Vector3d(2, 0.4, 5)).norm() <= tol(5));
    CHECK((toEigen(under.normal) - Eigen::Vector3d(0, 1, 0)).norm() <= tol(1));
    CHECK((toEigen(under.velocity) - Eigen::Vector3d(0.3, 0, -0.2)).norm() <= tol(1));
    const btWaterQueryResult above = w.buoyancy.queryWater(btVector3(-7, 2, 1));
    CHECK(above.hasWater);
    CHECK_FALSE(above.inWater);
    CHECK(double(above.depth) == Approx(0.4 - 2.0).margin(tol(2)));
    CHECK((toEigen(above.velocity) - Eigen::Vector3d(0.3, 0, -0.2)).norm() <= tol(1));
    // On the surface: depth 0 counts as in the water.
    btFlatWaterSurface level(0.5);  // a level btScalar holds exactly
    w.buoyancy.setWater(&level);
    CHECK(w.buoyancy.queryWater(btVector3(1, btScalar(0.5), 1)).inWater);
    CHECK(w.buoyancy.queryWater(btVector3(1, btScalar(0.5), 1)).depth == 0);
    CHECK_THROWS_AS(w.buoyancy.queryWater(btVector3(0, btScalar(std::nan("")), 0)), std::invalid_argument);
    CHECK_THROWS_WITH(w.buoyancy.queryWater(btVector3(0, btScalar(std::nan("")), 0)), Contains("queryWater") && Contains("not finite"));
    // No water at all: nothing there.
    w.buoyancy.setWater(nullptr);
    const btWaterQueryResult none = w.buoyancy.queryWater(btVector3(0, -1, 0));
    CHECK_FALSE(none.hasWater);
    CHECK_FALSE(none.inWater);
}

TEST_CASE("water queries: each water body answers inside its region only", "[bullet][queries]") {
    btFlatWaterSurface pool(0.0), lake(1.5);
    QueryWorld w(nullptr);
    w.buoyancy.addWaterBody(btWaterBodyInfo{"pool", &pool, 1000.0, btVector3(-6, -2, -3), btVector3(-1, 0.5, 3)});
    w.buoyancy.addWaterBody(btWaterBodyInfo{"lake", &lake, 1025.0, btVector3(1, -2, -3), btVector3(9, 2.5, 3)});
    const btWaterQueryResult inPool = w.buoyancy.queryWater(btVector3(-3, -1, 0));
    CHECK(inPool.hasWater);
    CHECK(inPool.inWater);
    CHECK(inPool.waterBody == 0);
    CHECK(std::string(inPool.waterBodyName) == "pool");
    CHECK(double(inPool.depth) == Approx(1.0).margin(tol(1)));
    const btWaterQueryResult inLake = w.buoyancy.queryWater(btVector3(4, 0, 2));
    CHECK(inLake.waterBody == 1);
    CHECK(std::string(inLake.waterBodyName) == "lake");
    CHECK(double(inLake.surfaceHeight) == Approx(1.5).margin(tol(1.5)));
    CHECK(double(inLake.depth) == Approx(1.5).margin(tol(1.5)));
    // Above the pool's box (a footstep on a diving board): the pool's surface below, not in the water.
    const btWaterQueryResult abovePool = w.buoyancy.queryWater(btVector3(-2, 3, 1));
    CHECK(abovePool.hasWater);
    CHECK_FALSE(abovePool.inWater);
    CHECK(abovePool.waterBody == 0);
    CHECK(double(abovePool.depth) == Approx(-3.0).margin(tol(3)));
    // Between the regions, beside them and under a region's bottom: no water.
    for (const btVector3& p : {btVector3(0, -1, 0), btVector3(4, 0, 5), btVector3(-3, -2.5, 0)}) {
        const btWaterQueryResult r = w.buoyancy.queryWater(p);
        CHECK_FALSE(r.hasWater);
        CHECK_FALSE(r.inWater);
        CHECK(r.waterBody == -1);
    }
}

TEST_CASE("water queries: Gerstner waves against the wave formula", "[bullet][queries]") {
    WaveFormula f;
    f.h = 0.25;
    btGerstnerWave a;
    a.amplitude = 0.6;
    a.wavelength = 18.0;
    a.directionX = 1.0;
    a.directionZ = 0.4;
    a.steepness = 0.7;
    a.phase = 0.3;
    btGerstnerWave b;
    b.amplitude = 0.2;
    b.wavelength = 7.0;
    b.directionX = -0.3;
    b.directionZ = 1.0;
    b.steepness = 0.5;
    b.phase = 1.9;
    f.waves = {a, b};
    const btGerstnerWaterSurface waves(f.waves, f.h, kGravity);
    const double t = 3.7;
    SECTION("y-up") {
        QueryWorld w(&waves);
        w.buoyancy.setTime(t);
        for (const Eigen::Vector3d& p : {Eigen::Vector3d(1.3, -0.8, -2.1), Eigen::Vector3d(-11.0, 1.5, 6.25),
                                         Eigen::Vector3d(40.0, 0.0, 3.0)}) {
            double height = 0;
            Eigen::Vector3d normal, velocity;
            f.at(p.x(), p.y(), p.z(), t, height, normal, velocity);
            const bool under = height >= p.y();
            if (!under) f.at(p.x(), height, p.z(), t, height, normal, velocity);  // the velocity at the surface
            const btWaterQueryResult r = w.buoyancy.queryWater(btVector3(btScalar(p.x()), btScalar(p.y()), btScalar(p.z())));
            INFO("point " << p.transpose());
            CHECK(r.hasWater);
            CHECK(r.inWater == under);
            CHECK(double(r.surfaceHeight) == Approx(height).margin(tol(1)));
            CHECK(double(r.depth) == Approx(height - p.y()).margin(tol(1)));
            CHECK((toEigen(r.surfacePoint) - Eigen::Vector3d(p.x(), height, p.z())).norm() <= tol(40));
            CHECK((toEigen(r.normal) - normal).norm() <= 1e-4);  // central differences over λ_min / 1000
            CHECK((toEigen(r.velocity) - velocity).norm() <= tol(1) + 1e-9);
        }
    }
    SECTION("Z-up: water coordinates (x, z) are world (x, -y)") {
        QueryWorld w(&waves, btVector3(0, 0, btScalar(-kGravity)));
        w.buoyancy.setTime(t);
        for (const Eigen::Vector3d& p : {Eigen::Vector3d(1.3, 2.1, -0.8), Eigen::Vector3d(-11.0, -6.25, 1.5)}) {
            // World (X, Y, Z) is water (X, Z, −Y); a water vector (u, v, w) is the world vector (u, −w, v).
            double height = 0;
            Eigen::Vector3d normal, velocity;
            f.at(p.x(), p.z(), -p.y(), t, height, normal, velocity);
            const bool under = height >= p.z();
            if (!under) f.at(p.x(), height, -p.y(), t, height, normal, velocity);
            const btWaterQueryResult r = w.buoyancy.queryWater(btVector3(btScalar(p.x()), btScalar(p.y()), btScalar(p.z())));
            INFO("point " << p.transpose());
            CHECK(r.inWater == under);
            CHECK(double(r.surfaceHeight) == Approx(height).margin(tol(1)));
            CHECK(double(r.depth) == Approx(height - p.z()).margin(tol(1)));
            CHECK((toEigen(r.surfacePoint) - Eigen::Vector3d(p.x(), p.y(), height)).norm() <= tol(12));
            CHECK((toEigen(r.normal) - Eigen::Vector3d(normal.x(), -normal.z(), normal.y())).norm() <= 1e-4);
            CHECK((toEigen(r.velocity) - Eigen::Vector3d(velocity.x(), -velocity.z(), velocity.y())).norm() <=
                  tol(1) + 1e-9);
        }
    }
}

TEST_CASE("water queries: flat water and water bodies in a Z-up world", "[bullet][queries]") {
    btFlatWaterSurface pool(1.0, 0.5, 0.25);  // level 1 m along +z; current along water x̂ = +x and ẑ = −y
    QueryWorld w(nullptr, btVector3(0, 0, btScalar(-kGravity)));
    w.buoyancy.addWaterBody(btWaterBodyInfo{"pool", &pool, 1000.0, btVector3(0, 0, -2), btVector3(4, 4, 1.5)});
    const btWaterQueryResult r = w.buoyancy.queryWater(btVector3(1, 2, btScalar(-0.5)));
    CHECK(r.hasWater);
    CHECK(r.inWater);
    CHECK(r.waterBody == 0);
    CHECK(double(r.surfaceHeight) == Approx(1.0).margin(tol(1)));
    CHECK(double(r.depth) == Approx(1.5).margin(tol(1.5)));
    CHECK((toEigen(r.surfacePoint) - Eigen::Vector3d(1, 2, 1)).norm() <= tol(2));
    CHECK((toEigen(r.normal) - Eigen::Vector3d(0, 0, 1)).norm() <= tol(1));
    CHECK((toEigen(r.velocity) - Eigen::Vector3d(0.5, -0.25, 0)).norm() <= tol(1));
    // Above the box's top (+z) the pool is still below; beside it (y > 4) or under its bottom (z < −2) nothing.
    const btWaterQueryResult above = w.buoyancy.queryWater(btVector3(1, 2, 5));
    CHECK(above.hasWater);
    CHECK_FALSE(above.inWater);
    CHECK(double(above.depth) == Approx(-4.0).margin(tol(4)));
    CHECK_FALSE(w.buoyancy.queryWater(btVector3(1, 5, 0)).hasWater);
    CHECK_FALSE(w.buoyancy.queryWater(btVector3(1, 2, -3)).hasWater);
}

TEST_CASE("water debug drawing: a grid of segments on each surface", "[bullet][queries]") {
    SECTION("water bodies: a grid over each region's footprint at its level") {
        btFlatWaterSurface pool(0.0), lake(1.5);
        QueryWorld w(nullptr);
        w.buoyancy.addWaterBody(btWaterBodyInfo{"pool", &pool, 1000.0, btVector3(-6, -2, -3), btVector3(-1, 0.5, 3)});
        w.buoyancy.addWaterBody(btWaterBodyInfo{"lake", &lake, 1025.0, btVector3(1, -2, -3), btVector3(9, 2.5, 3)});
        LineRecorder rec;
        const int n = 8;
        w.buoyancy.debugDrawWater(&rec, btVector3(0, 0, 0), 50, n, btVector3(1, 0, 0));
        REQUIRE(rec.lines.size() == std::size_t(2 * 2 * n * (n + 1)));  // per surface n + 1 lines of n segments each way
        Eigen::Vector2d poolMin(1e9, 1e9), poolMax(-1e9, -1e9);
        for (const LineRecorder::Line& l : rec.lines) {
            CHECK(toEigen(l.colour) == Eigen::Vector3d(1, 0, 0));
            for (const btVector3& p : {l.from, l.to}) {
                const double x = double(p.x()), y = double(p.y()), z = double(p.z());
                const bool inPool = x >= -6 - tol(6) && x <= -1 + tol(6);
                const bool inLake = x >= 1 - tol(9) && x <= 9 + tol(9);
                REQUIRE((inPool || inLake));
                CHECK(z >= -3 - tol(3));
                CHECK(z <= 3 + tol(3));
                CHECK(y == Approx(inPool ? 0.0 : 1.5).margin(tol(1.5)));
                if (inPool) {
                    poolMin = poolMin.cwiseMin(Eigen::Vector2d(x, z));
                    poolMax = poolMax.cwiseMax(Eigen::Vector2d(x, z));
                }
            }
            // Neighbours along x or z: a cell of the pool's 5 × 6 m or the lake's 8 × 6 m footprint.
            const double length = double((l.to - l.from).length());
            const bool cell = std::abs(length - 5.0 / n) <= tol(1) || std::abs(length - 6.0 / n) <= tol(1) ||
                              std::abs(length - 8.0 / n) <= tol(1);
            CHECK(cell);
        }
        CHECK((poolMin - Eigen::Vector2d(-6, -3)).norm() <= tol(6));  // the grid covers the footprint
        CHECK((poolMax - Eigen::Vector2d(-1, 3)).norm() <= tol(6));
    }
    SECTION("unbounded Gerstner waves in a Z-up world: every endpoint on the surface") {
        WaveFormula f;
        f.h = -0.5;
        btGerstnerWave a;
        a.amplitude = 0.4;
        a.wavelength = 12.0;
        a.directionX = 0.6;
        a.directionZ = 0.8;
        a.steepness = 0.6;
        f.waves = {a};
        const btGerstnerWaterSurface waves(f.waves, f.h, kGravity);
        QueryWorld w(&waves, btVector3(0, 0, btScalar(-kGravity)));
        w.buoyancy.setTime(1.25);
        LineRecorder rec;
        const int n = 6;
        const double half = 10.0;
        w.buoyancy.debugDrawWater(&rec, btVector3(3, -2, 7), btScalar(half), n);
        REQUIRE(rec.lines.size() == std::size_t(2 * n * (n + 1)));
        for (const LineRecorder::Line& l : rec.lines)
            for (const btVector3& p : {l.from, l.to}) {
                const double x = double(p.x()), y = double(p.y()), z = double(p.z());
                // Around the centre's horizontal position (3, −2); the height along +z at water (x, −y).
                CHECK(std::abs(x - 3) <= half + tol(13));
                CHECK(std::abs(y + 2) <= half + tol(12));
                double height = 0;
                Eigen::Vector3d normal, velocity;
                f.at(x, 0, -y, 1.25, height, normal, velocity);
                CHECK(z == Approx(height).margin(tol(13)));
            }
    }
    SECTION("bad arguments are refused") {
        btFlatWaterSurface water(0.0);
        QueryWorld w(&water);
        LineRecorder rec;
        CHECK_THROWS_AS(w.buoyancy.debugDrawWater(nullptr), std::invalid_argument);
        CHECK_THROWS_WITH(w.buoyancy.debugDrawWater(nullptr), Contains("drawer"));
        CHECK_THROWS_AS(w.buoyancy.debugDrawWater(&rec, btVector3(0, 0, 0), 0), std::invalid_argument);
        CHECK_THROWS_WITH(w.buoyancy.debugDrawWater(&rec, btVector3(0, 0, 0), 0), Contains("halfSize"));
        CHECK_THROWS_AS(w.buoyancy.debugDrawWater(&rec, btVector3(0, 0, 0), 5, 0), std::invalid_argument);
        CHECK_THROWS_WITH(w.buoyancy.debugDrawWater(&rec, btVector3(0, 0, 0), 5, 0), Contains("cellsPerSide"));
        CHECK(rec.lines.empty());
    }
}
