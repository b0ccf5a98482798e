// The default exact-mesh evaluation on waves (treeHydrostatics with the wave patch the body action builds) against the
// independent divergence-theorem reference (tests/oracles/WaveOracle.h) on low-poly shapes in a long and a short sea,
// and against the closed form of a box under one Airy wave. Bar (design.md 2.5): worst submerged-volume error ≤ 0.1 %
// of the body's volume, centre of buoyancy as a first-moment error |ΔC_B|·V_sub ≤ 1e-3 · V · D (D the body's diagonal).
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/MeshMomentTree.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btGridWaterSurface.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>
#include <BulletBuoyancy/water/btWaterSurface.h>
#include "oracles/OracleMeshes.h"
#include "oracles/PolyhedralOracle.h"
#include "oracles/WaveOracle.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <chrono>
#include <random>
#include <time.h>

using namespace buoyancy;
using namespace buoyancy_test;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kRho = 1000, kG = 9.81;

/// The long sea: four Gerstner waves, wavelengths 10–60 m, amplitudes 0.2–1 m, Σ Q A k ≈ 0.17.
std::vector<btGerstnerWave> swell() {
    return {{1.0, 60.0, 1.0, 0.0, 0.5, 0.0},
            {0.6, 35.0, 0.8, 0.6, 0.5, 1.3},
            {0.35, 20.0, -0.3, 1.0, 0.5, 2.1},
            {0.2, 10.0, 0.6, -0.8, 0.5, 0.4}};
}
/// A short steep sea: wavelengths 4–10 m, Σ Q A k ≈ 0.48.
std::vector<btGerstnerWave> chop() {
    return {{0.25, 10.0, 1.0, 0.0, 0.8, 0.0},
            {0.18, 7.0, 0.6, 0.8, 0.8, 1.1},
            {0.12, 5.0, -0.5, 0.87, 0.8, 2.3},
            {0.08, 4.0, 0.9, -0.44, 0.8, 0.7}};
}

struct Shape {
    const char* name;
    OracleMesh mesh;
};
std::vector<Shape> lowPolyShapes() {
    return {{"box-12", oracleBox(4.0, 1.0, 1.5)},
            {"cylinder-14", oracleCylinder(0.6, 3.0, 14)},
            {"ellipsoid-64", [] {
                 OracleMesh m = oracleSphere(1.0, 8, 5);
                 for (auto& v : m.verts) v = Eigen::Vector3d(2.0 * v.x(), 0.6 * v.y(), 0.8 * v.z());
                 return m;
             }()}};
}

/// The evaluation the body action makes by default for a mesh at this pose: the moment tree, with the wave patch
/// the action would build (btBuoyancyWaterPatchNodes; none when it would have as many nodes as the mesh has vertices
/// plus drag clusters).
HydrostaticsResult defaultEvaluation(const MeshMomentTree& tree, const TriangleMesh& mesh, const Eigen::Isometry3d& pose,
                                     const btWaterSurface& water, double t, const Eigen::Vector3d& com,
                                     double radius, WaterPatch& patch, btWaterQueryCache& cache) {
    const btBuoyancySettings settings;
    const std::size_t nodes = std::size_t(btBuoyancyWaterPatchNodes(settings, radius, water.shortestWavelength()));
    // The hydrostatics use the patch only when it has fewer nodes than the mesh has vertices; drag probes do not
    // count (the action decides for its drag apart).
    const std::size_t points = mesh.vertices.size();
    const Eigen::Vector3d c = pose * Eigen::Vector3d::Zero();
    const WaterPatch* p = nullptr;
    // The action builds a patch only over Gerstner water (whose query is an iterative solve).
    if (dynamic_cast<const btGerstnerWaterSurface*>(&water) && nodes * nodes < points) {
        patch.build(water, c.x(), c.z(), radius, t, int(nodes), cache);
        p = &patch;
    }
    return treeHydrostatics(tree, mesh, pose, water, t, kRho, kG, com, p);
}

struct Worst {
    double volumePct = 0, firstMoment = 0, forcePct = 0;
    double planeVolumePct = 0;  ///< the plane through each triangle's corner heights (vertexHydrostatics), for scale
};

