#include "cli/HydrostaticsCommand.h"

#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include "scene/ChildProcessImport.h"
#include "scene/ModelPreparation.h"
#include "scene/ModelSize.h"
#include "scene/NumberFormat.h"
#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"
#include "scene/SceneWater.h"
#include <BulletBuoyancy/integrals/BuoyancyMethod.h>
#include <BulletBuoyancy/integrals/IntegrationMethod.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/MassProperties.h>
#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>
#include <filesystem>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

namespace buoyancy::cli {

void addHydrostaticsCommand(CLI::App& app, HydrostaticsOptions& o) {
    CLI::App* sub = app.add_subcommand(
        "hydrostatics",
        "Dry mass properties and hydrostatics of a mesh. The pose is applied to the mesh (rotation about the axis "
        "through the mesh origin, then translation), then the water cuts it: flat water at y = H, or with --water "
        "the water a scene file describes (flat, gerstner, grid or fft) at time --time.");
    sub->add_option("MESH", o.mesh, "mesh file (.obj .ply .stl .gltf .glb .dae .fbx .3ds)")->required();
    sub->add_option("--scale", o.scale, "uniform scale applied after import (default 1)");
    sub->add_option("--rotate", o.rotate, "rotation: axis AX AY AZ (normalised) and angle DEG")
        ->expected(4)
        ->type_name("AX AY AZ DEG");
    sub->add_option("--translate", o.translate, "translation TX TY TZ, m")->expected(3)->type_name("TX TY TZ");
    sub->add_option("--water-height", o.water_height, "flat water level H, m (default 0); not with --water");
    sub->add_option("--water-density", o.water_density, "water density, kg/m^3 (default 1000); not with --water");
    sub->add_option("--water", o.water_file,
                    "JSON file holding a scene's \"water\" object: flat, gerstner, grid or fft (interactive water needs "
                    "`buoyancy run`); its \"density\" is the water's, a grid's \"file\" is relative to this "
                    "file's folder")
        ->type_name("FILE.json");
    sub->add_option("--time", o.time, "time at which the --water water is taken, s (default 0); needs --water")->type_name("T");
    sub->add_option("--gravity", o.gravity, "gravitational acceleration g, m/s^2 (default 9.81)");
    sub->add_option("--method", o.method,
                    "texel-centre | exact-coverage | exact-mesh | default (default: chosen per mesh)");
    sub->add_option("--texture", o.texture, "texture side N (N x N texels); ignored by exact-mesh");
    sub->add_option("--error-budget", o.error_budget,
                    "automatic level of detail: worst volume error allowed, % of the body's volume");
    sub->add_option("--import-timeout", o.import_timeout, "time limit of the mesh import, s (default 10)");
    sub->add_flag("--json", o.json, "print one JSON object instead of a table");
    sub->add_flag("--repair", o.repair,
                  "repair a broken model instead of refusing it: remove faces given twice, turn faces to agree, close "
                  "each hole with the least-area cap of its rim (an open-deck hull is closed at its gunwale); says "
                  "what it did and the volume before and after");
    sub->add_flag("--convex-hull", o.convex_hull,
                  "replace the model by the convex hull of its vertices (works on any model; states the volume it "
                  "adds)");
}

namespace {

void requireFinite(double v, const char* what) {
    if (!std::isfinite(v) || std::fabs(v) > 1e300) throw UsageError(std::string("non-finite value given for ") + what);
}

bool allFinite(const Eigen::Vector3d& v) { return v.allFinite(); }

nlohmann::json vec(const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); }

/// The water the mesh is cut by: flat water from the flags, or the water of a `--water` file at `--time`.
struct CommandWater {
    std::unique_ptr<btWaterSurface> surface;
    std::string type = "flat";          ///< the scene file's water type: flat, gerstner, grid or fft
    std::optional<std::string> file;    ///< the --water file; absent for the flags' flat water
    double time = 0;                    ///< the water's time, s
    std::optional<double> meanLevel;    ///< mean (rest) level, m (world y); absent for a grid (absolute heights)
    double density = 1000;              ///< kg/m³
};

/// Refuses the flag combinations that cannot mean anything; every message names both flags.
void checkWaterFlags(const HydrostaticsOptions& o) {
    if (o.water_file && o.water_height)
        throw UsageError("--water-height cannot be used with --water: the water file sets the level (its \"height\" "
                         "key)");
    if (o.water_file && o.water_density)
        throw UsageError("--water-density cannot be used with --water: the water file sets the density (its "
                         "\"density\" key)");
    if (o.time && !o.water_file)
        throw UsageError("--time needs --water: the flat water of --water-height does not change with time");
    if (o.time) requireFinite(*o.time, "--time");
    if (o.water_height) requireFinite(*o.water_height, "--water-height");
    if (o.water_density) {
        requireFinite(*o.water_density, "--water-density");
        if (!(*o.water_density > 0)) throw UsageError("--water-density must be positive");
    }
    if (o.water_file && o.water_file->empty()) throw UsageError("--water: the file name is empty");
}

/// The water of the flags, or of the --water file (read by the scene reader, built as `buoyancy run` builds it).
/// @param gravity  g, m/s² (the waves' dispersion)
CommandWater makeCommandWater(const HydrostaticsOptions& o, double gravity) {
    CommandWater w;
    w.time = o.time.value_or(0.0);
    if (!o.water_file) {
        w.meanLevel = o.water_height.value_or(0.0);
        w.density = o.water_density.value_or(1000.0);
        w.surface = std::make_unique<btFlatWaterSurface>(*w.meanLevel);
        return w;
    }
    const std::string& path = *o.water_file;
    const Scene scene = loadSceneWaterFile(path, gravity, [](const std::string& type) -> std::string {
        if (type == "interactive")
            return "\"interactive\" water needs a simulation (the bodies push it and it moves with them): use it in "
                   "a scene with `buoyancy run`";
        return "";
    });
    // The command's world is y-up with the water's coordinates (the mesh is posed by --rotate / --translate): a
    // "frame" other than that one would be ignored, so it is refused rather than silently dropped.
    if (!scene.waterFrame.isIdentity())
        throw UsageError(path + ": frame: `buoyancy hydrostatics` works in the water's own coordinates (y up): leave "
                                "\"frame\" out and pose the mesh with --rotate / --translate");
    SceneWaterSurface made;
    try {
        made = makeSceneWater(scene);
    } catch (const UsageError& e) {
        throw UsageError(path + ": " + e.what());
    }
    w.surface = std::move(made.surface);
    w.type = scene.water.type;
    w.file = path;
    w.density = scene.waterDensity;
    if (w.type != "grid") w.meanLevel = scene.waterHeight;
    return w;
}

/// The "water" entry of --json.
nlohmann::json waterJson(const CommandWater& w) {
    return {{"type", w.type},
            {"file", w.file ? nlohmann::json(*w.file) : nlohmann::json(nullptr)},
            {"time", w.time},
            {"height", w.meanLevel ? nlohmann::json(*w.meanLevel) : nlohmann::json(nullptr)},
            {"density", w.density}};
}

}  // namespace

