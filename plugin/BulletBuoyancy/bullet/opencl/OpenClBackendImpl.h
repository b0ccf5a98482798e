#pragma once
/// @file OpenClBackendImpl.h
/// Internal to the OpenCL backend (not installed): the host-side state behind btOpenClBuoyancyBackend, shared by its
/// files, one per job:
/// - OpenClTransfers.cpp: uploads and reads in the device's scalar (float or double);
/// - OpenClWaterPacking.cpp: the water's parameters for kernels/water.cl, from the surface's own description;
/// - OpenClSampleSlots.cpp: every mesh's samples (and every action's drag clusters) in one device buffer, and the
///   re-bake of deformable meshes on the device;
/// - OpenClBatches.cpp: a substep's batch of bodies: tiles, launches, reductions, read-back;
/// - ../btOpenClBuoyancyBackend.cpp: choosing the device, building the kernels, and the public calls.
/// CMake compiles these only when the library is built with OpenCL; otherwise ../btOpenClBuoyancyBackendStub.cpp.

#include <BulletBuoyancy/bullet/btOpenClBuoyancyBackend.h>

#include <BulletBuoyancy/bullet/btBuoyancyDeformable.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/integrals/DragClusters.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <CL/opencl.hpp>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace buoyancy {
namespace opencl {

constexpr int kHydroTerms = 12;   ///< BB_HYDRO_TERMS: sums per body of the hydrostatics kernel
constexpr int kDragTerms = 11;    ///< BB_DRAG_TERMS: sums per body of the drag kernel
constexpr int kSampleStride = 16; ///< BB_SAMPLE_STRIDE (kernels/samples.cl): reals per sample
constexpr int kBodyStride = 32;   ///< BB_BODY_STRIDE: reals per body's parameters
constexpr int kWaterFlat = 0, kWaterGerstner = 1, kWaterGrid = 2;  ///< the water kinds of kernels/water.cl


/// "what() failed with OpenCL error N".
inline std::string clError(const cl::Error& e) {
    return std::string(e.what()) + " failed with OpenCL error " + std::to_string(e.err());
}

/// A device buffer that grows (never shrinks); contents are not kept across growth.
struct DeviceBuffer {
    cl::Buffer buffer;
    std::size_t bytes = 0;
    std::vector<float> staging;     ///< float copy of the last upload (must live until the transfer is done)
    std::vector<double> last;       ///< last uploaded contents (uploadIfChanged)
    /// true when the buffer was (re)created
    bool reserve(const cl::Context& ctx, std::size_t need) {
        need = std::max<std::size_t>(need, 64);
        if (need <= bytes) return false;
        bytes = std::max(need, bytes + bytes / 2);
        buffer = cl::Buffer(ctx, CL_MEM_READ_WRITE, bytes);
        return true;
    }
};

/// One mesh's samples in the shared sample buffer.
struct MeshSlot {
    const void* key = nullptr;            ///< shape, deformable or drag clusters
    std::shared_ptr<const void> keep;     ///< keeps the owner alive while the slot exists (when we have one)
    std::size_t offset = 0, count = 0;    ///< sample range
    double fingerprint[3] = {0, 0, 0};    ///< checked for keys we cannot keep alive (drag clusters)
    // deformable meshes: their piece map on the device, and the vertex version last re-baked
    const btBuoyancyDeformable* deformable = nullptr;
    std::uint64_t rebakedVersion = std::numeric_limits<std::uint64_t>::max();
    DeviceBuffer triangles, pieceStart, pieceTri, pieceData, vertices;
};


}  // namespace opencl
}  // namespace buoyancy

struct btOpenClBuoyancyBackend::Impl {
    using DeviceBuffer = buoyancy::opencl::DeviceBuffer;
    using MeshSlot = buoyancy::opencl::MeshSlot;
    static constexpr int kWaterFlat = buoyancy::opencl::kWaterFlat;

    btBuoyancyWorld* world = nullptr;
    btOpenClOptions opt;
    cl::Context ctx;
    cl::Device dev;
    cl::CommandQueue q;
    cl::Program prog;
    cl::Kernel kHydro, kDrag, kReduce, kRebake;
    bool dbl = true;
    std::size_t realSize = 8;
    std::size_t local = 64;
    std::string devName, platName;
    Stats stats;
    std::string fallback;
    bool enabled = true;
    std::mutex mutex;  ///< actions run in parallel (e.g. by an OpenMP action) share one batch

    // Sample buffers: hydrostatic samples of every mesh, drag clusters of every action, each in one buffer.
    std::vector<MeshSlot> hydroSlots, dragSlots;
    std::vector<double> hostHydro, hostDrag;
    DeviceBuffer dHydro, dDrag;
    bool hydroDirty = false, dragDirty = false;

