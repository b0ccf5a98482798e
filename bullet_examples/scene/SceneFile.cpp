#include "scene/SceneFile.h"

#include "scene/SceneErrors.h"
#include "scene/SceneJsonReader.h"

#include <nlohmann/json.hpp>

#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <stdexcept>

namespace buoyancy::cli {

namespace {

using json = nlohmann::json;

/// The scene reader: SceneJsonReader whose failures are usage errors naming the file (exit 2).
class Reader : public SceneJsonReader {
public:
    explicit Reader(const std::string& source)
        : SceneJsonReader([source](const std::string& key, const std::string& what) {
              throw UsageError(source + ": " + key + ": " + what);
          }) {}
    /// A reader with its own fail function (which must throw).
    explicit Reader(SceneFailFn fail) : SceneJsonReader(std::move(fail)) {}
};

constexpr double kBig = 1e6;  // bounds for lengths, m, and speeds

SceneShape readShape(const Reader& r, const json& j, const std::string& key, const std::string& directory) {
    r.requireObject(j, key);
    if (!j.contains("type")) r.fail(key + ".type", "missing (box, sphere, cylinder or mesh)");
    SceneShape s;
    s.type = r.string(j["type"], key + ".type");
    if (s.type == "box") {
        r.allowKeys(j, key, {"type", "size"});
        if (!j.contains("size")) r.fail(key + ".size", "missing");
        s.size = r.vec3(j["size"], key + ".size", 0.0, kBig, true);
    } else if (s.type == "sphere" || s.type == "cylinder") {
        if (s.type == "sphere") r.allowKeys(j, key, {"type", "radius", "resolution"});
        else r.allowKeys(j, key, {"type", "radius", "height", "resolution"});
        if (!j.contains("radius")) r.fail(key + ".radius", "missing");
        s.radius = r.number(j["radius"], key + ".radius", 0.0, kBig, true);
        if (s.type == "cylinder") {
            if (!j.contains("height")) r.fail(key + ".height", "missing");
            s.height = r.number(j["height"], key + ".height", 0.0, kBig, true);
        }
        if (j.contains("resolution")) s.resolution = r.integer(j["resolution"], key + ".resolution", 8, 1024);
    } else if (s.type == "mesh") {
        r.allowKeys(j, key, {"type", "file", "scale", "repair", "convex_hull", "open_top"});
        if (!j.contains("file")) r.fail(key + ".file", "missing");
        const std::string file = r.string(j["file"], key + ".file");
        std::filesystem::path p(file);
        if (p.is_relative()) p = std::filesystem::path(directory) / p;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(p, ec)) r.fail(key + ".file", "no such file: " + p.string());
        s.file = p.string();
        if (j.contains("scale")) s.scale = r.number(j["scale"], key + ".scale", 0.0, kBig, true);
        if (j.contains("repair")) s.repair = r.boolean(j["repair"], key + ".repair");
        if (j.contains("convex_hull")) s.convexHull = r.boolean(j["convex_hull"], key + ".convex_hull");
        if (j.contains("open_top")) s.openTop = r.boolean(j["open_top"], key + ".open_top");
        if (s.openTop && s.convexHull)
            r.fail(key + ".open_top", "cannot be used with \"convex_hull\": a hull has no opening");
    } else {
        r.fail(key + ".type", "unknown shape type \"" + s.type + "\" (box, sphere, cylinder or mesh)");
    }
    return s;
}

btBuoyancySettings readBuoyancy(const Reader& r, const json& j, const std::string& key) {
    r.requireObject(j, key);
    r.allowKeys(j, key, {"method", "texture", "drag_coefficient", "skin_friction", "linear_damping", "radiation_damping", "added_mass",
                         "added_mass_coefficient", "added_mass_waterplane_coefficient", "water_acceleration", "error_budget", "drag_clusters", "water_patch_nodes",
                         "water_patch_nodes_per_wavelength", "hydrostatics_interval",
                         "hydrostatics_reuse_tolerance"});
    btBuoyancySettings b;
    if (j.contains("method")) {
        const std::string m = r.string(j["method"], key + ".method");
        try {
            b.method = btBuoyancyMethodFromName(m);
        } catch (const std::invalid_argument& e) {
            r.fail(key + ".method", e.what());
        }
    }
    if (j.contains("texture")) b.textureSize = r.integer(j["texture"], key + ".texture", 1, 16384);
    // Automatic level of detail and the level-of-detail knobs (btBuoyancySettings).
    if (j.contains("error_budget")) b.errorBudget = r.number(j["error_budget"], key + ".error_budget", 0, 100);
    if (j.contains("drag_clusters")) b.dragClusters = r.integer(j["drag_clusters"], key + ".drag_clusters", 0, 1000000);
    if (j.contains("water_patch_nodes")) {
        b.waterPatchNodes = r.integer(j["water_patch_nodes"], key + ".water_patch_nodes", 0, 64);
        if (b.waterPatchNodes != 0 && b.waterPatchNodes < 5)
            r.fail(key + ".water_patch_nodes", "must be 0 (exact wave queries) or in 5..64");
    }
    if (j.contains("water_patch_nodes_per_wavelength"))
        b.waterPatchNodesPerWavelength = r.number(j["water_patch_nodes_per_wavelength"],
                                                  key + ".water_patch_nodes_per_wavelength", 0, 1000);
    if (j.contains("hydrostatics_interval"))
        b.hydrostaticsInterval = r.integer(j["hydrostatics_interval"], key + ".hydrostatics_interval", 0, 16);
    if (j.contains("hydrostatics_reuse_tolerance"))
        b.hydrostaticsReuseTolerance =
            r.number(j["hydrostatics_reuse_tolerance"], key + ".hydrostatics_reuse_tolerance", 0, 1, true);
    if (j.contains("drag_coefficient")) b.dragCoefficient = r.number(j["drag_coefficient"], key + ".drag_coefficient", 0, 100);
    if (j.contains("skin_friction")) b.skinFriction = r.number(j["skin_friction"], key + ".skin_friction", 0, 100);
    if (j.contains("linear_damping")) b.linearDamping = r.number(j["linear_damping"], key + ".linear_damping", 0, 100);
    if (j.contains("radiation_damping"))
        b.radiationDamping = r.number(j["radiation_damping"], key + ".radiation_damping", 0, 10);
    if (j.contains("added_mass")) b.addedMass = r.boolean(j["added_mass"], key + ".added_mass");
    if (j.contains("added_mass_coefficient"))
        b.addedMassCoefficient = r.number(j["added_mass_coefficient"], key + ".added_mass_coefficient", 0, 100);
    if (j.contains("added_mass_waterplane_coefficient"))
        b.addedMassWaterplaneCoefficient = r.number(j["added_mass_waterplane_coefficient"],
                                                    key + ".added_mass_waterplane_coefficient", 0, 100);
    if (j.contains("water_acceleration")) {
        const std::string m = r.string(j["water_acceleration"], key + ".water_acceleration");
        if (m == "none") b.waterAcceleration = btWaterAccelerationForce::None;
        else if (m == "added-mass") b.waterAcceleration = btWaterAccelerationForce::AddedMass;
        else if (m == "added-mass-and-froude-krylov") b.waterAcceleration = btWaterAccelerationForce::AddedMassAndFroudeKrylov;
        else
            r.fail(key + ".water_acceleration",
                   "unknown value \"" + m + "\" (use \"none\", \"added-mass\" or \"added-mass-and-froude-krylov\")");
    }
    return b;
}

/// Bound of the hydrodynamic coefficients: a large ship's added mass is ~1e8 kg, its inertia's ~1e12 kg·m².
constexpr double kHydroBig = 1e15;

/// A 6×6 matrix as 6 numbers (its diagonal) or 36 (row-major), each finite and within ±kHydroBig.
std::array<double, 36> readMatrix6(const Reader& r, const json& j, const std::string& key) {
    if (!j.is_array() || (j.size() != 6 && j.size() != 36))
        r.fail(key, "expected an array of 6 numbers (the diagonal) or 36 (row-major 6x6)");
    std::array<double, 36> m{};
    for (std::size_t i = 0; i < j.size(); ++i) {
        const double x = r.number(j[i], key + "[" + std::to_string(i) + "]", -kHydroBig, kHydroBig);
        if (j.size() == 6) m[7 * i] = x;
        else m[i] = x;
    }
    return m;
}

btMarineHydrodynamics readHydrodynamics(const Reader& r, const json& j, const std::string& key) {
    r.requireObject(j, key);
    r.allowKeys(j, key, {"added_mass", "linear_damping", "quadratic_damping", "origin", "use_water_velocity",
                         "scale_by_submerged_fraction"});
    btMarineHydrodynamics h;
    h.enabled = true;
    if (j.contains("added_mass")) h.addedMass = readMatrix6(r, j["added_mass"], key + ".added_mass");
    if (j.contains("linear_damping")) h.linearDamping = readMatrix6(r, j["linear_damping"], key + ".linear_damping");
    if (j.contains("quadratic_damping")) {
        const json& q = j["quadratic_damping"];
        if (!q.is_array() || q.size() != 6) r.fail(key + ".quadratic_damping", "expected an array of 6 numbers");
        for (std::size_t i = 0; i < 6; ++i)
            h.quadraticDamping[i] = r.number(q[i], key + ".quadratic_damping[" + std::to_string(i) + "]", 0.0, kHydroBig);
    }
    if (j.contains("origin")) {
        const Eigen::Vector3d o = r.vec3(j["origin"], key + ".origin", -kBig, kBig);
        h.referenceFrame.setOrigin(btVector3(btScalar(o.x()), btScalar(o.y()), btScalar(o.z())));
    }
    if (j.contains("use_water_velocity")) h.useWaterVelocity = r.boolean(j["use_water_velocity"], key + ".use_water_velocity");
    if (j.contains("scale_by_submerged_fraction"))
        h.scaleBySubmergedFraction = r.boolean(j["scale_by_submerged_fraction"], key + ".scale_by_submerged_fraction");
    try {
        h.validate();
    } catch (const std::invalid_argument& e) {
        r.fail(key, e.what());
    }
    return h;
}

SceneBody readBody(const Reader& r, const json& j, const std::string& key, std::size_t index,
                   const std::string& directory) {
    r.requireObject(j, key);
    r.allowKeys(j, key, {"name", "shape", "density", "mass", "mass_model", "thickness", "position", "rotation",
                         "linear_velocity", "angular_velocity", "buoyancy", "ballast", "fixed", "collision",
                         "water_graph", "permeability", "density_map", "hydrodynamics"});
    SceneBody b;
    b.name = j.contains("name") ? r.string(j["name"], key + ".name") : "body" + std::to_string(index);
    if (b.name.empty()) r.fail(key + ".name", "must not be empty");
    if (b.name.find_first_of(",\"\n\r") != std::string::npos) r.fail(key + ".name", "must not contain , \" or newlines");
    if (!j.contains("shape")) r.fail(key + ".shape", "missing");
    b.shape = readShape(r, j["shape"], key + ".shape", directory);

    if (j.contains("fixed")) b.body.fixed = r.boolean(j["fixed"], key + ".fixed");
    const bool hasDensity = j.contains("density"), hasMass = j.contains("mass");
    if (hasDensity == hasMass && !b.body.fixed)
        r.fail(key, hasDensity ? "give exactly one of \"density\" and \"mass\", not both"
                               : "missing \"density\" or \"mass\"");
    if (hasDensity && hasMass) r.fail(key, "give at most one of \"density\" and \"mass\"");
    if (hasDensity) b.body.density = r.number(j["density"], key + ".density", 0.0, 1e6, true);
    if (hasMass) {
        b.body.mass = r.number(j["mass"], key + ".mass", 0.0, 1e12, true);
    }
    if (j.contains("mass_model")) {
        const std::string mm = r.string(j["mass_model"], key + ".mass_model");
        if (mm == "solid") b.body.massModel = btBuoyantMassModel::Solid;
        else if (mm == "shell") b.body.massModel = btBuoyantMassModel::Shell;
        else r.fail(key + ".mass_model", "unknown value \"" + mm + "\" (solid or shell)");
    }
    if (j.contains("thickness")) {
        if (b.body.massModel != btBuoyantMassModel::Shell) r.fail(key + ".thickness", "only with \"mass_model\": \"shell\"");
        b.body.shellThickness = r.number(j["thickness"], key + ".thickness", 0.0, kBig, true);
    } else if (b.body.massModel == btBuoyantMassModel::Shell) {
        r.fail(key + ".thickness", "missing (required with \"mass_model\": \"shell\")");
    }
    if (j.contains("position")) b.position = r.vec3(j["position"], key + ".position", -kBig, kBig);
    if (j.contains("rotation")) {
        const json& rot = j["rotation"];
        const std::string rk = key + ".rotation";
        r.requireObject(rot, rk);
        r.allowKeys(rot, rk, {"axis", "degrees"});
        if (rot.contains("axis")) b.axis = r.vec3(rot["axis"], rk + ".axis", -kBig, kBig);
        if (!(b.axis.norm() > 1e-12)) r.fail(rk + ".axis", "zero axis");
        b.axis.normalize();
        if (rot.contains("degrees")) b.degrees = r.number(rot["degrees"], rk + ".degrees", -1e6, 1e6);
    }
    if (j.contains("linear_velocity")) b.linearVelocity = r.vec3(j["linear_velocity"], key + ".linear_velocity", -kBig, kBig);
    if (j.contains("angular_velocity"))
        b.angularVelocity = r.vec3(j["angular_velocity"], key + ".angular_velocity", -kBig, kBig);
    if (j.contains("buoyancy")) b.buoyancy = readBuoyancy(r, j["buoyancy"], key + ".buoyancy");
    if (j.contains("hydrodynamics")) {
        b.hydrodynamics = readHydrodynamics(r, j["hydrodynamics"], key + ".hydrodynamics");
        // Its added-mass matrix replaces the scalar added mass: off unless asked for, and then a contradiction.
        if (j.contains("buoyancy") && j["buoyancy"].contains("added_mass") && b.buoyancy.addedMass)
            r.fail(key + ".hydrodynamics", "replaces buoyancy.added_mass: remove that key or set it to false");
        b.buoyancy.addedMass = false;
    }
    if (j.contains("ballast")) {
        const json& bl = j["ballast"];
        if (!bl.is_array()) r.fail(key + ".ballast", "expected an array of {\"position\", \"mass\"}");
        for (std::size_t i = 0; i < bl.size(); ++i) {
            const std::string bk = key + ".ballast[" + std::to_string(i) + "]";
            r.requireObject(bl[i], bk);
            r.allowKeys(bl[i], bk, {"position", "mass"});
            if (!bl[i].contains("position")) r.fail(bk + ".position", "missing");
            if (!bl[i].contains("mass")) r.fail(bk + ".mass", "missing");
            btBuoyantBallast ballast;
            ballast.position = r.vec3(bl[i]["position"], bk + ".position", -kBig, kBig);
            ballast.mass = r.number(bl[i]["mass"], bk + ".mass", 0.0, 1e12, true);
            b.body.ballast.push_back(ballast);
        }
    }
    if (j.contains("collision")) {
        const std::string c = r.string(j["collision"], key + ".collision");
        if (c == "hull") b.body.collision = btBuoyantCollision::ConvexHull;
        else if (c == "mesh") b.body.collision = btBuoyantCollision::TriangleMesh;
        else if (c == "none") b.body.collision = btBuoyantCollision::None;
        else r.fail(key + ".collision", "unknown value \"" + c + "\" (hull, mesh or none)");
    }
    b.flooding = readSceneFlooding(j, key, directory, [&](const std::string& k, const std::string& w) { r.fail(k, w); });
    if (b.shape.openTop && !b.flooding.enabled) {
        // Water coming in through an open top needs somewhere to go: an automatic graph of the closed hull.
        b.flooding.enabled = true;
        b.flooding.automatic = true;
    }
    if (b.flooding.enabled && b.body.fixed) r.fail(key + ".water_graph", "a fixed body cannot hold water");
    if (b.flooding.densityMap.enabled) {  // paper Fig. 15 (SceneGraph.h: SceneDensityMap)
        if (b.body.fixed) r.fail(key + ".density_map", "a fixed body has no mass to distribute");
        if (!hasMass) r.fail(key + ".density_map", "needs \"mass\" (the total dry mass the map distributes), not \"density\"");
        if (j.contains("mass_model")) r.fail(key + ".density_map", "give either \"mass_model\" or \"density_map\"");
        b.body.massModel = btBuoyantMassModel::DensityMap;
        b.body.arealDensity = [](const Eigen::Vector3d&) { return 1.0; };  // replaced by the map when the body is built
    }
    return b;
}

// ---- The "water" block (keys and defaults in docs/scene-format.md) ----

/// [a, b]: two numbers in [lo, hi].
Eigen::Vector2d vec2(const Reader& r, const json& j, const std::string& key, double lo, double hi) {
    if (!j.is_array() || j.size() != 2) r.fail(key, "expected an array of 2 numbers");
    return Eigen::Vector2d(r.number(j[0], key + "[0]", lo, hi), r.number(j[1], key + "[1]", lo, hi));
}

/// A non-zero horizontal direction [dx, dz].
Eigen::Vector2d direction2(const Reader& r, const json& j, const std::string& key) {
    const Eigen::Vector2d d = vec2(r, j, key, -kBig, kBig);
    if (!(d.norm() > 0)) r.fail(key, "must not be [0, 0]");
    return d.normalized();
}

/// Height grid CSV: one row per z sample, one column per x sample, comma-separated numbers; empty lines
/// and lines starting with '#' are skipped; every row must have the same number of values.
void readHeightCsv(const Reader& r, const std::string& path, const std::string& key, SceneWater& w) {
    std::error_code ec;  // a directory opens as a stream but fails on the first read
    if (!std::filesystem::is_regular_file(path, ec)) r.fail(key, "cannot read " + path + " (not a file)");
    std::ifstream in(path);
    if (!in) r.fail(key, "cannot read " + path);
    std::string line;
    int row = 0, lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        std::stringstream ls(line);
        std::string cell;
        int cols = 0;
        while (std::getline(ls, cell, ',')) {
            char* end = nullptr;
            const double v = std::strtod(cell.c_str(), &end);
            while (end && (*end == ' ' || *end == '\t' || *end == '\r')) ++end;
            if (end == cell.c_str() || (end && *end != '\0') || !std::isfinite(v))
                r.fail(key, path + " line " + std::to_string(lineNo) + ": \"" + cell + "\" is not a finite number");
            w.gridHeights.push_back(v);
            ++cols;
        }
        if (row == 0) w.gridNx = cols;
        else if (cols != w.gridNx)
            r.fail(key, path + " line " + std::to_string(lineNo) + ": " + std::to_string(cols) + " values, expected " +
                            std::to_string(w.gridNx) + " like the first row");
        ++row;
    }
    w.gridNz = row;
    if (w.gridNx < 2 || w.gridNz < 2) r.fail(key, path + ": needs at least 2 rows of at least 2 values");
}

