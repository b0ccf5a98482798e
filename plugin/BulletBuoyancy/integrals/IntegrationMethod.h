#pragma once
/// @file IntegrationMethod.h
/// The seam for integration methods (design.md 8.2): what a method prepares once per shape and how it evaluates
/// the hydrostatics of a pose. Every method is one entry of the registry (IntegrationMethod.cpp); the shape, the
/// action, the device backends and the command line ask the entry instead of testing the method's value.

#include <BulletBuoyancy/bake/SurfaceSamples.h>
#include <BulletBuoyancy/integrals/BuoyancyMethod.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/MassProperties.h>
#include <BulletBuoyancy/integrals/MeshMomentTree.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

class btWaterSurface;
struct btWaterQueryCache;

namespace buoyancy {

class WaterPatch;

/// What a shape's preparation is given besides its mesh.
struct PrepareOptions {
    int textureSize = 0;        ///< N of the N×N sample texture, resolved (sampled methods; ignored by the others)
    bool preferModelUvs = true; ///< sampled methods: use the model's UVs when they are a valid layout
    double boundsRadius = 0;    ///< radius of the mesh's bounding sphere, m (sizes the per-face drag samples)
};

/// What a method computed once for one mesh: the data its evaluation reads, its drag samples and the mesh's dry
/// mass properties from the same discretisation (so a body of the fluid's density stays exactly neutral).
struct PreparedShape {
    SurfaceSamples samples;          ///< baked surface samples (sampled methods; empty otherwise)
    SurfaceSamples faceSamples;      ///< drag samples of a method without surface samples: triangle pieces
    MeshMomentTree tree;             ///< moment tree of the mesh (methods that clip the mesh; empty otherwise)
    MassProperties unitSolid;        ///< solid at density 1 kg/m³ (mass = volume), mesh frame
    MassProperties unitShell;        ///< shell at density 1 kg/m³ and thickness 1 m (mass = area), mesh frame
    bool uvGenerated = false;        ///< the samples were baked through a generated atlas
    std::vector<std::string> uvProblems; ///< why the model's UVs were not used (when uvGenerated)
};

/// The shape data one evaluation reads (not owned).
struct MethodGeometry {
    const TriangleMesh& mesh;        ///< the mesh, body frame
    const MeshMomentTree& tree;      ///< PreparedShape::tree
    const SurfaceSamples& samples;   ///< the samples in use: PreparedShape::samples, or a deformable body's own
};

/// The water and frame of one evaluation (not owned).
struct MethodWater {
    const btWaterSurface& surface;           ///< the height field
    double time = 0;                         ///< s
    double fluidDensity = 1000;              ///< ρ, kg/m³
    double gravity = 9.81;                   ///< g, m/s²
    const Eigen::Vector3d& torqueReference;  ///< the torque's reference point, world, m
    const WaterPatch* patch = nullptr;       ///< optional per-body height grid over the body (design.md 2.5)
    SampleWorkspace* workspace = nullptr;    ///< per-body scratch arrays (required by sampled methods)
    btWaterQueryCache* cache = nullptr;      ///< optional per-body warm-start memory of the height query
};

/// One integration method: its name and its two steps. Plain data and function pointers: one indirect call per
/// body and evaluation, none per sample.
struct IntegrationMethod {
    BuoyancyMethod method = BuoyancyMethod::ExactMesh; ///< the enumerator it stands for (never Auto)
    const char* name = "";           ///< name in scene files, on the command line, in JSON and CSV (buoyancyMethodName)
    /// True when the method integrates over baked surface samples: it needs a texture size and a UV layout, its drag
    /// runs over the same samples, and a deformable body can re-bake them.
    bool sampled = false;
    /// True when the device backends compute the method's evaluation (sampledHydrostatics over the samples in use,
    /// kernels/samples.cl): a body of such a method may be batched on a device, others stay on the CPU.
    bool deviceBatched = false;
    BakeMethod bake = BakeMethod::ExactCoverage; ///< sampled methods: how texels become samples (design.md 1.1)
    int defaultTextureSize = 0;      ///< sampled methods: N when the settings give none; 0 for the others
    /// Prepare a shape once: bake what the evaluation reads and the dry mass properties.
    /// @throws std::invalid_argument when the mesh cannot be prepared (e.g. a texture too small: no samples)
    void (*prepare)(const TriangleMesh& mesh, const PrepareOptions& options, PreparedShape& out) = nullptr;
    /// Evaluate the hydrostatics of one pose (body → world), world frame, torque about water.torqueReference.
    HydrostaticsResult (*evaluate)(const MethodGeometry& geometry, const Eigen::Isometry3d& pose,
                                   const MethodWater& water) = nullptr;
    /// @name The automatic level of detail's model of the method (integrals/LevelOfDetail.h, design.md 8.2)
    ///@{
    /// True when errorBudget's pick for the Auto method considers this method (it is always considered when asked
    /// for by name).
    bool automatic = false;
    /// Worst submerged-volume error measured in flat water by `buoyancy bench` (docs/benchmarks speed_vs_error.csv,
    /// seven shapes × 15 poses), % of the body's volume, for an N × N texture (`textureSize`, one of
    /// kLodTextureSizes; 0 for a method without a texture). Before kLodSafetyFactor.
    double (*modelErrorPct)(int textureSize) = nullptr;
    /// Cost model, ns per body-substep (flat water, drag on) for a mesh of `triangles` triangles and an N × N
    /// texture; only the ratios between methods matter for the pick.
    double (*modelCostNs)(std::size_t triangles, int textureSize) = nullptr;
    ///@}
};

/// Every method, in the order of the enumeration (Auto excluded).
const std::vector<IntegrationMethod>& integrationMethods();

/// The entry of `method`; nullptr for Auto or a value that is no method.
const IntegrationMethod* findIntegrationMethod(BuoyancyMethod method);

/// The entry of a concrete method. @throws std::invalid_argument for Auto or a value that is no method
const IntegrationMethod& integrationMethod(BuoyancyMethod method);

}  // namespace buoyancy
