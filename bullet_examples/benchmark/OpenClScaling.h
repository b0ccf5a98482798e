#pragma once
/// @file OpenClScaling.h
/// The OpenCL benchmark rows: the OpenCL backend (PoCL on this machine) next to the CPU path for 1, 10, 100 and
/// 1,000 bodies of one sampled model in a Gerstner sea at 240 substeps/s, every action in the Bullet world (the
/// device computes all bodies in one launch set per substep). Written to docs/benchmarks/opencl_scaling.csv.

#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace buoyancy::bench {

/// What to run.
struct OpenClScalingOptions {
    std::vector<int> bodies{1, 10, 100, 1000}; ///< body counts
    double simSeconds = 0.25;                  ///< simulated time per run at most, s (after two untimed substeps)
    double maxBodySubsteps = 4000;             ///< at most this many body-substeps per run (cost per body-substep)
    int minSubsteps = 4;                       ///< at least this many substeps per run
    int textureSize = 64;                      ///< exact-coverage texture of the model (the device runs sampled methods)
};

/// One row of opencl_scaling.csv.
struct OpenClScalingRow {
    std::string backend;        ///< "cpu" (water patch on: the library default), "cpu-exact" (exact water queries, the
                                ///< device's work), "opencl-double" or "opencl-float"
    std::string device;         ///< OpenCL device name (empty for the CPU)
    std::string model;          ///< model id
    int samples = 0;            ///< hydrostatic samples per body
    int bodies = 0;             ///< body count
    long substeps = 0;          ///< substeps timed
    double wallSeconds = 0;     ///< wall-clock time of stepSimulation (Bullet + buoyancy), s
    double msPerSubstep = 0;    ///< wall / substeps, ms
    double nsPerBodySubstep = 0; ///< wall / (bodies × substeps), ns
    double realtimeFactor = 0;  ///< simulated / wall time
};

/// Run every body count on the CPU and on the OpenCL device (double, then float when the device has fp64).
/// Rows of a backend that is not available are left out (the log says why).
std::vector<OpenClScalingRow> runOpenClScaling(const TriangleMesh& mesh, const std::string& model,
                                               const OpenClScalingOptions& options, std::ostream& log);

/// Write opencl_scaling.csv. @throws std::runtime_error when the file cannot be written
void writeOpenClScalingCsv(const std::string& path, const std::vector<OpenClScalingRow>& rows);

}  // namespace buoyancy::bench
