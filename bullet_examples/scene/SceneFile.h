#pragma once
/// @file SceneFile.h
/// The JSON scene format of `buoyancy run` (documented in docs/scene-format.md): parsed and validated
/// completely before anything runs. Every error names the file and the key, e.g.
/// "boat.json: bodies[1].shape.size: expected an array of 3 numbers > 0".

#include <BulletBuoyancy/bullet/btBuoyancyEvents.h>
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btMarineHydrodynamics.h>
#include <BulletBuoyancy/bullet/btWaterBody.h>
#include <BulletBuoyancy/bullet/btWaterFrame.h>
#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btRiverSurface.h>
#include "scene/SceneGraph.h"

#include <Eigen/Core>
#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace buoyancy::cli {

/// Shape of a scene body.
struct SceneShape {
    std::string type;                                  ///< "box", "sphere", "cylinder", "mesh"
    Eigen::Vector3d size = Eigen::Vector3d::Ones();    ///< box full extents, m
    double radius = 0.5;                               ///< sphere / cylinder radius, m
    double height = 1.0;                               ///< cylinder full height (axis y), m
    int resolution = 128;                              ///< primitive segments around (sphere: rings = resolution/2)
    std::string file;                                  ///< mesh file, resolved against the scene's folder
    double scale = 1.0;                                ///< mesh scale
    bool repair = false;      ///< mesh "repair": repair what is safe to repair (holes, orientation, faces given twice)
    bool convexHull = false;  ///< mesh "convex_hull": replace the model by the convex hull of its vertices
    /// mesh "open_top": close the model's holes (an open-deck hull's rim) with caps that let water in: the caps'
    /// samples are permeable (open fraction 1) and feed the body's water graph (an automatic one when the body
    /// has none), so a swamped boat floods through its deck
    bool openTop = false;
};

/// One body of a scene.
struct SceneBody {
    std::string name;
    SceneShape shape;
    btBuoyantBodySettings body;       ///< density or mass, mass model, ballast, collision, fixed
    Eigen::Vector3d position = Eigen::Vector3d::Zero();   ///< mesh frame origin in world, m
    Eigen::Vector3d axis = Eigen::Vector3d::UnitY();      ///< rotation axis (normalised)
    double degrees = 0;                                   ///< rotation angle, degrees
    Eigen::Vector3d linearVelocity = Eigen::Vector3d::Zero();  ///< COM velocity, world, m/s
    Eigen::Vector3d angularVelocity = Eigen::Vector3d::Zero(); ///< world, rad/s
    btBuoyancySettings buoyancy;      ///< the "buoyancy" block (library defaults when absent)
    /// The "hydrodynamics" block: Fossen's added mass and damping (enabled when the block is present; its presence
    /// turns the buoyancy block's scalar added mass off)
    btMarineHydrodynamics hydrodynamics;
    SceneFlooding flooding;           ///< "water_graph" and "permeability" (SceneGraph.h)
};

/// The "water" block: which surface and its parameters (docs/scene-format.md lists keys and defaults).
/// Level and density live in Scene::waterHeight / Scene::waterDensity.
struct SceneWater {
    std::string type = "flat";                     ///< "flat", "gerstner", "grid", "fft", "interactive", "river"
    Eigen::Vector2d current = Eigen::Vector2d::Zero(); ///< flat: uniform current [vx, vz], m/s
    std::vector<btGerstnerWave> waves;             ///< gerstner
    std::string gridFile;                          ///< grid: CSV path (resolved), rows = z, columns = x
    int gridNx = 0, gridNz = 0;                    ///< grid: samples along x, z
    std::vector<double> gridHeights;               ///< grid: nx·nz heights, m, index j·nx + i
    Eigen::Vector2d gridOrigin = Eigen::Vector2d::Zero(); ///< grid: world [x, z] of the first sample, m
    double gridSpacing = 1.0;                      ///< grid: m
    bool gridPeriodic = true;                      ///< grid: wrap (true) or clamp
    btFftOceanSettings fft;                        ///< fft (height and gravity filled from the scene)
    btRiverSettings river;                         ///< river: centreline, width, speed (height filled from the scene)
    Eigen::Vector2d size = Eigen::Vector2d(20, 20); ///< interactive: extent [x, z], m
    Eigen::Vector2d centre = Eigen::Vector2d::Zero(); ///< interactive: world centre [x, z], m
    int resolution = 128;                          ///< interactive: cells along x
    double waveSpeed = 2.0;                        ///< interactive: c, m/s
    double damping = 0.1;                          ///< interactive: γ, 1/s
    /// "frame": the water frame's up, first horizontal axis and origin (world) as given; absent: the default frame
    /// of the scene's gravity (Scene::waterFrame holds the frame in use either way).
    std::optional<Eigen::Vector3d> frameUp, frameX, frameOrigin;
};

