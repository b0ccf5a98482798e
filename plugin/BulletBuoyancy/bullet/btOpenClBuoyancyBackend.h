#pragma once
/// @file btOpenClBuoyancyBackend.h
/// The OpenCL backend (docs/opencl.md): every sampled body of a btBuoyancyWorld in one launch set per
/// substep (samples of all bodies in one buffer, per-body reductions on the device), waves evaluated on the
/// device (flat, Gerstner; grid and sampled-FFT heights as a buffer), deformable bodies re-baked on the device.
/// Kernels (kernels/*.cl + geometry/SampleFormulas.h, embedded in the library) are built at run time; the
/// scalar is double on devices with cl_khr_fp64, else float.
///
/// Usually selected with btBuoyancyWorld::setCompute(btBuoyancyCompute::OpenCl); create() gives control over
/// device and precision. Without an OpenCL platform or device, or in a library built without OpenCL,
/// create() returns nullptr with the reason: never an exception for that.

#include <BulletBuoyancy/bake/DeformableRebake.h>
#include <BulletBuoyancy/bullet/btBuoyancyDeviceBackend.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class btBuoyancyWorld;

/// Options of btOpenClBuoyancyBackend.
struct btOpenClOptions {
    /// Scalar on the device: Auto = double when the device has cl_khr_fp64, else float.
    enum class Precision { Auto, Double, Float };
    Precision precision = Precision::Auto;
    /// Device by position in the list of every device of every platform (as `clinfo -l`); −1 = the first GPU,
    /// else the first device. The environment variable BULLET_BUOYANCY_OPENCL_DEVICE (a number) overrides −1.
    int deviceIndex = -1;
    /// Samples per work-group tile (≥ 64); a body's samples are split into tiles of this size. Typical 1024.
    int tileSamples = 1024;
    /// Work-group size (a power of two, 1..256); clamped to what the device and kernels allow. Typical 64.
    int workGroupSize = 64;
};

/// OpenCL implementation of btBuoyancyDeviceBackend.
class btOpenClBuoyancyBackend : public btBuoyancyDeviceBackend {
public:
    /// Pick a device, build the kernels (the build log is in the message of a failure).
    /// @param world    the world whose registered actions are batched (not owned; must outlive the backend)
    /// @param message  optional: on failure the reason (no platform, no device, no fp64 when Double was asked,
    ///                 build log); on success describe()
    /// @return the backend, or nullptr (message says why). Never throws for a missing or failing OpenCL.
    static std::unique_ptr<btOpenClBuoyancyBackend> create(btBuoyancyWorld& world,
                                                           const btOpenClOptions& options = btOpenClOptions(),
                                                           std::string* message = nullptr);
    /// True when the library was built with OpenCL (BULLET_BUOYANCY_OPENCL found it).
    static bool compiledIn();

    ~btOpenClBuoyancyBackend() override;
    btOpenClBuoyancyBackend(const btOpenClBuoyancyBackend&) = delete;
    btOpenClBuoyancyBackend& operator=(const btOpenClBuoyancyBackend&) = delete;

    void beginSubstep(double dt) override;
    bool hydrostatics(const btBuoyancyDeviceBody& body, const Eigen::Isometry3d& pose, const Eigen::Vector3d& com,
                      buoyancy::HydrostaticsResult& out) override;
    bool drag(const btBuoyancyDeviceBody& body, const Eigen::Vector3d& com, const Eigen::Vector3d& v,
              const Eigen::Vector3d& w, Eigen::Vector3d& force, Eigen::Vector3d& torque,
              Eigen::Vector3d& meanWaterVelocity, double& linearDampingPower) override;
    std::string describe() const override;

    /// Pause the backend (false: it declines every body, so the world runs on the CPU path) or resume it.
    /// For A/B comparisons and benchmarks; a new backend is enabled.
    void setEnabled(bool enabled);
    bool isEnabled() const;
    /// True when the device computes in double (cl_khr_fp64), false for float.
    bool usesDouble() const;
    /// Device name.
    std::string deviceName() const;
    /// Why the last batch left bodies to the CPU (e.g. "water surface type not supported on the device: ..."),
    /// empty when every eligible body was computed on the device.
    const std::string& lastFallbackReason() const;
    /// Counters since creation: batches (hydrostatic launch sets), bodies computed on the device, answers given,
    /// answers declined (the action computed them on the CPU).
    struct Stats {
        std::uint64_t hydroBatches = 0, dragBatches = 0, bodiesComputed = 0, hydroAnswers = 0, dragAnswers = 0,
                      declined = 0, rebakes = 0;
    };
    const Stats& stats() const;

    /// Re-bake `map` for `vertices` on the device and read the samples back (tests/opencl compares it with the CPU
    /// re-bake). @throws std::invalid_argument for a wrong vertex count, std::runtime_error for an OpenCL error
    void rebakeOnDevice(const buoyancy::RebakeMap& map, const std::vector<Eigen::Vector3d>& vertices,
                        buoyancy::SurfaceSamples& out);

private:
    struct Impl;
    explicit btOpenClBuoyancyBackend(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> m_impl;
};