int runHydrostatics(const HydrostaticsOptions& o) {
    // ---- Validate the flags before any work (exit 2 on bad input) -------------------------------------------
    requireFinite(o.scale, "--scale");
    if (!(o.scale > 0)) throw UsageError("--scale must be positive (got " + std::to_string(o.scale) + ")");
    for (double v : o.rotate) requireFinite(v, "--rotate");
    for (double v : o.translate) requireFinite(v, "--translate");
    checkWaterFlags(o);
    requireFinite(o.gravity, "--gravity");
    requireFinite(o.import_timeout, "--import-timeout");
    if (!(o.gravity > 0)) throw UsageError("--gravity must be positive (gravity points down y)");
    if (!(o.import_timeout > 0)) throw UsageError("--import-timeout must be positive");
    const Eigen::Vector3d axis(o.rotate[0], o.rotate[1], o.rotate[2]);
    if (!(axis.norm() > 1e-12)) throw UsageError("--rotate: the rotation axis is zero");
    if (o.method != "auto" && !parseBuoyancyMethod(o.method))
        throw UsageError("--method: unknown method '" + o.method +
                         "' (texel-centre, exact-coverage, exact-mesh, default)");
    if (o.texture && (*o.texture < 1 || *o.texture > 8192))
        throw UsageError("--texture must be between 1 and 8192 (got " + std::to_string(*o.texture) + ")");
    // The water file is read before the (slower) mesh import, so its mistakes are reported at once.
    const CommandWater water = makeCommandWater(o, o.gravity);

    // ---- Load and check the mesh (assimp in a child process) -------------------------------------------------
    std::vector<MeshWarning> warnings;
    TriangleMesh mesh;
    MeshReport report;
    PreparedModel prepared;
    try {
        mesh = importMeshInChildProcess(o.mesh, o.scale, o.import_timeout, &warnings);
        // Name the file as the importer does (its name, not the whole path) in every message.
        const std::string name = std::filesystem::path(o.mesh).filename().string();
        prepared = prepareModel(mesh, name.empty() ? o.mesh : name, ModelChoices{o.repair, o.convex_hull},
                                "--repair closes holes and fixes orientation; --convex-hull replaces the model by its "
                                "hull");
        report = prepared.report;
    } catch (const MeshError& e) {
        throw UsageError(e.what());
    }
    for (const auto& w : report.warnings) warnings.push_back(w);
    if (const auto hint = modelSizeHint(mesh, o.scale)) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "the model's largest side is %.6g m (after --scale %g): is it in another unit? "
                      "e.g. --scale %g", hint->side, o.scale, hint->suggestedScale);
        warnings.push_back({buf});
    }

    // ---- Shape: the library's own pipeline (method choice, UVs, baking, mass properties) ---------------------
    // The CLI runs exactly what a btBuoyancyAction would use, so its numbers are the library's.
    btBuoyancySettings settings;
    settings.method = btBuoyancyMethodFromName(o.method);  // "default" = Auto
    settings.textureSize = o.texture.value_or(0);
    if (!std::isfinite(o.error_budget) || o.error_budget < 0)
        throw UsageError("--error-budget: must be a number >= 0 (% of the body's volume)");
    settings.errorBudget = o.error_budget;  // automatic level of detail
    const bool meshHadUvs = mesh.hasUvs();
    const std::size_t triangles = mesh.triangleCount();
    std::shared_ptr<const btBuoyancyShape> shape;
    try {
        shape = btBuoyancyShape::create(std::move(mesh), settings);
    } catch (const std::exception& e) {  // e.g. charts that cannot fit a tiny --texture, a texture too coarse
        const btBuoyancyMethod wanted = btBuoyancyResolveMethod(settings, triangles);
        if (!integrationMethod(wanted).sampled) throw UsageError(o.mesh + ": " + e.what());
        // A mesh that passed prepareMesh encloses a positive volume: a texture method that fails on it had too
        // few texels (found by fuzzing).
        throw UsageError(o.mesh + ": texture " + std::to_string(btBuoyancyResolveTextureSize(settings, wanted)) +
                         " is too coarse for this mesh (" + e.what() + "); use a larger --texture");
    }
    const btBuoyancyMethod method = shape->getMethod();
    const int texture = shape->getTextureSize();
    const IntegrationMethod& integration = shape->getIntegrationMethod();
    if (!integration.sampled && o.texture)
        warnings.push_back({std::string("--texture is ignored by the ") + integration.name + " method"});
    if (shape->usesGeneratedUvs() && meshHadUvs) {
        std::string why;
        for (const auto& r : shape->getUvProblems()) why += (why.empty() ? "" : "; ") + r;
        warnings.push_back({"model UVs not usable (" + why + "): generated an atlas"});
    }

    // Pose: rotation about the axis through the mesh origin, then translation.
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translate(Eigen::Vector3d(o.translate[0], o.translate[1], o.translate[2]));
    pose.rotate(Eigen::AngleAxisd(o.rotate[3] * M_PI / 180.0, axis.normalized()));

    const MassProperties& dry = shape->getUnitSolid();
    HydrostaticsResult wet;
    // "generated" when the samples came through our atlas; exact-mesh uses no texture: it reports the model's.
    const std::string uvSource = shape->usesGeneratedUvs() || !meshHadUvs ? "generated" : "model";
    const std::size_t sampleCount = shape->getSamples().size();
    {
        // As the action computes it (design.md 2.5, 8.2): the method's own evaluation, exact heights, no cache.
        const Eigen::Vector3d reference = pose * dry.centre;
        SampleWorkspace ws;
        wet = integration.evaluate(shape->getGeometry(shape->getSamples()), pose,
                                   {*water.surface, water.time, water.density, o.gravity, reference, nullptr, &ws,
                                    nullptr});
    }
    if (!std::isfinite(dry.volume) || !allFinite(dry.centre) || !dry.inertia.allFinite() ||
        !std::isfinite(wet.submerged_volume) || !allFinite(wet.force) || !allFinite(wet.torque))
        throw InternalError("non-finite result for " + o.mesh);
    for (const auto& w : warnings) std::cerr << "warning: " << w.message << '\n';

    // A body is "dry" when no measurable volume is under water (relative to its own volume).
    const bool isWet = wet.submerged_volume > 1e-12 * std::fabs(dry.volume);

    if (o.json) {
        nlohmann::json j;
        nlohmann::json warn = nlohmann::json::array();
        for (const auto& w : warnings) warn.push_back(w.message);
        nlohmann::json inertia = nlohmann::json::array();
        for (int r = 0; r < 3; ++r) inertia.push_back({dry.inertia(r, 0), dry.inertia(r, 1), dry.inertia(r, 2)});
        j["mesh"] = {{"file", o.mesh},
                     {"triangles", triangles},
                     {"components", report.components},
                     {"uv", uvSource},
                     {"warnings", warn},
                     {"area", dry.area},
                     {"volume", dry.volume},
                     {"centre_of_volume", vec(dry.centre)},
                     {"inertia_unit_density", inertia}};
        {
            // What --repair and --convex-hull did (null when not asked for).
            const MeshRepairReport& r = report.repair;
            auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
            j["repair"] = o.repair && !prepared.hulled
                              ? nlohmann::json{{"duplicate_faces_removed", r.duplicate_faces_removed},
                                               {"faces_reoriented", r.faces_reoriented},
                                               {"paired_nonmanifold_edges", r.paired_nonmanifold_edges},
                                               {"holes_closed", r.holes_closed},
                                               {"hole_edges", r.hole_edges},
                                               {"area_added", r.area_added},
                                               {"volume_before", number(r.volume_before)},
                                               {"volume_after", number(r.volume_after)}}
                              : nlohmann::json(nullptr);
            j["convex_hull"] = prepared.hulled
                                   ? nlohmann::json{{"volume", prepared.hullVolume},
                                                    {"model_volume", prepared.modelVolume
                                                                         ? nlohmann::json(*prepared.modelVolume)
                                                                         : nlohmann::json(nullptr)}}
                                   : nlohmann::json(nullptr);
        }
        j["method"] = {{"name", btBuoyancyMethodName(method)}, {"texture", texture}, {"samples", sampleCount},
                       {"level_of_detail", btBuoyancyPickLevelOfDetail(settings, triangles).description}};
        j["submerged"] = {{"volume", isWet ? wet.submerged_volume : 0.0},
                          {"centre_of_buoyancy", isWet ? vec(wet.centre_of_buoyancy) : nlohmann::json(nullptr)},
                          {"force", vec(wet.force)},
                          {"torque", vec(wet.torque)},
                          {"waterline_area", wet.waterline_area}};
        j["water"] = waterJson(water);
        removeNegativeZeros(j);
        std::cout << j.dump(2) << '\n';
        return kExitOk;
    }

    auto v3 = [](const Eigen::Vector3d& v) {
        char buf[128];
        std::snprintf(buf, sizeof buf, "(%.9g, %.9g, %.9g)", withoutNegativeZero(v.x()), withoutNegativeZero(v.y()),
                      withoutNegativeZero(v.z()));
        return std::string(buf);
    };
    std::printf("mesh               %s\n", o.mesh.c_str());
    std::printf("  triangles        %zu (components %zu, UVs %s)\n", triangles, report.components,
                uvSource.c_str());
    std::printf("  area             %.9g m^2\n", dry.area);
    std::printf("  volume           %.9g m^3\n", dry.volume);
    std::printf("  centre of volume %s m (mesh frame)\n", v3(dry.centre).c_str());
    std::printf("  inertia / rho    [%.9g %.9g %.9g; %.9g %.9g %.9g; %.9g %.9g %.9g] m^5 (about the centre)\n",
                withoutNegativeZero(dry.inertia(0, 0)), withoutNegativeZero(dry.inertia(0, 1)),
                withoutNegativeZero(dry.inertia(0, 2)), withoutNegativeZero(dry.inertia(1, 0)),
                withoutNegativeZero(dry.inertia(1, 1)), withoutNegativeZero(dry.inertia(1, 2)),
                withoutNegativeZero(dry.inertia(2, 0)), withoutNegativeZero(dry.inertia(2, 1)),
                withoutNegativeZero(dry.inertia(2, 2)));
    std::printf("method             %s", btBuoyancyMethodName(method));
    if (texture) std::printf(" (texture %dx%d, %zu samples)", texture, texture, sampleCount);
    std::printf("\nlevel of detail    %s", btBuoyancyPickLevelOfDetail(settings, triangles).description.c_str());
    if (!water.file) {
        std::printf("\nwater              flat at y = %.9g m, density %.9g kg/m^3, g = %.9g m/s^2\n",
                    withoutNegativeZero(*water.meanLevel), water.density, o.gravity);
    } else {
        std::printf("\nwater              %s from %s at t = %.9g s", water.type.c_str(), water.file->c_str(),
                    withoutNegativeZero(water.time));
        if (water.meanLevel) std::printf(", mean level y = %.9g m", withoutNegativeZero(*water.meanLevel));
        std::printf(", density %.9g kg/m^3, g = %.9g m/s^2\n", water.density, o.gravity);
    }
    std::printf("submerged volume   %.9g m^3 (%.6g %% of the body)\n", isWet ? wet.submerged_volume : 0.0,
                dry.volume > 0 ? 100.0 * (isWet ? wet.submerged_volume : 0.0) / dry.volume : 0.0);
    std::printf("centre of buoyancy %s\n", isWet ? (v3(wet.centre_of_buoyancy) + " m (world)").c_str() : "none (dry)");
    std::printf("force              %s N\n", v3(wet.force).c_str());
    std::printf("torque             %s N m (about the posed centre of volume)\n", v3(wet.torque).c_str());
    std::printf("waterline area     %.9g m^2\n", withoutNegativeZero(wet.waterline_area));
    return kExitOk;
}

}  // namespace buoyancy::cli