    // Per-substep batch.
    std::uint64_t substep = 0, hydroDone = ~0ull, dragDone = ~0ull;
    double dt = 0;
    struct Body {
        const btBuoyancyDeviceBody* body = nullptr;
        btBuoyancyDeviceRecord record;  ///< this substep's (btBuoyancyDeviceBody::deviceRecord)
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        Eigen::Vector3d com = Eigen::Vector3d::Zero();
        std::size_t hydroSlot = 0;
        buoyancy::HydrostaticsResult h;
        bool valid = false, dragValid = false;
        Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero(), F = Eigen::Vector3d::Zero(),
                        T = Eigen::Vector3d::Zero(), u = Eigen::Vector3d::Zero();
        double linearPower = 0;  ///< the linear damping's power, W
    };
    std::vector<Body> bodies;
    std::unordered_map<const btBuoyancyDeviceBody*, std::size_t> index;
    std::vector<double> params, out;
    std::vector<cl_int> tiles, bodyTiles;
    std::vector<float> staging;
    DeviceBuffer dParams, dTiles, dBodyTiles, dPartials, dOut, dWater, dGrid;
    int waterType = kWaterFlat;
    bool waterDrag = true;
    btWaterDeviceDescription waterDescription;  ///< the water's last description (packWater)
    std::vector<double> wp, grid;

    // ---- transfers in the device's scalar ----
    /// Non-blocking write: `data` must stay unchanged until the batch's final (blocking) read, which in the
    /// in-order queue also waits for every transfer before it (so one host-device synchronisation per batch).
    /// With `blocking`, `data` may go away as soon as the call returns (rare uploads from temporaries).
    void write(DeviceBuffer& b, const double* data, std::size_t n, std::size_t offsetReals = 0, bool blocking = false);
    /// Upload unless the contents equal the last upload to this buffer (water parameters, grids).
    void uploadIfChanged(DeviceBuffer& b, const std::vector<double>& v);
    void upload(DeviceBuffer& b, const std::vector<double>& v, bool blocking = false);
    void uploadInts(DeviceBuffer& b, const std::vector<cl_int>& v, bool blocking = false);
    void read(DeviceBuffer& b, std::size_t n, std::vector<double>& dst);
    void setReal(cl::Kernel& k, int arg, double value);

    // ---- water on the device (kernels/water.cl) ----
    /// Pack the world's water at time t from its own description (btWaterSurface::describeForDevice); false (and
    /// `fallback`, the surface's reason) when it is not one of the kinds the kernels evaluate.
    bool packWater(const btWaterSurface& water, double t);

    // ---- sample slots ----
    static void fingerprint(const std::vector<double>& a, const std::vector<double>& b, double* out);
    std::size_t hydroSlotFor(const btBuoyancyDeviceRecord& r);
    std::size_t dragSlotFor(const buoyancy::DragClusters& c);
    /// Upload new meshes; re-bake deformable ones whose vertices changed (or whose region was overwritten).
    void syncHydroSamples();
    void uploadMap(MeshSlot& s, const buoyancy::RebakeMap& map);
    void runRebake(MeshSlot& s, const buoyancy::RebakeMap& map, DeviceBuffer& outBuf, std::size_t first);

    // ---- batches ----
    /// Warm-start state (2 reals per body-sample) of one action's samples; a new or resized action gets a new range.
    struct StateSlot {
        std::size_t offset = 0, count = 0;
    };
    std::unordered_map<const btBuoyancyDeviceBody*, StateSlot> hydroState, dragState;
    std::size_t hydroStateUsed = 0, dragStateUsed = 0;
    DeviceBuffer dHydroState, dDragState;
    std::size_t stateFor(std::unordered_map<const btBuoyancyDeviceBody*, StateSlot>& map, std::size_t& used,
                         const btBuoyancyDeviceBody* a, std::size_t count);
    /// Grow a state buffer to `used` entries; a new buffer starts cold (zero displacement).
    void ensureState(DeviceBuffer& b, std::size_t used);

    void addTiles(std::size_t body, std::size_t first, std::size_t count, std::size_t state);
    void pushPose(const Eigen::Isometry3d& pose, const Eigen::Vector3d& com);
    /// Launch `kernel` over the tiles, reduce per body, read nterms sums per body into `out`.
    void launch(cl::Kernel& kernel, DeviceBuffer& samples, DeviceBuffer& state, int nterms, std::size_t nb);

    void computeHydro();

    void computeDrag();
};
