// The paper's Fig. 15 (a ball whose density map changes over time) and Fig. 16 (a plush toy soaking up
// water), from the shipped scene files, against physical expectations:
// - a floating sphere's stable attitude puts its centre of mass straight below its centre (the centre of
//   buoyancy of a sphere is always below its centre), so the heavy spot of the map points down and the ball
//   turns with the spot as the map turns; a map that does not turn leaves the ball still;
// - the mass properties are recomputed only when the map changes (one per update interval);
// - the plush toy only gains water while it floats, its mass is dry + ρ_w × water, it floats at
//   Archimedes' draft (submerged volume = mass / ρ_w), so its draft grows, and it goes under once saturated
//   because its dry mass exceeds ρ_w × its material volume (design.md 5).
#include <catch2/catch.hpp>

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include "scene/SceneErrors.h"
#include "cli/RunCommand.h"
#include "scene/SceneFile.h"
#include <BulletBuoyancy/bullet/btTimeVaryingMassAction.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <btBulletDynamicsCommon.h>

#include <Eigen/Geometry>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <unistd.h>  // getpid: a private temporary folder per test process

using namespace buoyancy;

namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

std::vector<std::map<std::string, double>> readCsv(const fs::path& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    {
        std::stringstream ss(line);
        std::string c;
        while (std::getline(ss, c, ',')) header.push_back(c);
    }
    std::vector<std::map<std::string, double>> rows;
    while (std::getline(in, line)) {
        std::stringstream ss(line);
        std::string c;
        std::map<std::string, double> row;
        for (std::size_t k = 0; std::getline(ss, c, ','); ++k)
            if (k != 1 && k < header.size()) row[header[k]] = std::stod(c);
        rows.push_back(row);
    }
    return rows;
}

/// Run a shipped scene (optionally with its JSON edited by `edit`) for `duration` s; rows of the CSV.
std::vector<std::map<std::string, double>> runShipped(const std::string& name, double duration,
                                                      const std::function<std::string(std::string)>& edit = {}) {
    const fs::path src = fs::path(BUOYANCY_SOURCE_DIR) / "bullet_examples" / "scenes" / name;
    const fs::path dir = fs::temp_directory_path() / ("buoyancy_fig_" + std::to_string(::getpid()) + "_" + name);
    fs::create_directories(dir);
    std::ifstream in(src);
    std::stringstream text;
    text << in.rdbuf();
    std::string json = text.str();
    // Keep relative mesh paths working from the temporary folder.
    const std::string models = "../models/";
    for (std::size_t p = json.find(models); p != std::string::npos; p = json.find(models, p + 1))
        json.replace(p, models.size(), (fs::path(BUOYANCY_SOURCE_DIR) / "bullet_examples" / "models").string() + "/");
    if (edit) json = edit(json);
    { std::ofstream(dir / "scene.json") << json; }
    REQUIRE(cli::runSceneCommand((dir / "scene.json").string(), (dir / "out").string(), duration) == 0);
    auto rows = readCsv(dir / "out" / "trajectory.csv");
    std::error_code ec;
    fs::remove_all(dir, ec);
    return rows;
}

/// Angle between the heavy spot's world direction and world down, degrees. The spot's body direction at time
/// t is Rz(k·Δ·ω)·(0, −1, 0) with k = floor(t/Δ) (the scene's map: Δ = 0.25 s, ω = 6 °/s about z).
double spotTiltDegrees(const std::map<std::string, double>& r, double degreesPerSecond) {
    const double t = r.at("t");
    const double spot = std::floor(t / 0.25 + 1e-9) * 0.25 * degreesPerSecond * kPi / 180;
    const Eigen::Vector3d body = Eigen::AngleAxisd(spot, Eigen::Vector3d::UnitZ()) * Eigen::Vector3d(0, -1, 0);
    const Eigen::Quaterniond q(r.at("qw"), r.at("qx"), r.at("qy"), r.at("qz"));
    return std::acos(std::clamp((q * body).dot(Eigen::Vector3d(0, -1, 0)), -1.0, 1.0)) * 180 / kPi;
}

}  // namespace

