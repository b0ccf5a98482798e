// Every shipped scene (bullet_examples/scenes/*.json) through the runner with its expected outcome against
// an analytic oracle; the default primitive resolution against the analytic volumes; the substep count not
// changing a dynamic motion. (hard_cases.json is covered by RunCommandTest.cpp.)
#include <unistd.h>
#include "oracles/BulletTestWorld.h"
#include "cli/RunCommand.h"
#include "scene/SceneFile.h"
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kScenes = std::string(BUOYANCY_SOURCE_DIR) + "/bullet_examples/scenes/";

/// One CSV row: t, body, then the numeric columns after "body" (x=0, y=1, z=2, qx..qw=3..6, c=7..9,
/// v=10..12, w=13..15, submerged_volume=16, mass=17, water_volume=18, ...).
struct Row {
    double t = 0;
    std::string body;
    std::vector<double> v;
};

/// Run a scene through runSceneCommand; rows grouped by body. Fails the test on a non-zero exit or a
/// non-finite number.
std::map<std::string, std::vector<Row>> runScene(const std::string& file, std::optional<double> duration = std::nullopt) {
    const auto out = std::filesystem::temp_directory_path() / ("buoyancy_scene_test_" + std::to_string(::getpid()) + "_" + file);
    std::filesystem::remove_all(out);
    const auto t0 = std::chrono::steady_clock::now();
    const int rc = buoyancy::cli::runSceneCommand(kScenes + file, out.string(), duration);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("scene %s: exit %d, %.2f s\n", file.c_str(), rc, sec);
    REQUIRE(rc == 0);
    std::ifstream in(out / "trajectory.csv");
    std::string line;
    std::getline(in, line);
    std::map<std::string, std::vector<Row>> rows;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string cell;
        Row r;
        std::getline(ss, cell, ',');
        r.t = std::stod(cell);
        std::getline(ss, r.body, ',');
        while (std::getline(ss, cell, ',')) {
            r.v.push_back(std::stod(cell));
            REQUIRE(std::isfinite(r.v.back()));
        }
        REQUIRE(r.v.size() >= 19);
        rows[r.body].push_back(r);
    }
    return rows;
}

/// Rotation matrix element R(i, j) of the row's quaternion (mesh frame in world).
double rot(const Row& r, int i, int j) {
    const btQuaternion q(btScalar(r.v[3]), btScalar(r.v[4]), btScalar(r.v[5]), btScalar(r.v[6]));
    return double(btMatrix3x3(q)[i][j]);
}

/// Angle between the mesh's y axis and world y, degrees.
double yAxisTilt(const Row& r) { return std::acos(std::clamp(rot(r, 1, 1), -1.0, 1.0)) * 180.0 / M_PI; }

/// Angle between the body axis closest to vertical and world y, degrees.
double closestAxisTilt(const Row& r) {
    double best = 0;
    for (int k = 0; k < 3; ++k) best = std::max(best, std::abs(rot(r, 1, k)));
    return std::acos(std::min(1.0, best)) * 180.0 / M_PI;
}

/// Mean and range (max − min) of column `col` over rows with t ≥ tFrom.
std::pair<double, double> meanRange(const std::vector<Row>& rows, int col, double tFrom) {
    double sum = 0, lo = 1e300, hi = -1e300;
    int n = 0;
    for (const Row& r : rows)
        if (r.t >= tFrom - 1e-9) {
            sum += r.v[col];
            lo = std::min(lo, r.v[col]);
            hi = std::max(hi, r.v[col]);
            ++n;
        }
    return {n ? sum / n : 0.0, hi - lo};
}

}  // namespace

TEST_CASE("scene plank.json floats at its draft", "[bullet][scenes]") {
    const auto rows = runScene("plank.json");
    const auto& p = rows.at("plank");
    // Box 2 × 0.4 × 1 at s = 0.5: draft s c = 0.2, centre at the water line.
    const auto [y, range] = meanRange(p, 1, p.back().t - 2.0);
    std::printf("plank: mean centre y over the last 2 s %.6f (theory 0), range %.2e, tilt %.3f deg\n", y, range,
                closestAxisTilt(p.back()));
    CHECK(std::abs(y) < 0.005 * 0.4);
    CHECK(range < 0.005);
    CHECK(closestAxisTilt(p.back()) < 1.0);
}