/// Oracle settings for a surface: Gerstner sub-triangles ≤ λ_min / 40; water bilinear over a lattice: clipped to its
/// cells, sub-triangles ≤ a tenth of the spacing.
WaveOracleOptions oracleOptionsFor(const btWaterSurface& water, double t, double D) {
    WaveOracleOptions o;
    btWaterLattice lattice;
    if (water.bilinearLattice(t, lattice)) {
        o.kinkSpacing = lattice.spacingX;
        o.kinkOriginX = lattice.originX;
        o.kinkOriginZ = lattice.originZ;
        o.maxEdge = 0.1 * lattice.spacingX;
        o.gradientStep = 1e-6;  // central differences inside one cell
    } else {
        o.maxEdge = water.shortestWavelength() > 0 ? water.shortestWavelength() / 40.0 : 0.05;
    }
    o.maxEdge = std::max(o.maxEdge, 0.01 * D);
    return o;
}

Worst measure(const Shape& s, const btWaterSurface& water, int poses, unsigned seed) {
    const TriangleMesh mesh = toTriangleMesh(s.mesh);
    const MeshMomentTree tree = buildMeshMomentTree(mesh);
    const OracleMoments dry = oracleDryMoments(s.mesh.verts, s.mesh.tris);
    Eigen::Vector3d lo = s.mesh.verts[0], hi = lo;
    for (const auto& v : s.mesh.verts) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
    }
    const double D = (hi - lo).norm(), radius = 0.5 * D, height = hi.y() - lo.y();
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    WaterPatch patch;
    btWaterQueryCache cache;
    Worst w;
    for (int i = 0; i < poses; ++i) {
        const double t = 10.0 + 20.0 * (U(rng) + 1.0);
        const double x = 30.0 * U(rng), z = 30.0 * U(rng);
        const double eta = water.height(x, z, t);
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.linear() = (Eigen::AngleAxisd(kPi * U(rng), Eigen::Vector3d::UnitY()) *
                         Eigen::AngleAxisd(0.5 * U(rng), Eigen::Vector3d(1, 0, 0.3 * U(rng)).normalized()))
                            .toRotationMatrix();
        pose.translation() = Eigen::Vector3d(x, eta + 0.3 * height * U(rng), z);
        const Eigen::Vector3d com = pose * dry.centroid;
        const HydrostaticsResult h =
            defaultEvaluation(tree, mesh, pose, water, t, com, radius, patch, cache);
        double hMin = 0, hMax = 0;
        water.heightBounds(x - D, z - D, x + D, z + D, t, hMin, hMax);
        WaveOracleOptions o = oracleOptionsFor(water, t, D);
        o.waterMax = hMax;
        const WaveOracleResult ref =
            waveOracle(oraclePose(s.mesh.verts, pose), s.mesh.tris, [&](double qx, double qz) { return water.height(qx, qz, t); },
                       com, o);
        w.volumePct = std::max(w.volumePct, 100.0 * std::abs(h.submerged_volume - ref.volume) / dry.volume);
        const HydrostaticsResult plane = vertexHydrostatics(tree.shares, pose, water, t, kRho, kG, com, nullptr);
        w.planeVolumePct = std::max(w.planeVolumePct, 100.0 * std::abs(plane.submerged_volume - ref.volume) / dry.volume);
        // First moments about the centre of mass (about a point far away they would grow with the distance).
        const Eigen::Vector3d first = (h.centre_of_buoyancy - com) * h.submerged_volume;
        const Eigen::Vector3d firstRef = ref.firstMoment - com * ref.volume;
        w.firstMoment = std::max(w.firstMoment, (first - firstRef).norm() / (dry.volume * D));
        w.forcePct = std::max(w.forcePct, 100.0 * (h.force / (kRho * kG) - ref.force).norm() / dry.volume);
    }
    return w;
}

}  // namespace

TEST_CASE("waves: the default evaluation of low-poly shapes against the divergence-theorem reference",
          "[waves][accuracy][slow]") {
    const std::pair<const char*, std::vector<btGerstnerWave>> seas[] = {{"swell", swell()}, {"chop", chop()}};
    for (const Shape& s : lowPolyShapes())
        for (const auto& sea : seas)
            {
                const Worst w = measure(s, btGerstnerWaterSurface(sea.second), 10, 7u);
                std::printf("  %-13s %-6s  volume %.4f %%  first moment %.2e V·D  force %.4f %% of ρgV\n", s.name,
                            sea.first, w.volumePct, w.firstMoment, w.forcePct);
                INFO(s.name << " in " << sea.first);
                CHECK(w.volumePct <= 0.1);
                CHECK(w.firstMoment <= 1e-3);
                CHECK(w.forcePct <= 0.1);
            }
}