TEST_CASE("Fig. 15 ball: the heavy spot stays down as the density map turns, a still map leaves it still", "[graph][cli]") {
    const auto rows = runShipped("variable_density_ball.json", 20);
    double worst = 0, turned = 0;
    for (const auto& r : rows) {
        if (r.at("t") < 3) continue;  // the first roll from the initial bob
        worst = std::max(worst, spotTiltDegrees(r, 6));
        CHECK(r.at("mass") == Approx(200.0));  // the map moves mass around, never changes it
    }
    const auto& last = rows.back();
    const Eigen::Quaterniond q(last.at("qw"), last.at("qx"), last.at("qy"), last.at("qz"));
    turned = 2 * std::atan2(q.z(), q.w()) * 180 / kPi;  // rotation about z (the only axis it turns about)
    INFO("worst tilt of the heavy spot " << worst << " deg; turned " << turned << " deg by t = " << last.at("t"));
    CHECK(worst < 5.0);
    // By t = 20 s the spot has turned 120° about +z in the body, so the ball turned −120° to keep it down.
    CHECK(turned == Approx(-120.0).margin(5.0));
    // The centre of mass is below the centre of the sphere (the mesh origin) and off it by the spot's pull.
    CHECK(last.at("cy") < last.at("y") - 0.05);

    // Control: the same map without rotation keeps the ball where it is.
    const auto still = runShipped("variable_density_ball.json", 10, [](std::string j) {
        const std::string key = "\"degrees_per_second\": 6";
        j.replace(j.find(key), key.size(), "\"degrees_per_second\": 0");
        return j;
    });
    for (const auto& r : still) CHECK(spotTiltDegrees(r, 0) < 1.0);
}

TEST_CASE("time-varying mass: recomputed only when the map changes, mesh does not jump", "[graph][bullet]") {
    btDefaultCollisionConfiguration config;
    btCollisionDispatcher dispatcher(&config);
    btDbvtBroadphase broadphase;
    btSequentialImpulseConstraintSolver solver;
    btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &config);
    world.setGravity(btVector3(0, btScalar(-9.81), 0));
    btFlatWaterSurface surface(0.0);
    btBuoyancyWorld water(&surface, 1000.0, 9.81);
    auto shape = btBuoyancyShape::create(makeSphereMesh(0.5, 32, 17));
    btBuoyantBodySettings s;
    s.mass = 150;
    btTransform pose;
    pose.setIdentity();
    btBuoyantBody body(shape, s, pose);
    world.addRigidBody(body.getRigidBody());
    btBuoyancyAction action(body, &water);
    world.addAction(&action);
    // Map: all the mass in the lower half until t = 1 s, then in the upper half (a weight moved up).
    int calls = 0;
    btTimeVaryingMassAction varying(
        body, &water, s, [](double t) { return std::int64_t(t >= 1.0); },
        [&calls](double t, const Eigen::Vector3d& p) {
            ++calls;
            return (t < 1.0) == (p.y() < 0) ? 1.0 : 0.0;
        });
    world.addAction(&varying);
    CHECK(varying.getRecomputeCount() == 1);
    // A uniform hemispherical shell of radius R has its centre R/2 from the flat side (textbook).
    CHECK(body.getMassProperties().centre.y() == Approx(-0.25).margin(0.01));
    const int perMap = calls;
    for (int i = 0; i < 30; ++i) world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));  // 0.5 s
    CHECK(varying.getRecomputeCount() == 1);
    CHECK(calls == perMap);  // not one more evaluation while the map stays the same
    for (int i = 0; i < 60; ++i) {
        const btTransform a = body.getMeshWorldTransform();
        const long long before = varying.getRecomputeCount();
        world.stepSimulation(btScalar(1.0 / 60), 4, btScalar(1.0 / 240));
        if (varying.getRecomputeCount() != before) {
            // The recompute moved the COM by R/2 without moving the mesh (in-place update): the mesh moves only
            // by one frame of motion.
            CHECK((body.getMeshWorldTransform().getOrigin() - a.getOrigin()).length() < 0.05);
        }
    }
    CHECK(varying.getRecomputeCount() == 2);
    CHECK(calls == 2 * perMap);
    CHECK(body.getMassProperties().centre.y() == Approx(0.25).margin(0.01));
    CHECK(body.getMass() == Approx(150.0));
    world.removeAction(&varying);
    world.removeAction(&action);
    world.removeRigidBody(body.getRigidBody());
}