TEST_CASE("scene pool_and_lake.json: each crate floats in its own water body, the stone between them falls", "[bullet][scenes]") {
    const auto rows = runScene("pool_and_lake.json");
    // Boxes 1 × 0.5 × 1 of density 500: draft ρ_b/ρ_w · 0.5, centre at level − draft + 0.25. The pool: level 0,
    // 1000 kg/m³ (centre at 0); the lake: level 1.5, 1025 kg/m³.
    const auto& pool = rows.at("pool_crate");
    const auto& lake = rows.at("lake_crate");
    const double poolCentre = 0.0 - 500.0 / 1000.0 * 0.5 + 0.25, lakeCentre = 1.5 - 500.0 / 1025.0 * 0.5 + 0.25;
    const auto [poolY, poolRange] = meanRange(pool, 8, pool.back().t - 2.0);
    const auto [lakeY, lakeRange] = meanRange(lake, 8, lake.back().t - 2.0);
    std::printf("pool_and_lake: pool crate %.5f (theory %.5f), lake crate %.5f (theory %.5f)\n", poolY, poolCentre, lakeY,
                lakeCentre);
    CHECK(poolY == Approx(poolCentre).margin(0.01));
    CHECK(lakeY == Approx(lakeCentre).margin(0.01));
    CHECK(pool.back().v[16] == Approx(250.0 / 1000.0).margin(0.01));  // V_sub = m / ρ_w, m³ (1 m² waterplane: 1 cm)
    CHECK(lake.back().v[16] == Approx(250.0 / 1025.0).margin(0.01));
    // Between the regions there is no water: the stone (radius 0.2 m) falls to the ground at -2, never wet.
    const auto& stone = rows.at("stone");
    CHECK(stone.back().v[8] == Approx(-2.0 + 0.2).margin(0.02));
    for (const Row& r : stone) CHECK(r.v[16] == 0.0);
}

TEST_CASE("scene lake_and_tank.json: a crate floats in the L-shaped lake and one in the tank, the stone in the notch falls",
          "[bullet][scenes]") {
    const auto rows = runScene("lake_and_tank.json");
    // Boxes 1 × 0.5 × 1 of density 500: centre at level − ρ_b/ρ_w · 0.5 + 0.25. The lake: level 0, 1000 kg/m³ (an
    // L-shaped footprint); the tank: level 1, 1025 kg/m³ (a triangular prism given as a mesh).
    const auto& lake = rows.at("lake_crate");
    const auto& tank = rows.at("tank_crate");
    const double lakeCentre = 0.0 - 500.0 / 1000.0 * 0.5 + 0.25, tankCentre = 1.0 - 500.0 / 1025.0 * 0.5 + 0.25;
    const auto [lakeY, lakeRange] = meanRange(lake, 8, lake.back().t - 2.0);
    const auto [tankY, tankRange] = meanRange(tank, 8, tank.back().t - 2.0);
    std::printf("lake_and_tank: lake crate %.5f (theory %.5f), tank crate %.5f (theory %.5f)\n", lakeY, lakeCentre, tankY,
                tankCentre);
    CHECK(lakeY == Approx(lakeCentre).margin(0.01));
    CHECK(tankY == Approx(tankCentre).margin(0.01));
    CHECK(lake.back().v[16] == Approx(250.0 / 1000.0).margin(0.01));  // V_sub = m / ρ_w, m³
    CHECK(tank.back().v[16] == Approx(250.0 / 1025.0).margin(0.01));
    // The notch of the L holds no water: the stone (radius 0.2 m) falls to the ground at -2, never wet.
    const auto& stone = rows.at("stone");
    CHECK(stone.back().v[8] == Approx(-2.0 + 0.2).margin(0.02));
    for (const Row& r : stone) CHECK(r.v[16] == 0.0);
}