/// A "river" water object's own keys into `out` (its level `height`, m, already read): "centreline" (at least 2
/// [x, z] points, upstream first, no point repeating the one before), "width" (m, > 0) and "speed" (the surface speed
/// on the centreline, m/s, ≥ 0), all required. The surface's own checks run too (btRiverSurface).
void readRiver(const Reader& r, const json& w, double height, btRiverSettings& out) {
    if (!w.contains("centreline")) r.fail("water.centreline", "missing (an array of at least 2 [x, z] points, m, upstream first)");
    const json& c = w["centreline"];
    if (!c.is_array() || c.size() < 2)
        r.fail("water.centreline", "expected an array of at least 2 [x, z] points, m, upstream first");
    out.centreline.clear();
    for (std::size_t i = 0; i < c.size(); ++i) {
        const std::string key = "water.centreline[" + std::to_string(i) + "]";
        const Eigen::Vector2d p = vec2(r, c[i], key, -kBig, kBig);
        if (i > 0 && std::hypot(p.x() - out.centreline.back().x, p.y() - out.centreline.back().z) < 1e-6)
            r.fail(key, "repeats centreline[" + std::to_string(i - 1) + "]: consecutive points must be at least 1e-6 m "
                        "apart");
        out.centreline.push_back({p.x(), p.y()});
    }
    if (!w.contains("width")) r.fail("water.width", "missing (the channel's width, m, > 0)");
    out.width = r.number(w["width"], "water.width", 0.0, kBig, true);
    if (!w.contains("speed")) r.fail("water.speed", "missing (the surface speed on the centreline, m/s, >= 0)");
    if (w["speed"].is_number() && w["speed"].get<double>() < 0)
        r.fail("water.speed", "must be >= 0 m/s (the current runs from the first centreline point to the last: "
                              "list the points the other way round to reverse it)");
    out.surfaceSpeed = r.number(w["speed"], "water.speed", 0.0, kBig);
    out.height = height;
    try {  // every field checked by the surface itself too
        btRiverSurface check(out);
    } catch (const std::invalid_argument& e) {
        r.fail("water", e.what());
    }
}