namespace {

/// A user's height grid: 64 × 64 samples 1 m apart over [−32, 32)², periodic, from three waves (wavelengths 8–32 m,
/// amplitudes 0.15–0.6 m) plus uniform noise of ±0.05 m, so every cell has its own bilinear twist and slope kinks.
btGridWaterSurface userGrid() {
    const int n = 64;
    std::vector<double> h(std::size_t(n * n));
    std::mt19937 rng(11u);
    std::uniform_real_distribution<double> noise(-0.05, 0.05);
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const double x = -32.0 + i, z = -32.0 + j;
            h[std::size_t(j * n + i)] = 0.6 * std::cos(2 * kPi * x / 32.0) + 0.3 * std::sin(2 * kPi * (x + z) / 16.0 + 0.4) +
                                        0.15 * std::cos(2 * kPi * z / 8.0 + 1.1) + noise(rng);
        }
    return btGridWaterSurface(n, n, 1.0, -32.0, -32.0, h, true);
}

/// An FFT ocean as the example scenes build it (64 samples over 64 m, wind 9 m/s), without choppiness: the height is
/// the bilinear lookup of its samples.
btFftOceanSurface fftOcean(double choppiness) {
    btFftOceanSettings o;
    o.resolution = 64;
    o.patchSize = 64.0;
    o.windSpeed = 9.0;
    o.windDirectionX = 1.0;
    o.windDirectionZ = 0.4;
    o.choppiness = choppiness;
    o.seed = 3;
    return btFftOceanSurface(o);
}

}  // namespace

TEST_CASE("waves: the default evaluation on grid and FFT water against the bilinear reference",
          "[waves][accuracy][slow]") {
    const btGridWaterSurface grid = userGrid();
    const btFftOceanSurface fft = fftOcean(0.0);
    const btFftOceanSurface choppy = fftOcean(0.4);
    // The interactive surface after a few bodies' displacements have spread for 3 s (0.5 m cells).
    btInteractiveWaterSurface interactive(64.0, 64.0, 128, 2.0, 0.1);
    for (int k = 0; k < 6; ++k) interactive.addVolumeChange(4.0, -20.0 + 8.0 * k, 10.0 - 4.0 * k, 1.5);
    interactive.step(3.0);
    const std::pair<const char*, const btWaterSurface*> waters[] = {
        {"grid", &grid}, {"fft", &fft}, {"fft-choppy", &choppy}, {"interactive", &interactive}};
    for (const Shape& s : lowPolyShapes())
        for (const auto& water : waters) {
            const Worst w = measure(s, *water.second, 8, 5u);
            std::printf("  %-13s %-11s volume %.5f %%  first moment %.2e V·D  force %.5f %% of ρgV  (plane per triangle: "
                        "volume %.3f %%)\n",
                        s.name, water.first, w.volumePct, w.firstMoment, w.forcePct, w.planeVolumePct);
            INFO(s.name << " in " << water.first);
            CHECK(w.volumePct <= 0.1);
            CHECK(w.firstMoment <= 1e-3);
            CHECK(w.forcePct <= 0.1);
        }
}

TEST_CASE("waves: a box under grid water against the closed form per cell", "[waves][accuracy]") {
    // Axis-aligned 4 × 1.5 × 1.5 m box (12 triangles), bottom wet and top dry everywhere: V = Σ over the cells its
    // footprint meets of area × (η at the piece's centre − y_b) (tests/oracles/WaveOracle.h).
    const btGridWaterSurface grid = userGrid();
    const OracleMesh box = oracleBox(4.0, 1.5, 1.5);
    const TriangleMesh mesh = toTriangleMesh(box);
    const MeshMomentTree tree = buildMeshMomentTree(mesh);
    std::mt19937 rng(3u);
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    double worst = 0;
    for (int i = 0; i < 20; ++i) {
        const double x = 20.0 * U(rng), z = 20.0 * U(rng);
        const Eigen::Vector3d c(x, grid.height(x, z, 0.0) + 0.1 * U(rng), z);
        double lo = 0, hi = 0;
        grid.heightBounds(x - 2, z - 0.75, x + 2, z + 0.75, 0.0, lo, hi);
        if (c.y() - 0.75 >= lo || c.y() + 0.75 <= hi) continue;  // the closed form needs the bottom wet, the top dry
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation() = c;
        const HydrostaticsResult h = treeHydrostatics(tree, mesh, pose, grid, 0.0, kRho, kG, c, nullptr);
        const double ref = bilinearBoxVolume([&](double qx, double qz) { return grid.height(qx, qz, 0.0); }, -32.0, -32.0,
                                             1.0, x - 2.0, x + 2.0, z - 0.75, z + 0.75, c.y() - 0.75);
        worst = std::max(worst, std::abs(h.submerged_volume - ref) / 9.0);
    }
    INFO("worst volume error " << worst << " of V");
    CHECK(worst <= 1e-9);
}