TEST_CASE("scene rivers_and_lakes.json: the river carries the boat at its current while the crates float still",
          "[bullet][scenes]") {
    const auto rows = runScene("rivers_and_lakes.json");
    // The boat (4 m hull, density 300, 900 kg) is released at rest on the centreline of a river 8 m wide with 1.5 m/s
    // on the centreline (u(d) = 1.5 (1 − (2d/8)²)). Only drag moves it along the stream, so it approaches the current
    // from below. Its along-stream speed: the COM displacement over a second, at 10 s and at 20 s.
    const auto& boat = rows.at("boat");
    const auto rowAt = [](const std::vector<Row>& r, double t) -> const Row& {
        for (const Row& row : r)
            if (row.t >= t - 1e-9) return row;
        return r.back();
    };
    const auto speedOver = [&](double t0, double t1) {
        const Row &a = rowAt(boat, t0), &b = rowAt(boat, t1);
        return (b.v[7] - a.v[7]) / (b.t - a.t);
    };
    const double d = std::abs(boat.back().v[9]);  // lateral distance from the centreline z = 0
    const double current = 1.5 * (1.0 - (2.0 * d / 8.0) * (2.0 * d / 8.0));
    const double early = current - speedOver(9.0, 10.0), late = current - speedOver(19.0, 20.0);
    std::printf("rivers_and_lakes: boat at x = %.2f, d = %.4f m; along-stream speed %.4f m/s after 20 s against the "
                "current %.4f there (%.1f %% below; %.1f %% after 10 s)\n",
                boat.back().v[7], d, speedOver(19.0, 20.0), current, 100.0 * late / current, 100.0 * early / current);
    // Tolerance 10 % of the local current at 20 s. The quadratic drag alone, ½ ρ C_d A (u − v)² with C_d = 1 on the
    // hull's cross-section A ≈ 0.5 m² (1.4 m beam, 0.5 m draft), leaves u − v = u / (1 + ½ ρ C_d A u t / m′) at time t:
    // 11–15 % of u at 20 s for m′ between the boat's 900 kg and 1.5 times that (added mass). The radiation damping,
    // linear in the same relative velocity, takes it faster (measured: 4.3 % at 20 s, 15.8 % at 10 s). 10 % lies
    // between: it fails if the current were not felt, halved or read at the wrong place, and keeps the drag model's
    // own latitude.
    CHECK(late > 0);  // from below: the current is the only push along the stream
    CHECK(late < 0.10 * current);
    CHECK(late < 0.5 * early);  // still approaching
    CHECK(d < 0.2);             // carried down the centreline, not to a bank
    CHECK(boat.back().v[7] > 20.0);
    CHECK(yAxisTilt(boat.back()) < 5.0);
    // A crate on the river's region beside the channel (d = 5 m > 4 m): still water, it does not move.
    const auto& bank = rows.at("bank_crate");
    CHECK(bank.back().v[7] == Approx(10.0).margin(1e-3));
    CHECK(bank.back().v[9] == Approx(5.0).margin(1e-3));
    // The crates in the pool (level 0) and the lake (level 1.5) float at their own levels: boxes 1 × 0.5 × 1 of
    // density 500 in fresh water, draft 0.25 m, centre at the level.
    const auto [poolY, poolRange] = meanRange(rows.at("pool_crate"), 8, boat.back().t - 2.0);
    const auto [lakeY, lakeRange] = meanRange(rows.at("lake_crate"), 8, boat.back().t - 2.0);
    CHECK(poolY == Approx(0.0).margin(0.01));
    CHECK(lakeY == Approx(1.5).margin(0.01));
    CHECK(poolRange < 0.01);
    CHECK(lakeRange < 0.01);
}

TEST_CASE("scene zup_plank.json: a Z-up world (gravity -z, water frame up +z) floats the plank in its waves", "[bullet][scenes]") {
    // The plank of plank.json, 0.4 m tall along z, in a 0.1 m, 12 m swell along x: its centre follows the swell along z
    // (mean 0 over whole periods: the Gerstner crest is sharper than the trough, so by a little) and stays at y = 0.
    const auto rows = runScene("zup_plank.json");
    const auto& p = rows.at("plank");
    const auto [z, zRange] = meanRange(p, 9, p.back().t - 5.55);  // two periods of 2.77 s
    const auto [y, yRange] = meanRange(p, 8, p.back().t - 5.55);
    std::printf("zup_plank: mean centre z %.4f, range %.3f; mean y %.2e, range %.2e\n", z, zRange, y, yRange);
    CHECK(std::abs(z) < 0.02);
    CHECK(zRange > 0.1);   // heaving with the swell (wave height 0.2 m)
    // Linear theory's heave response of a wall-sided body to a long wave, 1 / (1 − (T_n / T)²) undamped: with
    // T_n = 2π sqrt((m + m_a) / (ρ g A)) = 1.39 s (m 400 kg, A 2 m², heave added mass 0.2 ρ A^(3/2) = 566 kg,
    // design.md 2.7) and T = 2.77 s, 1.34: a range of 0.27 m at most.
    CHECK(zRange < 0.28);
    // Almost nothing along y: the swell runs along x. The box's triangulation is not mirror-symmetric, so on curved
    // water (the quadratic over each triangle) the lateral force is not exactly 0: the plank drifts by 1.2e-5 m in 10 s
    // in both precisions, and the Y-up copy of this scene drifts by the same along its −z (measured, to 1e-14 m).
    const double bar = 1e-4;
    CHECK(std::abs(y) < bar);
    CHECK(yRange < bar);
}

