/// @file IntegrationMethod.cpp
/// The registry of integration methods (declared in IntegrationMethod.h): one entry per method, each with its
/// preparation and evaluation. A new method is an enumerator in BuoyancyMethod.h and an entry here (design.md 8.2).

#include <BulletBuoyancy/integrals/IntegrationMethod.h>

#include <BulletBuoyancy/atlas/UvLayout.h>
#include <BulletBuoyancy/bake/BakeSamples.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

/// Drag/shell samples for the methods without surface samples: each triangle split into n×n congruent
/// sub-triangles (n from its longest edge / targetEdge, 1..64), one sample per sub-triangle at its centroid with
/// area vector A_tri / n². A box's 12 triangles alone would leave whole rotation axes undamped.
SurfaceSamples faceSamples(const TriangleMesh& mesh, double targetEdge) {
    auto splits = [&](std::size_t t) {
        const Eigen::Vector3d& a = mesh.corner(t, 0);
        const Eigen::Vector3d& b = mesh.corner(t, 1);
        const Eigen::Vector3d& c = mesh.corner(t, 2);
        const double e = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
        return static_cast<int>(std::clamp(std::ceil(e / targetEdge), 1.0, 64.0));
    };
    // Keep the count moderate: at most ≈ 16384 samples beyond one per triangle.
    for (int pass = 0; pass < 20; ++pass) {
        std::size_t total = 0;
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t) total += std::size_t(splits(t)) * splits(t);
        if (total <= std::max<std::size_t>(16384, mesh.triangleCount())) break;
        targetEdge *= 1.5;
    }
    SurfaceSamples s;
    s.texture_size = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const Eigen::Vector3d& a = mesh.corner(t, 0);
        const Eigen::Vector3d& b = mesh.corner(t, 1);
        const Eigen::Vector3d& c = mesh.corner(t, 2);
        const int n = splits(t);
        const Eigen::Vector3d A = 0.5 * (b - a).cross(c - a) / double(n * n);
        const double area = A.norm();
        const Eigen::Vector3d du = (b - a) / double(n), dv = (c - a) / double(n);
        for (int i = 0; i < n; ++i) {
            for (int j = 0; i + j < n; ++j) {
                // Upward sub-triangle (i,j),(i+1,j),(i,j+1): centroid at (i+1/3, j+1/3).
                Eigen::Vector3d p = a + (i + 1.0 / 3.0) * du + (j + 1.0 / 3.0) * dv;
                s.push(p.x(), p.y(), p.z(), A.x(), A.y(), A.z(), area, 0u, static_cast<std::uint32_t>(t));
                if (i + j < n - 1) {
                    // Downward sub-triangle (i+1,j),(i,j+1),(i+1,j+1): centroid at (i+2/3, j+2/3).
                    p = a + (i + 2.0 / 3.0) * du + (j + 2.0 / 3.0) * dv;
                    s.push(p.x(), p.y(), p.z(), A.x(), A.y(), A.z(), area, 0u, static_cast<std::uint32_t>(t));
                }
            }
        }
    }
    return s;
}

// ---- Exact mesh: clip the triangles (design.md 2.4, 2.5) ----------------------------------------------------------

void prepareExactMesh(const TriangleMesh& mesh, const PrepareOptions& options, PreparedShape& out) {
    out.faceSamples = faceSamples(mesh, std::max(2.0 * options.boundsRadius / 16.0, 1e-9));
    out.unitSolid = polyhedronMassProperties(mesh, 1.0);
    out.tree = buildMeshMomentTree(mesh);  // closed-form wet nodes (design.md 2.5)
    // Shell from point masses on the sub-triangles (their own small inertia neglected).
    out.unitShell = shellMassProperties(out.faceSamples, 1.0, 1.0);
}

HydrostaticsResult evaluateExactMesh(const MethodGeometry& geometry, const Eigen::Isometry3d& pose,
                                     const MethodWater& water) {
    return treeHydrostatics(geometry.tree, geometry.mesh, pose, water.surface, water.time, water.fluidDensity,
                            water.gravity, water.torqueReference, water.patch);
}

// ---- Sampled: surface samples baked through a texture (design.md 1, 2.2–2.3) -------------------------------------

void prepareSampled(const TriangleMesh& mesh, BakeMethod bake, const PrepareOptions& options, PreparedShape& out) {
    const UvLayout layout = chooseUvLayout(mesh, options.textureSize, options.preferModelUvs);
    out.uvGenerated = layout.generated;
    out.uvProblems = layout.reasons;
    out.samples = bakeSurfaceSamples(mesh, layout.corner_uvs, options.textureSize, bake);
    if (out.samples.size() == 0) throw std::invalid_argument("mesh: baking produced no samples");
    // Mass properties from the same samples as the buoyancy (design.md 2.1), so ρ_body = ρ_w is neutral.
    out.unitSolid = solidMassProperties(out.samples, 1.0);
    out.unitShell = shellMassProperties(out.samples, 1.0, 1.0);
}

void prepareTexelCentre(const TriangleMesh& mesh, const PrepareOptions& options, PreparedShape& out) {
    prepareSampled(mesh, BakeMethod::TexelCentre, options, out);
}

void prepareExactCoverage(const TriangleMesh& mesh, const PrepareOptions& options, PreparedShape& out) {
    prepareSampled(mesh, BakeMethod::ExactCoverage, options, out);
}