TEST_CASE("waves: timing of the default evaluation (manual)", "[.timing]") {
    const std::pair<const char*, std::vector<btGerstnerWave>> seas[] = {{"swell", swell()}, {"chop", chop()}};
    for (const Shape& s : lowPolyShapes())
        for (const auto& sea : seas) {
            const btGerstnerWaterSurface water(sea.second);
            const TriangleMesh mesh = toTriangleMesh(s.mesh);
            const MeshMomentTree tree = buildMeshMomentTree(mesh);
            WaterPatch patch;
            btWaterQueryCache cache;
            const int n = 2000;
            double sink = 0;
            const auto t0 = std::chrono::steady_clock::now();
            for (int i = 0; i < n; ++i) {
                const double t = 10 + 0.01 * i, x = 3.0, z = 1.0;
                Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
                pose.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 0, 0.2).normalized()).toRotationMatrix();
                pose.translation() = Eigen::Vector3d(x, water.height(x, z, t), z);
                sink += defaultEvaluation(tree, mesh, pose, water, t, pose.translation(), 3.0, patch, cache).submerged_volume;
            }
            const double us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / n;
            const auto t1 = std::chrono::steady_clock::now();
            for (int i = 0; i < n; ++i) sink += water.height(3.0 + 1e-3 * i, 1.0, 10 + 0.01 * i);
            const double usQ = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t1).count() / n;
            std::printf("  %-13s %-6s  %.2f us per evaluation (one height query %.3f us) %g\n", s.name, sea.first, us, usQ, sink * 0);
        }
}

/// CPU time of the calling thread, s (timings on a shared machine: the wall clock counts other processes' time).
double threadCpuSeconds() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

TEST_CASE("waves: timing on grid and FFT water, against the plane per triangle (manual)", "[.timing]") {
    const btGridWaterSurface grid = userGrid();
    const btFftOceanSurface fft = fftOcean(0.0), choppy = fftOcean(0.4);
    const std::pair<const char*, const btWaterSurface*> waters[] = {{"grid", &grid}, {"fft", &fft}, {"fft-choppy", &choppy}};
    std::vector<Shape> shapes = lowPolyShapes();
    shapes.push_back({"sphere-960", oracleSphere(1.0, 24, 20)});
    for (const Shape& s : shapes)
        for (const auto& water : waters) {
            const TriangleMesh mesh = toTriangleMesh(s.mesh);
            const MeshMomentTree tree = buildMeshMomentTree(mesh);
            const int n = 500;
            double sink = 0;
            // One time for every evaluation: an FFT ocean synthesises its field once per time value (once per substep
            // for a whole world), which is not the cost of one body.
            const auto pose = [&](int i) {
                const double t = 10, x = 3.0 + 0.01 * i, z = 1.0;
                Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
                p.linear() = Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 0, 0.2).normalized()).toRotationMatrix();
                p.translation() = Eigen::Vector3d(x, water.second->height(x, z, t), z);
                return p;
            };
            const double t0 = threadCpuSeconds();
            for (int i = 0; i < n; ++i) {
                const Eigen::Isometry3d p = pose(i);
                sink += treeHydrostatics(tree, mesh, p, *water.second, 10, kRho, kG, p.translation(), nullptr)
                            .submerged_volume;
            }
            const double us = (threadCpuSeconds() - t0) * 1e6 / n;
            const double t1 = threadCpuSeconds();
            for (int i = 0; i < n; ++i) {
                const Eigen::Isometry3d p = pose(i);
                sink += vertexHydrostatics(tree.shares, p, *water.second, 10, kRho, kG, p.translation(), nullptr)
                            .submerged_volume;
            }
            const double usPlane =
                (threadCpuSeconds() - t1) * 1e6 / n;
            std::printf("  %-13s %-10s  default %.2f us, plane per triangle %.2f us %g\n", s.name, water.first, us, usPlane,
                        sink * 0);
        }
}