TEST_CASE("scene sphere_half.json: a sphere at s = 0.5 floats with its centre at the water line", "[bullet][scenes]") {
    const auto rows = runScene("sphere_half.json");
    const auto& b = rows.at("ball");
    const auto [y, range] = meanRange(b, 1, b.back().t - 2.0);
    std::printf("sphere_half: mean centre y %.6f (theory 0 by symmetry), range %.2e\n", y, range);
    CHECK(std::abs(y) < 0.005 * 1.0);
    CHECK(range < 0.03);  // still bobbing slightly after 8 s (a sphere's waterplane shrinks off-centre)
}

TEST_CASE("scene cylinder_side.json: a log at s = 0.5 lies on its side at the water line", "[bullet][scenes]") {
    const auto rows = runScene("cylinder_side.json");
    const auto& b = rows.at("log");
    const auto [y, range] = meanRange(b, 1, b.back().t - 2.0);
    const double axisUp = std::abs(rot(b.back(), 1, 1));  // world-y component of the cylinder axis (mesh y)
    std::printf("cylinder_side: mean centre y %.6f (theory 0 by symmetry), axis vertical component %.2e\n", y, axisUp);
    CHECK(std::abs(y) < 0.005 * 0.6);
    CHECK(axisUp < 0.02);
}

TEST_CASE("scene neutral_sphere.json: a neutral sphere stays at its depth", "[bullet][scenes]") {
    const auto rows = runScene("neutral_sphere.json");
    const auto& b = rows.at("ball");
    double worst = 0;
    for (const Row& r : b) worst = std::max(worst, std::sqrt(r.v[0] * r.v[0] + (r.v[1] + 2) * (r.v[1] + 2) + r.v[2] * r.v[2]));
    std::printf("neutral_sphere: largest displacement from (0, -2, 0) over 20 s: %.3g m\n", worst);
    CHECK(b.back().t >= 20.0 - 1e-9);
    CHECK(worst < 0.01);
}

TEST_CASE("scene sinking_sphere.json: reaches the quadratic-drag terminal velocity", "[bullet][scenes]") {
    const auto rows = runScene("sinking_sphere.json");
    const auto& b = rows.at("ball");
    const Row& a = b[b.size() - 2];
    const Row& z = b.back();
    // Mean velocity between the last two rows (the state between kicks, not Bullet's post-kick velocity).
    const double v = -(z.v[1] - a.v[1]) / (z.t - a.t);
    // Oracle: v_t = sqrt(2 (m − ρV) g / (ρ C_d A)); V = m / 2000 (the body's own volume, density 2000); A the
    // silhouette of the default 128-segment sphere seen along its pole: the 128-gon of radius 0.1.
    const double m = z.v[17], V = m / 2000.0, R = 0.1;
    const double A = 0.5 * 128 * R * R * std::sin(2 * M_PI / 128);
    const double vt = std::sqrt(2 * (m - 1000 * V) * 9.81 / (1000 * 1.0 * A));
    std::printf("sinking_sphere: sinking speed after 4 s %.5f m/s, theory %.5f m/s (%.3f%%), y %.3f\n", v, vt,
                100 * (v / vt - 1), z.v[1]);
    CHECK(z.v[1] < -50 - 4);
    CHECK(std::abs(v / vt - 1) < 0.03);
}