/// Scene::waterFrame from "water.frame" (up, x, origin; each optional) and the scene's gravity: up defaults to
/// −gravity (+y for a zero gravity), x to btWaterFrame::fromUp's choice. Refuses an x not perpendicular to up and an up
/// not antiparallel to a non-zero gravity (1e-6 rad), naming both vectors.
void resolveWaterFrame(const Reader& r, Scene& s) {
    const SceneWater& w = s.water;
    const double g = s.gravity.norm();
    const Eigen::Vector3d origin = w.frameOrigin.value_or(Eigen::Vector3d::Zero());
    const Eigen::Vector3d up = w.frameUp ? *w.frameUp : g > 0 ? Eigen::Vector3d(-s.gravity) : Eigen::Vector3d::UnitY();
    try {
        s.waterFrame = w.frameX ? btWaterFrame(origin, up, *w.frameX) : btWaterFrame::fromUp(up, origin);
    } catch (const std::invalid_argument& e) {
        std::string what = e.what();
        const std::string prefix = "btWaterFrame: ";
        if (what.compare(0, prefix.size(), prefix) == 0) what = what.substr(prefix.size());
        r.fail(w.frameX ? "water.frame.x" : "water.frame.up", what);
    }
    if (g > 0) {
        const double angle = s.waterFrame.angleToGravity(s.gravity);
        if (!(angle <= 1e-6)) {
            char buf[64];
            std::snprintf(buf, sizeof buf, "%.6g", angle);
            r.fail("water.frame.up", btWaterFrame::vectorText(up) + " is not antiparallel to the scene's gravity " +
                                         btWaterFrame::vectorText(s.gravity) + " m/s^2 (" + buf +
                                         " rad apart, 1e-6 allowed): the water is a height field along up = -gravity");
        }
    }
}

