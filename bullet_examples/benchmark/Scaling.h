#pragma once
/// @file Scaling.h
/// The scaling run (the 1,000-boat real-time figure): N bodies of one model in a 4-wave Gerstner sea at 240 substeps/s,
/// colliding through their convex hulls, spread four body lengths apart. Two drivers: `world` — exactly as a user writes
/// it: bodies and one btBuoyancyAction per body added to the Bullet world, btBuoyancyWorld::setThreads, stepSimulation
/// (the library evaluates the bodies in parallel itself); `bench` — the earlier benchmark-private driver, one Bullet
/// action running the per-body actions across OpenMP threads, kept for comparison. Debian's Bullet has no task
/// scheduler, so Bullet's own step stays on one thread in both.

#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace buoyancy::bench {

/// What to run.
struct ScalingOptions {
    std::vector<int> bodies{1, 10, 100, 1000}; ///< body counts
    std::vector<int> threads{1, 2};            ///< thread counts (btBuoyancyWorld::setThreads; OpenMP for `bench`)
    /// Drivers: "world" (the public API) and/or "bench" (the benchmark-private OpenMP action, for comparison).
    std::vector<std::string> drivers{"world"};
    /// Timed windows per row (each simSeconds long, one after the other after one warm-up): the row's real-time
    /// factor is their median, its times those of the median window.
    int windows = 1;
    double simSeconds = 1.0;                   ///< simulated time per run at most, s (after the warm-up)
    /// Simulated untimed first, s: the bodies settle into the waves (the heave of the benchmark's boat decays over
    /// ≈ 2–3 s; in the first seconds the temporal level of detail predicts less: 52–60 % of the substeps at 1–2 s,
    /// 68 % at 5–7 s for 1,000 boats).
    double warmupSeconds = 4.0;
    /// At most this many body-substeps are timed per run (the substep count is cut for many bodies, never
    /// below minSubsteps): the cost per body-substep is what is measured.
    double maxBodySubsteps = 8000;
    int minSubsteps = 4;                       ///< at least this many substeps per run
    int substepsPerSecond = 240;               ///< fixed substep rate
    btBuoyancySettings settings;               ///< buoyancy settings of every body (default: the library's)
    std::string variant;                       ///< label of `settings` in the CSV (empty: the defaults)
    /// The water over each triangle as the plane through its corners' heights (the exact-mesh model on waves before the
    /// curved-water default): the same sea, declaring no third-derivative scale. For comparison rows only.
    bool planeWater = false;
};

/// One row of scaling.csv.
struct ScalingRow {
    std::string model;            ///< model id
    std::size_t triangles = 0;    ///< triangles of the model
    std::string method;           ///< the resolved default method (and N)
    std::string variant;          ///< ScalingOptions::variant (empty: default settings)
    std::string driver;           ///< "world" (public API) or "bench" (benchmark-private OpenMP action)
    int bodies = 0;               ///< body count
    int threads = 0;              ///< threads for buoyancy
    long substeps = 0;            ///< substeps timed
    double simSeconds = 0;        ///< simulated time, s
    double wallSeconds = 0;       ///< wall-clock time of stepSimulation, s
    double buoyancySeconds = 0;   ///< of which in the buoyancy actions, s
    double realtimeFactor = 0;    ///< simSeconds / wallSeconds (≥ 1: real time); the median over the windows
    int windows = 1;              ///< timed windows the median is over
    double realtimeFactorMin = 0; ///< the lowest of the windows
    double realtimeFactorMax = 0; ///< the highest of the windows
    double nsPerBodySubstepTotal = 0;    ///< wall / (bodies × substeps), ns
    double nsPerBodySubstepBuoyancy = 0; ///< buoyancy wall / (bodies × substeps), ns
    long contacts = 0;            ///< contact manifolds with points, summed over substeps
    /// Share of the median window's body-substeps whose hydrostatics the temporal level of detail predicted (0..1;
    /// −1 for the `bench` driver, which does not count them)
    double predictedShare = -1;
    double loadAverage = -1;      ///< the machine's 1-minute load average at the row's end (−1: unknown)
};

/// The scaling sea: four Gerstner waves, amplitudes 1, 0.6, 0.35, 0.2 m, wavelengths 60, 35, 20, 10 m.
std::vector<btGerstnerWave> p3Sea();

/// Height of the mesh origin above flat water at which the unrotated mesh floats (V_sub = densityRatio · V, volume its
/// volume, m³), m, found by bisection on the exact clip: the scaling bodies start near equilibrium, so the timed second
/// is not their first plunge.
double floatingHeight(const TriangleMesh& mesh, double volume, double densityRatio);

/// True when the benchmark was built with OpenMP (threads > 1 possible).
bool scalingHasOpenMP();

/// Run every (bodies, threads) pair with the model at the library's default settings, density 500 kg/m³.
std::vector<ScalingRow> runScaling(const TriangleMesh& mesh, const std::string& model, const ScalingOptions& options,
                                   std::ostream& log);

/// Where a body-substep of the scaling run goes (Markdown lines): the cost of one height and one velocity
/// query of the run's Gerstner sea (batch of 16384 points), and how many of each the model's default
/// configuration makes per substep (mesh vertices or samples for the hydrostatics, drag samples for drag).
std::string scalingBreakdownMarkdown(const TriangleMesh& mesh, std::ostream& log);

/// Write scaling.csv. @throws std::runtime_error when the file cannot be written
void writeScalingCsv(const std::string& path, const std::vector<ScalingRow>& rows);

}  // namespace buoyancy::bench