TEST_CASE("scene heave_box.json: undamped heave keeps its amplitude at the analytic period", "[bullet][scenes]") {
    const auto rows = runScene("heave_box.json");
    const auto& b = rows.at("box");
    // Box 2 × 0.5 × 2 at s = 0.5 starts 5 cm below its equilibrium (centre at 0): y(t) = −0.05 cos(ω t),
    // T = 2π sqrt(m / (ρ g A_wp)) (added mass off).
    const double m = b[0].v[17];
    const double T = 2 * M_PI * std::sqrt(m / (1000 * 9.81 * 4.0));
    double maxAbs = 0, lastAmp = 0;
    std::vector<double> up;
    for (std::size_t k = 1; k < b.size(); ++k) {
        const double y0 = b[k - 1].v[1], y1 = b[k].v[1];
        maxAbs = std::max(maxAbs, std::abs(y1));
        if (b[k].t > b.back().t - T) lastAmp = std::max(lastAmp, std::abs(y1));
        if (y0 < 0 && y1 >= 0) up.push_back(b[k - 1].t + (b[k].t - b[k - 1].t) * (-y0) / (y1 - y0));
    }
    REQUIRE(up.size() >= 5);
    const double period = (up.back() - up.front()) / double(up.size() - 1);
    std::printf("heave_box: period %.4f s (theory %.4f, %.2f%%), max |y| %.5f, amplitude in the last period %.5f (start 0.05)\n",
                period, T, 100 * (period / T - 1), maxAbs, lastAmp);
    CHECK(std::abs(period / T - 1) < 0.03);
    CHECK(maxAbs < 0.0505);
    CHECK(lastAmp > 0.048);
}

TEST_CASE("scene cube_attitudes.json: face-down stable at s = 0.1, 0.9, unstable at 0.5", "[bullet][scenes]") {
    const auto rows = runScene("cube_attitudes.json");
    const double t01 = closestAxisTilt(rows.at("cube_s01").back());
    const double t05 = closestAxisTilt(rows.at("cube_s05").back());
    const double t09 = closestAxisTilt(rows.at("cube_s09").back());
    std::printf("cube_attitudes: tilt s=0.1 %.3f deg, s=0.5 %.2f deg, s=0.9 %.3f deg\n", t01, t05, t09);
    CHECK(t01 < 1.0);
    CHECK(t05 > 20.0);
    CHECK(t09 < 1.0);
}

TEST_CASE("scene ballast_boat.json: a ballasted shell hull floats upright at its draft", "[bullet][scenes]") {
    const auto rows = runScene("ballast_boat.json");
    const auto& h = rows.at("hull");
    // Hull 3 × 0.6 × 1, total mass 200 + 150 kg: displaced 0.35 m³ over a 3 × 1 waterplane: draft 0.11667 m,
    // bottom at −draft, so the mesh centre at 0.3 − draft. Upright: the ballast below the centre makes the upright attitude stable.
    const double mass = h.back().v[17];
    const double yTheory = 0.3 - mass / 1000.0 / 3.0;
    const auto [y, range] = meanRange(h, 1, h.back().t - 2.0);
    const double tilt = yAxisTilt(h.back());
    std::printf("ballast_boat: mass %.3f kg, mean centre y %.5f (theory %.5f), range %.2e, tilt %.3f deg (start 10)\n",
                mass, y, yTheory, range, tilt);
    CHECK(mass == Approx(350.0).epsilon(1e-9));
    CHECK(std::abs(y - yTheory) < 0.005 * 0.6);
    CHECK(tilt < 1.0);
}

namespace {
/// Volumes (density 1000, so mass / 1000) of the default-resolution sphere (R = 1) and cylinder (R = 0.5,
/// h = 2) as the runner builds and integrates them, m³.
std::map<std::string, double> defaultPrimitiveVolumes() {
    // The scene default (docs/scene-format.md): the runner's mesh at that resolution, measured through the
    // runner itself (mass = density × the volume the library integrates) at t = 0.
    const auto scene = buoyancy::cli::parseScene(
        R"({"bodies": [{"shape": {"type": "sphere", "radius": 1}, "density": 1000}]})", "default.json", ".");
    const int res = scene.bodies.at(0).shape.resolution;
    std::printf("default primitive resolution: %d\n", res);
    const auto dir = std::filesystem::temp_directory_path() / ("buoyancy_scene_test_resolution_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    {
        std::ofstream f(dir / "prims.json");
        f << R"({"bodies": [{"name": "sphere", "shape": {"type": "sphere", "radius": 1}, "density": 1000,
                             "position": [0, 5, 0]},
                            {"name": "cylinder", "shape": {"type": "cylinder", "radius": 0.5, "height": 2},
                             "density": 1000, "position": [5, 5, 0]}]})";
    }
    REQUIRE(buoyancy::cli::runSceneCommand((dir / "prims.json").string(), (dir / "out").string(), 0.0) == 0);
    std::ifstream in(dir / "out" / "trajectory.csv");
    std::string line;
    std::getline(in, line);
    std::map<std::string, double> volume;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string cell, name;
        std::vector<double> v;
        std::getline(ss, cell, ',');
        std::getline(ss, name, ',');
        while (std::getline(ss, cell, ',')) v.push_back(std::stod(cell));
        volume[name] = v.at(17) / 1000.0;
    }
    return volume;
}
}  // namespace