/// `refuseType` (optional): returns why a type cannot be used where this water is read ("" to accept it).
void readWater(const Reader& r, const json& w, Scene& s, const std::string& directory,
               const SceneWaterTypeFilter& refuseType = {}) {
    r.requireObject(w, "water");
    SceneWater& out = s.water;
    out.type = w.contains("type") ? r.string(w["type"], "water.type") : "flat";
    const std::string& t = out.type;
    if (refuseType) {
        const std::string why = refuseType(t);
        if (!why.empty()) r.fail("water.type", why);
    }
    if (t == "flat") r.allowKeys(w, "water", {"type", "height", "density", "current", "frame"});
    else if (t == "gerstner") r.allowKeys(w, "water", {"type", "height", "density", "waves", "frame"});
    else if (t == "grid") r.allowKeys(w, "water", {"type", "density", "file", "origin", "spacing", "periodic", "frame"});
    else if (t == "fft")
        r.allowKeys(w, "water", {"type", "height", "density", "resolution", "patch_size", "wind_speed", "wind_direction",
                                 "spectrum", "choppiness", "seed", "frame"});
    else if (t == "interactive")
        r.allowKeys(w, "water",
                    {"type", "height", "density", "size", "centre", "resolution", "wave_speed", "damping", "frame"});
    else if (t == "river")
        r.allowKeys(w, "water", {"type", "height", "density", "centreline", "width", "speed", "frame"});
    else r.fail("water.type", "unknown value \"" + t + "\" (flat, gerstner, grid, fft, interactive or river)");
    if (w.contains("height")) s.waterHeight = r.number(w["height"], "water.height", -kBig, kBig);
    if (w.contains("density")) s.waterDensity = r.number(w["density"], "water.density", 0.0, 1e5, true);
    const double g = s.gravity.norm();  // the waves' dispersion: |g| (9.81 when the scene has none)
    if (w.contains("frame")) {
        const json& f = w["frame"];
        r.requireObject(f, "water.frame");
        r.allowKeys(f, "water.frame", {"up", "x", "origin"});
        if (f.contains("up")) out.frameUp = r.vec3(f["up"], "water.frame.up", -kBig, kBig);
        if (f.contains("x")) out.frameX = r.vec3(f["x"], "water.frame.x", -kBig, kBig);
        if (f.contains("origin")) out.frameOrigin = r.vec3(f["origin"], "water.frame.origin", -kBig, kBig);
        if (out.frameUp && !(out.frameUp->norm() > 0)) r.fail("water.frame.up", "zero vector");
        if (out.frameX && !(out.frameX->norm() > 0)) r.fail("water.frame.x", "zero vector");
    }
    resolveWaterFrame(r, s);

    if (t == "flat") {
        if (w.contains("current")) out.current = vec2(r, w["current"], "water.current", -kBig, kBig);
    } else if (t == "gerstner") {
        if (!w.contains("waves")) r.fail("water.waves", "missing (an array of waves)");
        if (!w["waves"].is_array()) r.fail("water.waves", "expected an array");
        for (std::size_t i = 0; i < w["waves"].size(); ++i) {
            const json& jw = w["waves"][i];
            const std::string key = "water.waves[" + std::to_string(i) + "]";
            r.requireObject(jw, key);
            r.allowKeys(jw, key, {"amplitude", "wavelength", "direction", "steepness", "phase"});
            btGerstnerWave wave;
            if (!jw.contains("amplitude")) r.fail(key + ".amplitude", "missing");
            if (!jw.contains("wavelength")) r.fail(key + ".wavelength", "missing");
            wave.amplitude = r.number(jw["amplitude"], key + ".amplitude", 0.0, kBig);
            wave.wavelength = r.number(jw["wavelength"], key + ".wavelength", 0.0, kBig, true);
            if (jw.contains("direction")) {
                const Eigen::Vector2d d = direction2(r, jw["direction"], key + ".direction");
                wave.directionX = d.x();
                wave.directionZ = d.y();
            }
            wave.steepness = jw.contains("steepness") ? r.number(jw["steepness"], key + ".steepness", 0.0, kBig) : 0.5;
            if (jw.contains("phase")) wave.phase = r.number(jw["phase"], key + ".phase", -kBig, kBig);
            out.waves.push_back(wave);
        }
        try {  // the loop condition Σ Q A k < 1 (and every field) checked by the surface itself
            btGerstnerWaterSurface check(out.waves, s.waterHeight, g > 0 ? g : 9.81);
        } catch (const std::invalid_argument& e) {
            r.fail("water", e.what());
        }
    } else if (t == "grid") {
        if (!w.contains("file")) r.fail("water.file", "missing (a CSV of heights: rows = z, columns = x)");
        std::filesystem::path p(r.string(w["file"], "water.file"));
        if (p.is_relative()) p = std::filesystem::path(directory) / p;
        out.gridFile = p.string();
        if (!w.contains("spacing")) r.fail("water.spacing", "missing (distance between samples, m)");
        out.gridSpacing = r.number(w["spacing"], "water.spacing", 0.0, kBig, true);
        if (w.contains("origin")) out.gridOrigin = vec2(r, w["origin"], "water.origin", -kBig, kBig);
        if (w.contains("periodic")) out.gridPeriodic = r.boolean(w["periodic"], "water.periodic");
        readHeightCsv(r, out.gridFile, "water.file", out);
    } else if (t == "fft") {
        btFftOceanSettings& f = out.fft;
        if (w.contains("resolution")) {
            f.resolution = r.integer(w["resolution"], "water.resolution", 4, 4096);
            if (f.resolution % 2) r.fail("water.resolution", "must be even");
        }
        if (w.contains("patch_size")) f.patchSize = r.number(w["patch_size"], "water.patch_size", 0.0, kBig, true);
        if (w.contains("wind_speed")) f.windSpeed = r.number(w["wind_speed"], "water.wind_speed", 0.0, 200.0, true);
        if (w.contains("wind_direction")) {
            const Eigen::Vector2d d = direction2(r, w["wind_direction"], "water.wind_direction");
            f.windDirectionX = d.x();
            f.windDirectionZ = d.y();
        }
        if (w.contains("spectrum")) {
            const std::string sp = r.string(w["spectrum"], "water.spectrum");
            if (sp == "phillips") f.spectrum = btFftOceanSettings::Spectrum::Phillips;
            else if (sp == "jonswap") f.spectrum = btFftOceanSettings::Spectrum::Jonswap;
            else r.fail("water.spectrum", "unknown value \"" + sp + "\" (phillips or jonswap)");
        }
        if (w.contains("choppiness")) f.choppiness = r.number(w["choppiness"], "water.choppiness", 0.0, 10.0);
        if (w.contains("seed")) f.seed = std::uint64_t(r.integer(w["seed"], "water.seed", 0, 2147483647));
        f.height = s.waterHeight;
        f.gravity = g > 0 ? g : 9.81;
    } else if (t == "interactive") {
        if (w.contains("size")) {
            out.size = vec2(r, w["size"], "water.size", 0.0, kBig);
            if (!(out.size.x() > 0) || !(out.size.y() > 0)) r.fail("water.size", "both extents must be > 0");
        }
        if (w.contains("centre")) out.centre = vec2(r, w["centre"], "water.centre", -kBig, kBig);
        if (w.contains("resolution")) out.resolution = r.integer(w["resolution"], "water.resolution", 4, 4096);
        if (w.contains("wave_speed")) out.waveSpeed = r.number(w["wave_speed"], "water.wave_speed", 0.0, 1e3, true);
        if (w.contains("damping")) out.damping = r.number(w["damping"], "water.damping", 0.0, 1e3);
        const double dx = out.size.x() / out.resolution;
        if (out.size.y() / dx > 4096.5) r.fail("water.size", "more than 4096 cells along z at this resolution");
    } else if (t == "river") {
        readRiver(r, w, s.waterHeight, out.river);
    }
}

