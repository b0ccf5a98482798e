#pragma once
/// @file SceneGraph.h
/// The body keys "water_graph" and "permeability" of a scene (docs/scene-format.md): parsing
/// with errors that name the file and key, and building the graph and the permeable samples of a body.

#include "scene/SceneJsonReader.h"  // SceneFailFn
#include <BulletBuoyancy/graph/AutoWaterGraph.h>
#include <BulletBuoyancy/graph/PermeabilityMap.h>
#include <BulletBuoyancy/graph/PermeabilityTexture.h>
#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/graph/WaterIngress.h>

#include <nlohmann/json_fwd.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace buoyancy::cli {

/// One heavier (or lighter) cap of a scene density map.
struct SceneDensitySpot {
    Eigen::Vector3d direction = -Eigen::Vector3d::UnitY(); ///< from the shape's bounds centre, body frame (unit)
    double angleDegrees = 45;                               ///< half-angle of the cap, degrees, (0, 180]
    double value = 1;                                       ///< relative areal density inside, >= 0
};

/// "density_map": a time-varying dry mass distribution over the surface (paper Fig. 15). Relative areal
/// density σ = `base`, or a spot's `value` inside its cap (the largest of overlapping spots); the spots turn
/// about `rotationAxis` at `degreesPerSecond`, in steps of `updateInterval` (the mass properties are
/// recomputed only at those steps). The body's "mass" is the total it is rescaled to.
struct SceneDensityMap {
    bool enabled = false;                                  ///< the body has a "density_map"
    double base = 1;                                       ///< relative areal density outside the spots, >= 0
    std::vector<SceneDensitySpot> spots;                   ///< "spots"
    Eigen::Vector3d rotationAxis = Eigen::Vector3d::UnitZ(); ///< "rotation.axis", body frame (unit)
    double degreesPerSecond = 0;                           ///< "rotation.degrees_per_second"
    double updateInterval = 0.1;                           ///< "update_interval", s, > 0
    /// Map version at time t: floor(t / updateInterval) while rotating, 0 for a fixed map.
    std::int64_t version(double t) const;
    /// Relative areal density at body-frame surface point p for the map of time t (`centre`: the shape's
    /// bounds centre).
    double density(double t, const Eigen::Vector3d& p, const Eigen::Vector3d& centre) const;
};

/// One body's water graph, permeability and density map as read from the scene.
struct SceneFlooding {
    bool enabled = false;           ///< the body has a "water_graph"
    bool automatic = false;         ///< "water_graph": {"auto": {...}}: built from the mesh at run time
    WaterGraph graph;               ///< the hand-made graph (or the parameters of the automatic one)
    AutoWaterGraphSettings autoSettings; ///< automatic graph settings
    bool sdf = false;               ///< "auto": {"method": "sdf"}: CGAL's SDF segmentation (BULLET_BUOYANCY_CGAL=ON only)
    std::vector<PermeabilityRegion> regions;  ///< "permeability": {"regions": [...]}; node resolved below
    std::vector<std::string> regionNodes;     ///< #regions node name each region feeds ("" = nearest node)
    bool hasTexture = false;                  ///< "permeability": {"texture": ...}
    std::string texturePath;                  ///< resolved against the scene's folder
    PermeabilityImage texture;                ///< loaded while reading the scene (errors name the key and file)
    TextureFilter textureFilter = TextureFilter::Bilinear; ///< "filter": "bilinear" (default) or "nearest"
    SceneDensityMap densityMap;               ///< "density_map" (paper Fig. 15; no graph needed)
};

/// Read the "water_graph", "permeability" and "density_map" keys of body object `body` (key = "bodies[i]").
/// A permeability texture is loaded here, so a missing or bad image fails before anything runs.
/// "water_graph" may be an object or the path of a JSON file with the same schema (relative to `directory`).
SceneFlooding readSceneFlooding(const nlohmann::json& body, const std::string& key, const std::string& directory,
                                const SceneFailFn& fail);

/// The body's graph: the hand-made one, or the automatic one built from `mesh`.
/// @throws std::invalid_argument (automatic graph of a mesh with no interior, region node names unknown)
WaterGraph buildSceneWaterGraph(const SceneFlooding& flooding, const TriangleMesh& mesh);

/// The permeable samples of the body from its regions (node names resolved in `graph`).
/// @throws std::invalid_argument naming a region whose node does not exist, or when a texture was given
/// (that needs the mesh: use the overload below)
PermeableSamples buildScenePermeability(const SceneFlooding& flooding, const WaterGraph& graph,
                                        const SurfaceSamples& samples);

/// The permeable samples from the texture (looked up at each sample's UV in the model's UVs, or in the
/// generated atlas at the image's larger side when the model has none; see PermeabilityTexture.h) and the
/// regions (largest value wins). Without a texture, as the overload above.
PermeableSamples buildScenePermeability(const SceneFlooding& flooding, const WaterGraph& graph,
                                        const SurfaceSamples& samples, const TriangleMesh& mesh);

/// Make the samples of `triangles` (a model's openings, e.g. an open-deck hull's deck) fully permeable: each
/// sample whose triangle is one of them is added to `holes` with its whole area open, feeding its nearest node
/// (a sample already there is left as it is).
void addOpenTriangles(PermeableSamples& holes, const SurfaceSamples& samples, const WaterGraph& graph,
                      const std::vector<std::size_t>& triangles);

}  // namespace buoyancy::cli