TEST_CASE("default primitive resolution: cylinder volume within 0.1 % of the analytic shape", "[bullet][scenes]") {
    const auto volume = defaultPrimitiveVolumes();
    const double cylinder = M_PI * 0.25 * 2;  // π R² h
    std::printf("default cylinder volume %.6f vs %.6f (%.4f%%)\n", volume.at("cylinder"), cylinder,
                100 * (volume.at("cylinder") / cylinder - 1));
    CHECK(std::abs(volume.at("cylinder") / cylinder - 1) < 1e-3);
}

// docs/scene-format.md promises the default resolution (128 segments, 65 rings) keeps a primitive within
// 0.1 % of the analytic volume.
TEST_CASE("default sphere volume within 0.1 % of 4/3 pi R^3", "[bullet][scenes]") {
    const auto volume = defaultPrimitiveVolumes();
    const double sphere = 4.0 / 3.0 * M_PI;  // R = 1
    std::printf("default sphere volume %.6f vs %.6f (%.4f%%)\n", volume.at("sphere"), sphere,
                100 * (volume.at("sphere") / sphere - 1));
    CHECK(std::abs(volume.at("sphere") / sphere - 1) < 1e-3);
}

TEST_CASE("substeps per frame 1, 4, 8 give the same dynamic motion", "[bullet][scenes][substeps]") {
    // A tumbling cylinder dropped into the water with drag and added mass on: impulses per substep make the
    // motion depend only on the substeps, not on how frames group them (design.md 3).
    using namespace buoyancy_test;
    btBuoyancySettings bs;
    bs.method = btBuoyancyMethod::ExactMesh;
    auto shape = btBuoyancyShape::create(buoyancy::makeCylinderMesh(0.3, 1.2, 24), bs);
    std::vector<std::vector<btTransform>> poses;
    for (int n : {1, 4, 8}) {
        BulletTestWorld w;
        btBuoyantBodySettings body;
        body.density = 700;
        w.add(shape, body, makePose(btVector3(0, 1.5, 0), btVector3(1, 0, 0.4), 35), bs);
        w.rigid(0)->setLinearVelocity(btVector3(1, -2, 0.5));
        w.rigid(0)->setAngularVelocity(btVector3(3, 1, -2));
        std::vector<btTransform> p;
        for (int k = 0; k < 240 * 6 / 8; ++k) {  // 6 s, compared every 8 substeps
            w.step(8 / n, n, 1.0 / 240.0);
            p.push_back(w.body(0).getMeshWorldTransform());
        }
        poses.push_back(p);
    }
    double worstPos = 0, worstRot = 0, minY = 1e9;
    for (std::size_t k = 0; k < poses[0].size(); ++k) {
        minY = std::min(minY, double(poses[0][k].getOrigin().y()));
        for (int j = 1; j < 3; ++j) {
            worstPos = std::max(worstPos, double((poses[j][k].getOrigin() - poses[0][k].getOrigin()).length()));
            for (int a = 0; a < 3; ++a)
                worstRot = std::max(worstRot, double((poses[j][k].getBasis()[a] - poses[0][k].getBasis()[a]).length()));
        }
    }
    std::printf("substeps 1/4/8 over 6 s of a tumbling drop (min y %.3f): worst position difference %.3g m, "
                "rotation %.3g\n",
                minY, worstPos, worstRot);
    CHECK(minY < 0);  // it did enter the water
    CHECK(worstPos < 1e-6);
    CHECK(worstRot < 1e-6);
}