/// "[x, y, z]" of a region corner, m.
std::string cornerText(const Eigen::Vector3d& v) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "[%.6g, %.6g, %.6g]", v.x(), v.y(), v.z());
    return buf;
}

/// The vertices and triangles of an OBJ file ("v x y z" and "f a b c ..." lines, faces of more than 3 corners fanned,
/// "a/t/n" and negative indices accepted); errors name `key` and the file's line.
void readObjMesh(const Reader& r, const std::string& file, const std::string& key, std::vector<Eigen::Vector3d>& vertices,
                 std::vector<int>& triangles) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) r.fail(key, "no such file: " + file);
    std::ifstream in(file);
    if (!in) r.fail(key, "cannot read " + file);
    std::string line;
    int lineNo = 0;
    while (std::getline(in, line)) {
        ++lineNo;
        std::istringstream ls(line);
        std::string tag;
        if (!(ls >> tag)) continue;
        const std::string where = file + " line " + std::to_string(lineNo);
        if (tag == "v") {
            double x = 0, y = 0, z = 0;
            if (!(ls >> x >> y >> z) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
                r.fail(key, where + ": expected \"v x y z\" with finite numbers");
            vertices.emplace_back(x, y, z);
        } else if (tag == "f") {
            std::vector<int> corners;
            std::string item;
            while (ls >> item) {
                char* endp = nullptr;
                const long v = std::strtol(item.c_str(), &endp, 10);
                if (endp == item.c_str() || v == 0) r.fail(key, where + ": bad face corner \"" + item + "\"");
                const long index = v > 0 ? v - 1 : long(vertices.size()) + v;
                if (index < 0 || index >= long(vertices.size()))
                    r.fail(key, where + ": face corner " + std::to_string(v) + " out of range");
                corners.push_back(int(index));
            }
            if (corners.size() < 3) r.fail(key, where + ": a face needs at least 3 corners");
            for (std::size_t k = 1; k + 1 < corners.size(); ++k)
                triangles.insert(triangles.end(), {corners[0], corners[k], corners[k + 1]});
        }
    }
    if (vertices.empty() || triangles.empty()) r.fail(key, file + ": no vertices or faces");
}