/// One entry of the "waters" array: a bounded water body (docs/scene-format.md, btWaterBody.h).
struct SceneWaterBody {
    SceneWater water;                 ///< surface type and parameters, as the "water" object (no "frame")
    double height = 0.0;              ///< level, m
    double density = 1000.0;          ///< ρ_w, kg/m³
    /// Which region: "region.box" (Box), "region.polygon" (Polygon) or "region.mesh" / "region.vertices" (Mesh).
    btWaterRegionKind regionKind = btWaterRegionKind::Box;
    /// Box: "region.box.min", lower corner, world, m (other kinds: the region's world bounding box).
    Eigen::Vector3d regionMin = Eigen::Vector3d::Zero();
    /// Box: "region.box.max", upper corner, world, m (> min).
    Eigen::Vector3d regionMax = Eigen::Vector3d::Zero();
    /// Polygon: "region.polygon", the footprint's corners [x, z] in the water frame's horizontal axes, m.
    std::vector<std::array<double, 2>> footprint;
    double bottom = 0.0;  ///< Polygon: "region.bottom", height along up, m
    double top = 0.0;     ///< Polygon: "region.top", height along up, m (> bottom)
    /// Mesh: "region.mesh" (an OBJ file, relative to the scene file; the path as resolved) or empty when given inline.
    std::string meshFile;
    /// Mesh: the vertices ("region.vertices", or the OBJ's), world, m.
    std::vector<Eigen::Vector3d> meshVertices;
    /// Mesh: three indices per triangle ("region.triangles", or the OBJ's faces fanned), outward.
    std::vector<int> meshTriangles;

    /// The region as btBuoyancyWorld::addWaterBody takes it (kind, box, footprint, heights, mesh); name, surface and
    /// density are left for the caller.
    btWaterBodyInfo regionInfo() const;
};

/// The "camera" block: the view of `buoyancy run --png` and of the scene browser. Fields left out are
/// chosen to frame the bodies at t = 0.
struct SceneCamera {
    std::optional<Eigen::Vector3d> target; ///< point looked at, world, m
    std::optional<double> distance;        ///< eye–target distance, m
    std::optional<double> yaw;             ///< eye rotation about +y, degrees (0: eye on +z)
    std::optional<double> pitch;           ///< eye elevation above the target, degrees
};

/// A whole scene.
struct Scene {
    Eigen::Vector3d gravity = Eigen::Vector3d(0, -9.81, 0); ///< m/s², any direction (zero: no buoyancy)
    /// The water frame in use (btWaterFrame.h): "water.frame" when given, else the default of `gravity` (the identity
    /// for a zero gravity). Its up is antiparallel to a non-zero gravity (checked by the loader).
    btWaterFrame waterFrame;
    double dt = 1.0 / 240.0;          ///< fixed substep, s
    int substepsPerFrame = 4;         ///< stepSimulation(dt·n, n, dt)
    double duration = 10.0;           ///< s
    double outputInterval = 0.1;      ///< s
    double waterHeight = 0.0;         ///< flat water level, m
    double waterDensity = 1000.0;     ///< kg/m³
    SceneWater water;                 ///< surface type and parameters
    /// "waters": bounded water bodies whose regions do not overlap (checked by the loader), instead of the single
    /// unbounded "water" (empty: that one). Given with "water" is an error.
    std::vector<SceneWaterBody> waters;
    std::optional<double> groundHeight; ///< static floor y = h
    /// Unit normal of the floor (world); the floor is the plane through the point at height h along the water
    /// frame's up (origin + h·up) with this normal (a sloped beach when not up). Key "ground.normal", default: up.
    Eigen::Vector3d groundNormal = Eigen::Vector3d::UnitY();
    std::vector<SceneBody> bodies;
    SceneCamera camera;               ///< "camera": the pictures' and the browser's view
    /// "events": the hysteresis of the water events (enter_fraction, leave_fraction, submerged_fraction,
    /// surfaced_fraction; btBuoyancyEventSettings, whose defaults fill what is left out).
    btBuoyancyEventSettings events;
    std::string directory;            ///< folder of the scene file (mesh paths are relative to it)
};

/// Read and validate a scene file. @throws UsageError naming the file and key for every problem
/// (unreadable file, bad JSON, unknown keys, wrong types, out-of-range values, duplicate names, zero axis,
/// missing mesh files).
Scene loadSceneFile(const std::string& path);

/// Parse a scene from JSON text; `sourceName` prefixes messages, `directory` resolves mesh paths.
Scene parseScene(const std::string& text, const std::string& sourceName, const std::string& directory);

/// Why a water type cannot be used by the caller (e.g. interactive water outside a simulation), or "" to accept it.
using SceneWaterTypeFilter = std::function<std::string(const std::string& type)>;

/// Parse a lone water object: JSON text holding what a scene's "water" key holds (same keys, defaults and checks;
/// messages name the keys from the object's top level: "FILE: waves[0].wavelength: ...").
/// @param sourceName  prefixes every message (the file)
/// @param directory   folder a grid's relative "file" is resolved against
/// @param gravity     g, m/s², > 0: the waves' dispersion (gerstner, fft)
/// @param refuseType  optional: a type it returns a reason for is refused with that reason, naming the "type" key
/// @return a Scene with only gravity, directory, waterHeight, waterDensity and water set (no bodies), ready for
///         makeSceneWater (SceneWater.h)
/// @throws UsageError naming the source and the key
Scene parseSceneWater(const std::string& text, const std::string& sourceName, const std::string& directory,
                      double gravity, const SceneWaterTypeFilter& refuseType = {});

/// parseSceneWater on the file at `path` (messages begin with `path`; a relative grid "file" is resolved against
/// the file's folder). @throws UsageError for a missing or unreadable file and every problem parseSceneWater finds
Scene loadSceneWaterFile(const std::string& path, double gravity, const SceneWaterTypeFilter& refuseType = {});

}  // namespace buoyancy::cli