HydrostaticsResult evaluateSampled(const MethodGeometry& geometry, const Eigen::Isometry3d& pose,
                                   const MethodWater& water) {
    if (!water.workspace) throw std::invalid_argument("sampled hydrostatics: no workspace");
    return sampledHydrostatics(geometry.samples, pose, water.surface, water.time, water.fluidDensity, water.gravity,
                               water.torqueReference, *water.workspace, water.cache, water.patch);
}

// ---- The automatic level of detail's models (LevelOfDetail.h) ----------------------------------------------------

/// Worst submerged-volume error (% of the body's volume) measured by `buoyancy bench` (docs/benchmarks,
/// speed_vs_error.csv: box, sphere, torus, boat, duck, duck-x4, torus-fine × 15 poses, flat water), per N.
struct MeasuredError {
    int n;
    double exactCoverage;
    double texelCentre;
};
constexpr MeasuredError kMeasured[] = {
    {32, 1.556, 108.7}, {64, 0.2107, 14.44}, {128, 0.02119, 7.962},
    {256, 0.005343, 1.29}, {512, 0.001337, 0.414}, {1024, 0.000328, 0.4058},
};
/// The measured row of N (the largest measured N not above it).
const MeasuredError& measuredAt(int n) {
    const MeasuredError* row = &kMeasured[0];
    for (const MeasuredError& m : kMeasured)
        if (m.n <= n) row = &m;
    return *row;
}
double exactCoverageErrorPct(int n) { return measuredAt(n).exactCoverage; }
double texelCentreErrorPct(int n) { return measuredAt(n).texelCentre; }
/// Exact-mesh is exact to rounding in flat water (measured ≤ 6e-12 %).
double exactMeshErrorPct(int) { return 1e-10; }
/// Cost model, ns per body-substep (one btBuoyancyAction substep, flat water, drag on; docs/benchmarks run of
/// 2026-11-22 on a loaded 2-core machine): ≈ 15 ns per clipped triangle (sphere 3968: 60 µs, torus 4096: 71 µs)
/// and ≈ 13 ns per surface sample at 64²–256² (more above: cache misses), and the samples an N² texture yields
/// (0.49–0.93 N² measured; the middle is used).
constexpr double kNsPerTriangle = 15.0;
constexpr double kNsPerSample = 13.0;
constexpr double kSamplesPerTexel = 0.7;
double exactMeshCostNs(std::size_t triangles, int) { return kNsPerTriangle * double(triangles); }
double sampledCostNs(std::size_t, int n) { return kNsPerSample * kSamplesPerTexel * double(n) * double(n); }

IntegrationMethod entry(BuoyancyMethod method, const char* name, bool sampled, bool deviceBatched, BakeMethod bake,
                        int textureSize,
                        void (*prepare)(const TriangleMesh&, const PrepareOptions&, PreparedShape&),
                        HydrostaticsResult (*evaluate)(const MethodGeometry&, const Eigen::Isometry3d&,
                                                       const MethodWater&)) {
    IntegrationMethod m;
    m.method = method;
    m.name = name;
    m.sampled = sampled;
    m.deviceBatched = deviceBatched;
    m.bake = bake;
    m.defaultTextureSize = textureSize;
    m.prepare = prepare;
    m.evaluate = evaluate;
    return m;
}

/// `m` with the level of detail's models.
IntegrationMethod withModel(IntegrationMethod m, bool automatic, double (*errorPct)(int),
                            double (*costNs)(std::size_t, int)) {
    m.automatic = automatic;
    m.modelErrorPct = errorPct;
    m.modelCostNs = costNs;
    return m;
}

}  // namespace

const std::vector<IntegrationMethod>& integrationMethods() {
    // Default texture sizes: 512 for texel-centre (the paper's own smallest size); 128 for exact-coverage, which
    // meets the default accuracy goals (docs/accuracy.md) on the shapes and models we test.
    static const std::vector<IntegrationMethod> methods = {
        //    method                        name              sampled device  bake                       N
        withModel(entry(BuoyancyMethod::TexelCentre,   "texel-centre",   true,   true,   BakeMethod::TexelCentre,   512,
                        prepareTexelCentre, evaluateSampled),
                  false, texelCentreErrorPct, sampledCostNs),
        withModel(entry(BuoyancyMethod::ExactCoverage, "exact-coverage", true,   true,   BakeMethod::ExactCoverage, 128,
                        prepareExactCoverage, evaluateSampled),
                  true, exactCoverageErrorPct, sampledCostNs),
        withModel(entry(BuoyancyMethod::ExactMesh,     "exact-mesh",     false,  false,  BakeMethod::ExactCoverage, 0,
                        prepareExactMesh, evaluateExactMesh),
                  true, exactMeshErrorPct, exactMeshCostNs),
    };
    return methods;
}

const IntegrationMethod* findIntegrationMethod(BuoyancyMethod method) {
    for (const IntegrationMethod& m : integrationMethods())
        if (m.method == method) return &m;
    return nullptr;
}

const IntegrationMethod& integrationMethod(BuoyancyMethod method) {
    if (const IntegrationMethod* m = findIntegrationMethod(method)) return *m;
    throw std::invalid_argument(method == BuoyancyMethod::Auto
                                    ? "integration method: Auto must be resolved first (resolveMethod)"
                                    : "integration method: not a BuoyancyMethod value (" +
                                          std::to_string(int(method)) + ")");
}

}  // namespace buoyancy