/// The "waters" array: each entry a water object (the keys of "water" but "frame") with a required "region": a box
/// {"box": {"min": [x, y, z], "max": [x, y, z]}}, a footprint {"polygon": [[x, z], ...], "bottom": h0, "top": h1}, or
/// a convex tank {"mesh": "tank.obj"} or {"vertices": [[x, y, z], ...], "triangles": [[i, j, k], ...]}. Messages
/// name the entry's keys ("waters[1].height"). Regions must not overlap (touching is allowed): the message names
/// both entries.
void readWaters(const Reader& r, const json& j, Scene& s, const std::string& directory) {
    if (!j.is_array()) r.fail("waters", "expected an array of water objects");
    if (j.empty()) r.fail("waters", "empty: give at least one water object (or use \"water\")");
    std::vector<btWaterBody> checkedRegions;  // the entries' regions as the world will hold them
    for (std::size_t i = 0; i < j.size(); ++i) {
        const std::string key = "waters[" + std::to_string(i) + "]";
        const json& w = j[i];
        r.requireObject(w, key);
        if (w.contains("frame"))
            r.fail(key + ".frame", "not allowed in a \"waters\" entry: the scene has one water frame, the default "
                                   "of its gravity");
        if (!w.contains("region")) r.fail(key + ".region", "missing ({\"box\": {\"min\": [x, y, z], \"max\": [x, y, z]}})");
        // The entry read as a "water" object, its keys named from the entry ("water.height" → "waters[i].height").
        const Reader entry([&r, key](const std::string& k, const std::string& what) {
            const std::string prefix = "water";
            const std::string local = k.compare(0, prefix.size(), prefix) == 0 ? key + k.substr(prefix.size()) : k;
            r.fail(local, what);
        });
        json surface = w;
        surface.erase("region");
        Scene one;
        one.gravity = s.gravity;
        readWater(entry, surface, one, directory, [](const std::string& type) -> std::string {
            if (type == "interactive") return "interactive water is not supported in \"waters\" (use \"water\")";
            return "";
        });
        SceneWaterBody body;
        body.water = one.water;
        body.height = one.waterHeight;
        body.density = one.waterDensity;
        const json& region = w["region"];
        r.requireObject(region, key + ".region");
        r.allowKeys(region, key + ".region", {"box", "polygon", "bottom", "top", "mesh", "vertices", "triangles"});
        const int kinds = int(region.contains("box")) + int(region.contains("polygon")) +
                          int(region.contains("mesh") || region.contains("vertices") || region.contains("triangles"));
        if (kinds != 1)
            r.fail(key + ".region", std::string(kinds == 0 ? "missing its shape" : "more than one shape") +
                                        ": give one of \"box\", \"polygon\" (with \"bottom\" and \"top\"), \"mesh\" "
                                        "(an OBJ file) or \"vertices\" with \"triangles\"");
        if (!region.contains("polygon"))
            for (const char* k : {"bottom", "top"})
                if (region.contains(k)) r.fail(key + ".region." + k, "only with \"polygon\"");
        if (region.contains("box")) {
            const json& box = region["box"];
            r.requireObject(box, key + ".region.box");
            r.allowKeys(box, key + ".region.box", {"min", "max"});
            if (!box.contains("min")) r.fail(key + ".region.box.min", "missing (the lower corner [x, y, z], m)");
            if (!box.contains("max")) r.fail(key + ".region.box.max", "missing (the upper corner [x, y, z], m)");
            body.regionMin = r.vec3(box["min"], key + ".region.box.min", -kBig, kBig);
            body.regionMax = r.vec3(box["max"], key + ".region.box.max", -kBig, kBig);
            static const char* const axes[3] = {"x", "y", "z"};
            for (int k = 0; k < 3; ++k)
                if (!(body.regionMin[k] < body.regionMax[k]))
                    r.fail(key + ".region.box.max", "must be greater than min on every axis (" + std::string(axes[k]) +
                                                        ": max " + cornerText(body.regionMax) + " <= min " +
                                                        cornerText(body.regionMin) + ")");
        } else if (region.contains("polygon")) {
            body.regionKind = btWaterRegionKind::Polygon;
            const json& poly = region["polygon"];
            const std::string pk = key + ".region.polygon";
            if (!poly.is_array()) r.fail(pk, "expected an array of [x, z] points (the water frame's horizontal axes, m)");
            for (std::size_t c = 0; c < poly.size(); ++c) {
                const std::string ck = pk + "[" + std::to_string(c) + "]";
                if (!poly[c].is_array() || poly[c].size() != 2) r.fail(ck, "expected an array of 2 numbers [x, z]");
                body.footprint.push_back({r.number(poly[c][0], ck + "[0]", -kBig, kBig),
                                          r.number(poly[c][1], ck + "[1]", -kBig, kBig)});
            }
            if (!region.contains("bottom")) r.fail(key + ".region.bottom", "missing (the bottom's height along up, m)");
            if (!region.contains("top")) r.fail(key + ".region.top", "missing (the top's height along up, m)");
            body.bottom = r.number(region["bottom"], key + ".region.bottom", -kBig, kBig);
            body.top = r.number(region["top"], key + ".region.top", -kBig, kBig);
        } else {
            body.regionKind = btWaterRegionKind::Mesh;
            if (region.contains("mesh")) {
                if (region.contains("vertices") || region.contains("triangles"))
                    r.fail(key + ".region.mesh", "give either \"mesh\" (a file) or \"vertices\" with \"triangles\"");
                std::filesystem::path p(r.string(region["mesh"], key + ".region.mesh"));
                if (p.is_relative()) p = std::filesystem::path(directory) / p;
                body.meshFile = p.string();
                readObjMesh(r, body.meshFile, key + ".region.mesh", body.meshVertices, body.meshTriangles);
            } else {
                if (!region.contains("vertices")) r.fail(key + ".region.vertices", "missing (an array of [x, y, z], m)");
                if (!region.contains("triangles"))
                    r.fail(key + ".region.triangles", "missing (an array of [i, j, k], outward)");
                const json& vs = region["vertices"];
                const json& ts = region["triangles"];
                if (!vs.is_array()) r.fail(key + ".region.vertices", "expected an array of [x, y, z]");
                if (!ts.is_array()) r.fail(key + ".region.triangles", "expected an array of [i, j, k]");
                for (std::size_t v = 0; v < vs.size(); ++v)
                    body.meshVertices.push_back(
                        r.vec3(vs[v], key + ".region.vertices[" + std::to_string(v) + "]", -kBig, kBig));
                for (std::size_t t = 0; t < ts.size(); ++t) {
                    const std::string tk = key + ".region.triangles[" + std::to_string(t) + "]";
                    if (!ts[t].is_array() || ts[t].size() != 3) r.fail(tk, "expected an array of 3 vertex indices");
                    for (int k = 0; k < 3; ++k)
                        body.meshTriangles.push_back(r.integer(ts[t][k], tk + "[" + std::to_string(k) + "]", 0,
                                                               std::max<long long>(0, (long long)vs.size() - 1)));
                }
            }
        }
        // The region checked as the world will (a simple footprint, a closed mesh), and its bounding box.
        const btWaterBodyInfo info = body.regionInfo();
        btWaterBody checked;
        checked.name = key;
        const std::string regionKey = key + ".region." + (region.contains("box") ? "box" : region.contains("polygon") ? "polygon"
                                                          : region.contains("mesh") ? "mesh" : "triangles");
        try {
            checked.setRegion(info, s.waterFrame, "");
        } catch (const std::invalid_argument& e) {
            const std::string what = e.what();
            if (what.compare(0, 4, "top:") == 0) r.fail(key + ".region.top", what.substr(5));
            if (what.compare(0, 7, "bottom:") == 0) r.fail(key + ".region.bottom", what.substr(8));
            r.fail(regionKey, what);
        }
        if (body.regionKind != btWaterRegionKind::Box) {
            body.regionMin = checked.regionMin;
            body.regionMax = checked.regionMax;
        }
        for (std::size_t o = 0; o < s.waters.size(); ++o) {
            const SceneWaterBody& other = s.waters[o];
            if (body.regionKind == btWaterRegionKind::Box && other.regionKind == btWaterRegionKind::Box) {
                if ((body.regionMin.array() < other.regionMax.array()).all() &&
                    (other.regionMin.array() < body.regionMax.array()).all())
                    r.fail(key + ".region", "the box " + cornerText(body.regionMin) + " to " + cornerText(body.regionMax) +
                                                " overlaps waters[" + std::to_string(o) + "].region " +
                                                cornerText(other.regionMin) + " to " + cornerText(other.regionMax) +
                                                ": the regions of water bodies must not overlap");
            } else if (checked.overlaps(checkedRegions[o], s.waterFrame)) {
                const auto named = [](const btWaterBody& b) {
                    return (b.kind == btWaterRegionKind::Box ? "box " : "") + b.regionText();
                };
                r.fail(key + ".region", "the " + named(checked) + " overlaps waters[" + std::to_string(o) +
                                            "].region (" + named(checkedRegions[o]) +
                                            "): the regions of water bodies must not overlap");
            }
        }
        checkedRegions.push_back(std::move(checked));
        s.waters.push_back(std::move(body));
    }
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& sourceName, const std::string& directory) {
    const Reader r(sourceName);
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {  // parse_error, and out_of_range for numbers like 1e400
        throw UsageError(sourceName + ": invalid JSON: " + e.what());
    }
    r.requireObject(j, "");
    r.allowKeys(j, "", {"gravity", "dt", "substeps_per_frame", "duration", "output_interval", "water", "waters",
                        "bodies", "ground", "camera", "events"});
    Scene s;
    s.directory = directory;
    if (j.contains("gravity")) s.gravity = r.vec3(j["gravity"], "gravity", -1e3, 1e3);  // any direction, or zero
    if (j.contains("dt")) s.dt = r.number(j["dt"], "dt", 1e-6, 1.0, false);
    if (j.contains("substeps_per_frame")) s.substepsPerFrame = r.integer(j["substeps_per_frame"], "substeps_per_frame", 1, 1000);
    if (j.contains("duration")) s.duration = r.number(j["duration"], "duration", 0.0, 1e6);
    if (j.contains("output_interval")) s.outputInterval = r.number(j["output_interval"], "output_interval", 0.0, 1e6, true);
    if (j.contains("water") && j.contains("waters"))
        r.fail("water, waters", "give either \"water\" (one unbounded water) or \"waters\" (bounded water bodies), "
                                "not both");
    if (j.contains("water")) readWater(r, j["water"], s, directory);
    else resolveWaterFrame(r, s);  // the default frame of the gravity
    if (j.contains("waters")) readWaters(r, j["waters"], s, directory);
    if (j.contains("ground")) {
        const json& g = j["ground"];
        r.requireObject(g, "ground");
        r.allowKeys(g, "ground", {"height", "normal"});
        s.groundHeight = g.contains("height") ? r.number(g["height"], "ground.height", -kBig, kBig) : 0.0;
        s.groundNormal = s.waterFrame.up();
        if (g.contains("normal")) {  // a sloped floor (a beach) through the point at `height` along up
            s.groundNormal = r.vec3(g["normal"], "ground.normal", -kBig, kBig);
            if (!(s.groundNormal.norm() > 1e-12)) r.fail("ground.normal", "zero vector");
            s.groundNormal.normalize();
            if (!(s.groundNormal.dot(s.waterFrame.up()) >= 0.1))
                r.fail("ground.normal", "must point up (component of the unit normal along the water frame's up " +
                                            btWaterFrame::vectorText(s.waterFrame.up()) +
                                            " >= 0.1, slope <= 84 degrees)");
        }
    }
    if (j.contains("camera")) {  // the view of the pictures and the browser
        const json& c = j["camera"];
        r.requireObject(c, "camera");
        r.allowKeys(c, "camera", {"target", "distance", "yaw", "pitch"});
        if (c.contains("target")) s.camera.target = r.vec3(c["target"], "camera.target", -kBig, kBig);
        if (c.contains("distance")) s.camera.distance = r.number(c["distance"], "camera.distance", 0.1, 1e4);
        if (c.contains("yaw")) s.camera.yaw = r.number(c["yaw"], "camera.yaw", -360.0, 360.0);
        if (c.contains("pitch")) s.camera.pitch = r.number(c["pitch"], "camera.pitch", -89.0, 89.0);
    }
    if (j.contains("events")) {  // the hysteresis of the water events (btBuoyancyEventSettings)
        const json& e = j["events"];
        r.requireObject(e, "events");
        r.allowKeys(e, "events", {"enter_fraction", "leave_fraction", "submerged_fraction", "surfaced_fraction"});
        const std::pair<const char*, double btBuoyancyEventSettings::*> fields[] = {
            {"enter_fraction", &btBuoyancyEventSettings::enterFraction},
            {"leave_fraction", &btBuoyancyEventSettings::leaveFraction},
            {"submerged_fraction", &btBuoyancyEventSettings::submergedFraction},
            {"surfaced_fraction", &btBuoyancyEventSettings::surfacedFraction}};
        for (const auto& [name, field] : fields)
            if (e.contains(name)) s.events.*field = r.number(e[name], std::string("events.") + name, 0.0, 1.0);
        try {
            s.events.validate();
        } catch (const std::invalid_argument& ex) {  // the order of the thresholds, in the scene's names
            std::string what = ex.what();
            const std::string prefix = "btBuoyancyEventSettings::";
            if (what.compare(0, prefix.size(), prefix) == 0) what = what.substr(prefix.size());
            std::string key = "events";
            for (const auto& [name, field] : fields) {
                (void)field;
                std::string camel = name;  // enter_fraction -> enterFraction
                const std::size_t u = camel.find('_');
                camel = camel.substr(0, u) + char(std::toupper(camel[u + 1])) + camel.substr(u + 2);
                for (std::size_t at = what.find(camel); at != std::string::npos; at = what.find(camel))
                    what.replace(at, camel.size(), name);
            }
            const std::size_t colon = what.find(": ");
            if (colon != std::string::npos) {
                key += "." + what.substr(0, colon);
                what = what.substr(colon + 2);
            }
            r.fail(key, what);
        }
    }
    if (!j.contains("bodies")) r.fail("bodies", "missing");
    if (!j["bodies"].is_array()) r.fail("bodies", "expected an array");
    std::set<std::string> names;
    for (std::size_t i = 0; i < j["bodies"].size(); ++i) {
        const std::string key = "bodies[" + std::to_string(i) + "]";
        s.bodies.push_back(readBody(r, j["bodies"][i], key, i, directory));
        if (!names.insert(s.bodies.back().name).second)
            r.fail(key + ".name", "duplicate name \"" + s.bodies.back().name + "\"");
    }
    return s;
}

