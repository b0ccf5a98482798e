#include "cli/SceneFile.h"

#include "cli/CliErrors.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace buoyancy::cli {

namespace {

using json = nlohmann::json;

/// Strict reader: every accessor names the full key path in its error.
class Reader {
public:
    explicit Reader(std::string source) : m_source(std::move(source)) {}

    [[noreturn]] void fail(const std::string& key, const std::string& what) const {
        throw UsageError(m_source + ": " + key + ": " + what);
    }

    void requireObject(const json& j, const std::string& key) const {
        if (!j.is_object()) fail(key.empty() ? "(top level)" : key, "expected an object");
    }

    void allowKeys(const json& j, const std::string& key, std::initializer_list<const char*> allowed) const {
        std::set<std::string> ok(allowed.begin(), allowed.end());
        for (auto it = j.begin(); it != j.end(); ++it)
            if (!ok.count(it.key())) fail(join(key, it.key()), "unknown key");
    }

    static std::string join(const std::string& parent, const std::string& key) {
        return parent.empty() ? key : parent + "." + key;
    }

    /// Number in [lo, hi] (strict lower bound when lowOpen).
    double number(const json& j, const std::string& key, double lo, double hi, bool lowOpen = false) const {
        if (!j.is_number()) fail(key, "expected a number");
        const double v = j.get<double>();
        if (!std::isfinite(v) || (lowOpen ? !(v > lo) : !(v >= lo)) || !(v <= hi)) {
            std::ostringstream os;
            os << "value " << v << " out of range " << (lowOpen ? "(" : "[") << lo << ", " << hi << "]";
            fail(key, os.str());
        }
        return v;
    }

    int integer(const json& j, const std::string& key, int lo, int hi) const {
        if (!j.is_number_integer() && !j.is_number_unsigned()) fail(key, "expected an integer");
        const long long v = j.get<long long>();
        if (v < lo || v > hi) fail(key, "value " + std::to_string(v) + " out of range [" + std::to_string(lo) + ", " +
                                            std::to_string(hi) + "]");
        return int(v);
    }

    Eigen::Vector3d vec3(const json& j, const std::string& key, double lo = -1e9, double hi = 1e9,
                         bool lowOpen = false) const {
        if (!j.is_array() || j.size() != 3) fail(key, "expected an array of 3 numbers");
        Eigen::Vector3d v;
        for (int k = 0; k < 3; ++k) v[k] = number(j[k], key + "[" + std::to_string(k) + "]", lo, hi, lowOpen);
        return v;
    }

    std::string string(const json& j, const std::string& key) const {
        if (!j.is_string()) fail(key, "expected a string");
        return j.get<std::string>();
    }

    bool boolean(const json& j, const std::string& key) const {
        if (!j.is_boolean()) fail(key, "expected true or false");
        return j.get<bool>();
    }

private:
    std::string m_source;
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
        r.allowKeys(j, key, {"type", "file", "scale"});
        if (!j.contains("file")) r.fail(key + ".file", "missing");
        const std::string file = r.string(j["file"], key + ".file");
        std::filesystem::path p(file);
        if (p.is_relative()) p = std::filesystem::path(directory) / p;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(p, ec)) r.fail(key + ".file", "no such file: " + p.string());
        s.file = p.string();
        if (j.contains("scale")) s.scale = r.number(j["scale"], key + ".scale", 0.0, kBig, true);
    } else {
        r.fail(key + ".type", "unknown shape type \"" + s.type + "\" (box, sphere, cylinder or mesh)");
    }
    return s;
}

btBuoyancySettings readBuoyancy(const Reader& r, const json& j, const std::string& key) {
    r.requireObject(j, key);
    r.allowKeys(j, key, {"method", "texture", "drag_coefficient", "skin_friction", "linear_damping", "added_mass",
                         "added_mass_coefficient"});
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
    if (j.contains("drag_coefficient")) b.dragCoefficient = r.number(j["drag_coefficient"], key + ".drag_coefficient", 0, 100);
    if (j.contains("skin_friction")) b.skinFriction = r.number(j["skin_friction"], key + ".skin_friction", 0, 100);
    if (j.contains("linear_damping")) b.linearDamping = r.number(j["linear_damping"], key + ".linear_damping", 0, 100);
    if (j.contains("added_mass")) b.addedMass = r.boolean(j["added_mass"], key + ".added_mass");
    if (j.contains("added_mass_coefficient"))
        b.addedMassCoefficient = r.number(j["added_mass_coefficient"], key + ".added_mass_coefficient", 0, 100);
    return b;
}

SceneBody readBody(const Reader& r, const json& j, const std::string& key, std::size_t index,
                   const std::string& directory) {
    r.requireObject(j, key);
    r.allowKeys(j, key, {"name", "shape", "density", "mass", "mass_model", "thickness", "position", "rotation",
                         "linear_velocity", "angular_velocity", "buoyancy", "ballast", "fixed", "collision"});
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
    return b;
}

}  // namespace

Scene parseScene(const std::string& text, const std::string& sourceName, const std::string& directory) {
    const Reader r(sourceName);
    json j;
    try {
        j = json::parse(text);
    } catch (const json::parse_error& e) {
        throw UsageError(sourceName + ": invalid JSON: " + e.what());
    }
    r.requireObject(j, "");
    r.allowKeys(j, "", {"gravity", "dt", "substeps_per_frame", "duration", "output_interval", "water", "bodies",
                        "ground"});
    Scene s;
    s.directory = directory;
    if (j.contains("gravity")) {
        s.gravity = r.vec3(j["gravity"], "gravity", -1e3, 1e3);
        if (s.gravity.x() != 0 || s.gravity.z() != 0 || !(s.gravity.y() < 0))
            r.fail("gravity", "must point down y, e.g. [0, -9.81, 0] (the water is a height field in y)");
    }
    if (j.contains("dt")) s.dt = r.number(j["dt"], "dt", 1e-6, 1.0, false);
    if (j.contains("substeps_per_frame")) s.substepsPerFrame = r.integer(j["substeps_per_frame"], "substeps_per_frame", 1, 1000);
    if (j.contains("duration")) s.duration = r.number(j["duration"], "duration", 0.0, 1e6);
    if (j.contains("output_interval")) s.outputInterval = r.number(j["output_interval"], "output_interval", 0.0, 1e6, true);
    if (j.contains("water")) {
        const json& w = j["water"];
        r.requireObject(w, "water");
        r.allowKeys(w, "water", {"type", "height", "density"});
        if (w.contains("type")) {
            const std::string t = r.string(w["type"], "water.type");
            if (t != "flat") r.fail("water.type", "unknown value \"" + t + "\" (flat)");
        }
        if (w.contains("height")) s.waterHeight = r.number(w["height"], "water.height", -kBig, kBig);
        if (w.contains("density")) s.waterDensity = r.number(w["density"], "water.density", 0.0, 1e5, true);
    }
    if (j.contains("ground")) {
        const json& g = j["ground"];
        r.requireObject(g, "ground");
        r.allowKeys(g, "ground", {"height"});
        s.groundHeight = g.contains("height") ? r.number(g["height"], "ground.height", -kBig, kBig) : 0.0;
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

Scene loadSceneFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw UsageError(path + ": cannot read the scene file");
    std::ostringstream text;
    text << in.rdbuf();
    const std::filesystem::path p(path);
    return parseScene(text.str(), p.filename().string(), p.parent_path().empty() ? "." : p.parent_path().string());
}

}  // namespace buoyancy::cli