TEST_CASE("Fig. 16 plush toy soaks up water, floats at Archimedes' draft deeper and deeper, then goes under",
          "[graph][cli][slow]") {
    const auto rows = runShipped("plush_toy.json", 70);
    const double rho = 1000, dry = 1.7;
    double prevWater = -1, prevSub = 0;
    int floatingRows = 0;
    bool sank = false;
    for (const auto& r : rows) {
        const double t = r.at("t"), w = r.at("water_volume");
        CHECK(w >= prevWater);  // it only soaks up (no drainage out of a floating plush in calm water)
        prevWater = w;
        CHECK(r.at("mass") == Approx(dry + rho * w).epsilon(1e-9));
        if (t > 5 && r.at("submerged_volume") < 0.8 * 0.0122) {
            // Floating, sinking slowly (mm/s): Archimedes, submerged volume = mass / ρ_w. (Bullet's stored vy of a
            // body at rest is g·dt, so the CSV velocity cannot say "slow"; the draft can.)
            ++floatingRows;
            CHECK(r.at("submerged_volume") == Approx(r.at("mass") / rho).epsilon(0.03));
            CHECK(r.at("submerged_volume") >= prevSub - 1e-6);  // the draft only grows
            prevSub = r.at("submerged_volume");
        }
        if (r.at("y") < -0.5) sank = true;
    }
    CHECK(floatingRows > 20);
    CHECK(rows.back().at("water_volume") > 0.9 * 0.9 * 0.0122);  // nearly saturated (capacity 0.9 V)
    CHECK(sank);  // dry mass 1.7 kg > ρ_w V_material = 1000 × 0.1 × 0.0122 = 1.22 kg
}

TEST_CASE("scene keys density_map, water_inertia and permeability.filter: errors name the key", "[graph][cli]") {
    auto error = [](const std::string& body) {
        try {
            cli::parseScene(R"({"bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.5}, )" + body + "}]}",
                            "s.json", ".");
        } catch (const cli::UsageError& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    const std::string map = R"("density_map": {"spots": [{"direction": [0, -1, 0], "value": 5}]})";
    CHECK(error(R"("mass": 100, )" + map) == "no error");
    CHECK_THAT(error(R"("density": 100, )" + map), Catch::Contains("bodies[0].density_map") && Catch::Contains("\"mass\""));
    CHECK_THAT(error(R"("mass": 100, "mass_model": "solid", )" + map), Catch::Contains("bodies[0].density_map"));
    CHECK_THAT(error(R"("mass": 100, "density_map": {"base": 0})"), Catch::Contains("density_map") && Catch::Contains("zero everywhere"));
    CHECK_THAT(error(R"("mass": 100, "density_map": {"spots": [{"direction": [0, 0, 0], "value": 1}]})"),
               Catch::Contains("density_map.spots[0].direction"));
    CHECK_THAT(error(R"("mass": 100, "density_map": {"spots": [{"direction": [0, 1, 0], "value": 1, "angle": 0}]})"),
               Catch::Contains("density_map.spots[0].angle"));
    CHECK_THAT(error(R"("mass": 100, "density_map": {"spots": [{"direction": [0, 1, 0], "value": -1}]})"),
               Catch::Contains("density_map.spots[0].value"));
    CHECK_THAT(error(R"("mass": 100, "density_map": {"rotation": {"axis": [0, 0, 0]}})"), Catch::Contains("density_map.rotation.axis"));
    CHECK_THAT(error(R"("mass": 100, "density_map": {"update_interval": 0})"), Catch::Contains("density_map.update_interval"));
    CHECK_THAT(error(R"("mass": 100, "density_map": {"colour": 1})"), Catch::Contains("density_map.colour"));
    const std::string graph = R"("mass": 100, "water_graph": {"nodes": [{"name": "n", "capacity": 0.1}])";
    CHECK_THAT(error(graph + R"(, "water_inertia": "blob"})"), Catch::Contains("water_graph.water_inertia"));
    CHECK(error(graph + R"(, "water_inertia": "points"})") == "no error");
    CHECK_THAT(error(graph + R"(}, "permeability": {"regions": [], "filter": "nearest"})"),
               Catch::Contains("permeability.filter") && Catch::Contains("texture"));
    const cli::Scene ok = cli::parseScene(
        R"({"bodies": [{"name": "b", "shape": {"type": "sphere", "radius": 0.5}, "mass": 100, )" + map + "}]}", "s.json", ".");
    REQUIRE(ok.bodies[0].flooding.densityMap.enabled);
    CHECK(ok.bodies[0].body.massModel == btBuoyantMassModel::DensityMap);
    // The map: σ = value inside the 45° cone around −y, base outside; it does not change without rotation.
    const cli::SceneDensityMap& m = ok.bodies[0].flooding.densityMap;
    CHECK(m.density(0, Eigen::Vector3d(0, -1, 0), Eigen::Vector3d::Zero()) == 5.0);
    CHECK(m.density(0, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero()) == 1.0);
    CHECK(m.version(0) == m.version(100));
}