Scene parseSceneWater(const std::string& text, const std::string& sourceName, const std::string& directory,
                      double gravity, const SceneWaterTypeFilter& refuseType) {
    // The keys are those of a scene's "water" object; in a file that holds only that object they are named
    // from its top level ("waves[0].amplitude", not "water.waves[0].amplitude").
    const Reader r([sourceName](const std::string& key, const std::string& what) {
        const std::string prefix = "water.";
        const std::string local = key.compare(0, prefix.size(), prefix) == 0 ? key.substr(prefix.size()) : key;
        throw UsageError(sourceName + ": " + local + ": " + what);
    });
    if (!std::isfinite(gravity) || !(gravity > 0))
        throw UsageError(sourceName + ": gravity must be a positive number of m/s^2 (got " + std::to_string(gravity) + ")");
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception& e) {  // parse_error, and out_of_range for numbers like 1e400
        throw UsageError(sourceName + ": invalid JSON: " + e.what());
    }
    Scene s;
    s.directory = directory;
    s.gravity = Eigen::Vector3d(0, -gravity, 0);
    readWater(r, j, s, directory, refuseType);
    return s;
}

namespace {

/// The whole text of a JSON file (`what` names it in the message: "scene file", "water file").
std::string readJsonFileText(const std::string& path, const std::string& what) {
    std::error_code ec;  // a directory opens as a stream but fails on the first read
    if (!std::filesystem::is_regular_file(path, ec)) throw UsageError(path + ": cannot read the " + what + " (not a file)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw UsageError(path + ": cannot read the " + what);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

/// The folder relative paths in the file at `path` are resolved against ("." for a bare file name).
std::string folderOf(const std::string& path) {
    const std::filesystem::path p(path);
    return p.parent_path().empty() ? "." : p.parent_path().string();
}

}  // namespace

Scene loadSceneFile(const std::string& path) {
    const std::string text = readJsonFileText(path, "scene file");
    return parseScene(text, std::filesystem::path(path).filename().string(), folderOf(path));
}

Scene loadSceneWaterFile(const std::string& path, double gravity,
                         const SceneWaterTypeFilter& refuseType) {
    const std::string text = readJsonFileText(path, "water file");
    return parseSceneWater(text, path, folderOf(path), gravity, refuseType);
}

btWaterBodyInfo SceneWaterBody::regionInfo() const {
    const auto bt = [](const Eigen::Vector3d& v) { return btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())); };
    btWaterBodyInfo info;
    info.regionKind = regionKind;
    info.regionMin = bt(regionMin);
    info.regionMax = bt(regionMax);
    info.footprint = footprint;
    info.bottom = bottom;
    info.top = top;
    for (const Eigen::Vector3d& v : meshVertices) info.meshVertices.push_back(bt(v));
    info.meshTriangles = meshTriangles;
    return info;
}

}  // namespace buoyancy::cli
