/// @file btOpenClBuoyancyBackend.cpp
/// Host side of the OpenCL backend. Per substep, at the first action's request:
///   1. collect every eligible body of the world (the same gating as btBuoyancyAction::updateAction),
///   2. upload per-body parameters and the tile list (samples of every mesh live in one device buffer, shared by
///      the bodies using that mesh; deformable meshes are re-baked on the device when their vertices changed),
///   3. launch bb_hydro_tiles (one work-group per tile of ≤ tileSamples samples) and bb_reduce_bodies, read back
///      12 sums per body;
/// and at the first drag request: the same with bb_drag_tiles on each action's drag clusters, at each body's
/// btBuoyancyAction::dragEvaluationVelocity. The formulas are geometry/SampleFormulas.h, shared with the CPU.

#include <BulletBuoyancy/bullet/btOpenClBuoyancyBackend.h>

#include <BulletBuoyancy/bullet/btBuoyancyDeformable.h>
#include <BulletBuoyancy/bullet/btBulletConvert.h>
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/integrals/DragClusters.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_map>

#if BULLET_BUOYANCY_HAVE_OPENCL
#include <BulletBuoyancy/bullet/BuoyancyKernelSource.h>
#include <CL/opencl.hpp>
#endif

namespace {
constexpr int kHydroTerms = 12;   // BB_HYDRO_TERMS
constexpr int kDragTerms = 11;    // BB_DRAG_TERMS
constexpr int kSampleStride = 16; // BB_SAMPLE_STRIDE (kernels/samples.cl)
constexpr int kBodyStride = 32;   // BB_BODY_STRIDE
constexpr int kWaterFlat = 0, kWaterGerstner = 1, kWaterGrid = 2;
}  // namespace

bool btOpenClBuoyancyBackend::compiledIn() { return BULLET_BUOYANCY_HAVE_OPENCL != 0; }

#if !BULLET_BUOYANCY_HAVE_OPENCL

// ---- Library built without OpenCL: create() explains, nothing else is reachable. ---------------------------
struct btOpenClBuoyancyBackend::Impl {
    Stats stats;
    std::string none;
};
std::unique_ptr<btOpenClBuoyancyBackend> btOpenClBuoyancyBackend::create(btBuoyancyWorld&, const btOpenClOptions&,
                                                                         std::string* message) {
    if (message)
        *message = "OpenCL: this BulletBuoyancy was built without OpenCL (BULLET_BUOYANCY_OPENCL=OFF, or the OpenCL "
                   "headers/library were not found at configure time); using the CPU path";
    return nullptr;
}
btOpenClBuoyancyBackend::btOpenClBuoyancyBackend(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
btOpenClBuoyancyBackend::~btOpenClBuoyancyBackend() = default;
void btOpenClBuoyancyBackend::beginSubstep(double) {}
bool btOpenClBuoyancyBackend::hydrostatics(const btBuoyancyAction&, const Eigen::Isometry3d&, const Eigen::Vector3d&,
                                           buoyancy::HydrostaticsResult&) {
    return false;
}
bool btOpenClBuoyancyBackend::drag(const btBuoyancyAction&, const Eigen::Vector3d&, const Eigen::Vector3d&,
                                   const Eigen::Vector3d&, Eigen::Vector3d&, Eigen::Vector3d&, Eigen::Vector3d&,
                                   double&) {
    return false;
}
std::string btOpenClBuoyancyBackend::describe() const { return "OpenCL: not built"; }
bool btOpenClBuoyancyBackend::usesDouble() const { return false; }
void btOpenClBuoyancyBackend::setEnabled(bool) {}
bool btOpenClBuoyancyBackend::isEnabled() const { return false; }
std::string btOpenClBuoyancyBackend::deviceName() const { return ""; }
const std::string& btOpenClBuoyancyBackend::lastFallbackReason() const { return m_impl->none; }
const btOpenClBuoyancyBackend::Stats& btOpenClBuoyancyBackend::stats() const { return m_impl->stats; }
void btOpenClBuoyancyBackend::rebakeOnDevice(const buoyancy::RebakeMap&, const std::vector<Eigen::Vector3d>&,
                                             buoyancy::SurfaceSamples&) {
    throw std::runtime_error("OpenCL: not built");
}

#else

using buoyancy::toEigen;

namespace {

std::string clError(const cl::Error& e) { return std::string(e.what()) + " failed with OpenCL error " + std::to_string(e.err()); }

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

}  // namespace

struct btOpenClBuoyancyBackend::Impl {
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
        const btBuoyancyAction* action = nullptr;
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
    std::unordered_map<const btBuoyancyAction*, std::size_t> index;
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
    void write(DeviceBuffer& b, const double* data, std::size_t n, std::size_t offsetReals = 0, bool blocking = false) {
        if (n == 0) return;
        const cl_bool block = blocking ? CL_TRUE : CL_FALSE;
        if (dbl) {
            q.enqueueWriteBuffer(b.buffer, block, offsetReals * 8, n * 8, data);
        } else {
            b.staging.assign(data, data + n);
            q.enqueueWriteBuffer(b.buffer, block, offsetReals * 4, n * 4, b.staging.data());
        }
    }
    /// Upload unless the contents equal the last upload to this buffer (water parameters, grids).
    void uploadIfChanged(DeviceBuffer& b, const std::vector<double>& v) {
        if (b.bytes >= v.size() * realSize && b.last == v) return;
        b.last = v;
        b.reserve(ctx, v.size() * realSize);
        write(b, b.last.data(), b.last.size());
    }
    void upload(DeviceBuffer& b, const std::vector<double>& v, bool blocking = false) {
        b.reserve(ctx, v.size() * realSize);
        write(b, v.data(), v.size(), 0, blocking);
    }
    void uploadInts(DeviceBuffer& b, const std::vector<cl_int>& v, bool blocking = false) {
        b.reserve(ctx, v.size() * sizeof(cl_int));
        if (!v.empty())
            q.enqueueWriteBuffer(b.buffer, blocking ? CL_TRUE : CL_FALSE, 0, v.size() * sizeof(cl_int), v.data());
    }
    void read(DeviceBuffer& b, std::size_t n, std::vector<double>& dst) {
        dst.resize(n);
        if (n == 0) return;
        if (dbl) {
            q.enqueueReadBuffer(b.buffer, CL_TRUE, 0, n * 8, dst.data());
        } else {
            staging.resize(n);
            q.enqueueReadBuffer(b.buffer, CL_TRUE, 0, n * 4, staging.data());
            std::copy(staging.begin(), staging.end(), dst.begin());
        }
    }
    void setReal(cl::Kernel& k, int arg, double value) {
        if (dbl)
            k.setArg(arg, value);
        else
            k.setArg(arg, float(value));
    }

    // ---- water on the device (kernels/water.cl) ----
    /// Pack the world's water at time t from its own description (btWaterSurface::describeForDevice); false (and
    /// `fallback`, the surface's reason) when it is not one of the kinds the kernels evaluate.
    bool packWater(const btWaterSurface& water, double t) {
        wp.assign(8, 0.0);
        grid.clear();
        waterDrag = true;
        btWaterDeviceDescription& d = waterDescription;  // reused: its vectors keep their storage
        if (!water.describeForDevice(t, d)) {
            fallback = d.reason.empty() ? std::string("water: the surface did not describe itself for the device")
                                        : d.reason;
            return false;
        }
        switch (d.kind) {
        case btWaterDeviceDescription::Kind::Flat:
            waterType = kWaterFlat;
            wp[0] = d.level;
            wp[1] = d.currentX;
            wp[2] = d.currentZ;
            return true;
        case btWaterDeviceDescription::Kind::Gerstner: {
            const std::size_t m = d.waveConstants.size() / 7;
            waterType = kWaterGerstner;
            const double tol = dbl ? 1e-9 : 2e-5;  // btGerstnerWaterSurface's residual; float: a few ulps of 10 m
            wp.assign(8 + 8 * m, 0.0);
            wp[0] = d.meanLevel;
            wp[1] = double(m);
            wp[2] = tol * tol;
            wp[3] = double(d.maxIterations);
            for (std::size_t i = 0; i < m; ++i)
                for (int k = 0; k < 7; ++k) wp[8 + 8 * i + k] = d.waveConstants[7 * i + k];
            return true;
        }
        case btWaterDeviceDescription::Kind::HeightGrid: {
            const std::size_t n = std::size_t(std::max(d.sizeX, 0)) * std::size_t(std::max(d.sizeZ, 0));
            const bool vel = !d.velocityX.empty();
            if (d.sizeX < 2 || d.sizeZ < 2 || !(d.spacing > 0) || d.heights.size() != n ||
                (vel && (d.velocityX.size() != n || d.velocityY.size() != n || d.velocityZ.size() != n))) {
                fallback = "water: the surface's height-grid description is inconsistent (sizes " +
                           std::to_string(d.sizeX) + " x " + std::to_string(d.sizeZ) + ", " +
                           std::to_string(d.heights.size()) + " heights); its bodies use the CPU path";
                return false;
            }
            waterType = kWaterGrid;
            wp[0] = d.sizeX;
            wp[1] = d.sizeZ;
            wp[2] = d.spacing;
            wp[3] = d.originX;
            wp[4] = d.originZ;
            wp[5] = d.periodic ? 1 : 0;
            wp[6] = vel ? 1 : 0;
            grid.swap(d.heights);
            if (vel)
                for (auto* f : {&d.velocityX, &d.velocityY, &d.velocityZ}) grid.insert(grid.end(), f->begin(), f->end());
            waterDrag = d.velocityOnDevice;
            return true;
        }
        case btWaterDeviceDescription::Kind::None:
            break;
        }
        fallback = d.reason.empty() ? std::string("water: the surface did not describe itself for the device") : d.reason;
        return false;
    }

    // ---- sample slots ----
    static void fingerprint(const std::vector<double>& a, const std::vector<double>& b, double* out) {
        out[0] = double(a.size());
        out[1] = a.empty() ? 0.0 : a.front();
        out[2] = b.empty() ? 0.0 : b.back();
    }
    std::size_t hydroSlotFor(const btBuoyancyAction& a) {
        const auto& def = a.getDeformable();
        const void* key = def ? static_cast<const void*>(def.get()) : static_cast<const void*>(a.getShape().get());
        for (std::size_t i = 0; i < hydroSlots.size(); ++i)
            if (hydroSlots[i].key == key) return i;
        const buoyancy::SurfaceSamples& s = a.getSamplesInUse();
        MeshSlot slot;
        slot.key = key;
        slot.keep = def ? std::shared_ptr<const void>(def) : std::shared_ptr<const void>(a.getShape());
        slot.deformable = def.get();
        slot.offset = hostHydro.size() / kSampleStride;
        slot.count = s.size();
        for (std::size_t i = 0; i < s.size(); ++i) {
            const double row[kSampleStride] = {s.px[i], s.py[i], s.pz[i], s.ax[i], s.ay[i], s.az[i], s.area[i]};
            hostHydro.insert(hostHydro.end(), row, row + kSampleStride);
        }
        hydroSlots.push_back(std::move(slot));
        hydroDirty = true;
        return hydroSlots.size() - 1;
    }
    std::size_t dragSlotFor(const buoyancy::DragClusters& c) {
        double fp[3];
        fingerprint(c.px, c.area, fp);
        fp[0] += 1e6 * double(c.probeX.size());  // a re-probed cluster set is another slot
        for (std::size_t i = 0; i < dragSlots.size(); ++i)
            if (dragSlots[i].key == &c && std::equal(fp, fp + 3, dragSlots[i].fingerprint)) return i;
        MeshSlot slot;
        slot.key = &c;
        std::copy(fp, fp + 3, slot.fingerprint);
        slot.offset = hostDrag.size() / kSampleStride;
        slot.count = c.size();
        // The water velocity of a cluster is taken at its velocity probe (DragClusters::probeOf), as the CPU does
        // when there are fewer probes than clusters; else at the cluster itself.
        const bool probes = c.probeX.size() < c.size() && c.probeOf.size() == c.size();
        for (std::size_t i = 0; i < c.size(); ++i) {
            const std::size_t j = probes ? c.probeOf[i] : 0;
            const double qx = probes ? c.probeX[j] : c.px[i], qy = probes ? c.probeY[j] : c.py[i],
                         qz = probes ? c.probeZ[j] : c.pz[i];
            const double row[kSampleStride] = {c.px[i],  c.py[i],  c.pz[i],  c.ax[i],  c.ay[i],  c.az[i], c.area[i],
                                               c.cxx[i], c.cxy[i], c.cxz[i], c.cyy[i], c.cyz[i], c.czz[i],
                                               qx,       qy,       qz};
            hostDrag.insert(hostDrag.end(), row, row + kSampleStride);
        }
        // A stale slot with the same address (clusters freed and reallocated) is simply left unused.
        dragSlots.push_back(std::move(slot));
        dragDirty = true;
        return dragSlots.size() - 1;
    }
    /// Upload new meshes; re-bake deformable ones whose vertices changed (or whose region was overwritten).
    void syncHydroSamples() {
        if (hydroDirty) {
            dHydro.reserve(ctx, hostHydro.size() * realSize);
            write(dHydro, hostHydro.data(), hostHydro.size());
            for (MeshSlot& s : hydroSlots) s.rebakedVersion = std::numeric_limits<std::uint64_t>::max();
            hydroDirty = false;
        }
        for (MeshSlot& s : hydroSlots) {
            if (!s.deformable || s.rebakedVersion == s.deformable->getVersion()) continue;
            const buoyancy::RebakeMap& map = s.deformable->getMap();
            if (s.pieceStart.bytes == 0) uploadMap(s, map);
            std::vector<double>& v = s.vertices.last;  // kept until the batch's read (non-blocking write)
            v.clear();
            for (const Eigen::Vector3d& p : s.deformable->getVertices()) v.insert(v.end(), {p.x(), p.y(), p.z()});
            s.vertices.reserve(ctx, v.size() * realSize);
            write(s.vertices, v.data(), v.size());
            runRebake(s, map, dHydro, s.offset);
            s.rebakedVersion = s.deformable->getVersion();
            ++stats.rebakes;
        }
    }
    void uploadMap(MeshSlot& s, const buoyancy::RebakeMap& map) {
        std::vector<cl_int> tri, start(map.pieceStart.begin(), map.pieceStart.end()),
            ptri(map.pieceTriangle.begin(), map.pieceTriangle.end());
        for (const Eigen::Vector3i& t : map.triangles) tri.insert(tri.end(), {t[0], t[1], t[2]});
        std::vector<double> pd;
        pd.reserve(3 * map.pieceWeight.size());
        for (std::size_t k = 0; k < map.pieceWeight.size(); ++k)
            pd.insert(pd.end(), {map.pieceWeight[k], map.pieceBeta1[k], map.pieceBeta2[k]});
        uploadInts(s.triangles, tri, true);
        uploadInts(s.pieceStart, start, true);
        uploadInts(s.pieceTri, ptri, true);
        upload(s.pieceData, pd, true);
    }
    void runRebake(MeshSlot& s, const buoyancy::RebakeMap& map, DeviceBuffer& outBuf, std::size_t first) {
        const int n = int(map.size());
        if (n == 0) return;
        kRebake.setArg(0, s.vertices.buffer);
        kRebake.setArg(1, s.triangles.buffer);
        kRebake.setArg(2, s.pieceStart.buffer);
        kRebake.setArg(3, s.pieceTri.buffer);
        kRebake.setArg(4, s.pieceData.buffer);
        kRebake.setArg(5, cl_int(n));
        kRebake.setArg(6, cl_int(first));
        kRebake.setArg(7, outBuf.buffer);
        const std::size_t g = (std::size_t(n) + local - 1) / local * local;
        q.enqueueNDRangeKernel(kRebake, cl::NullRange, cl::NDRange(g), cl::NDRange(local));
    }

    // ---- batches ----
    /// Warm-start state (2 reals per body-sample) of one action's samples; a new or resized action gets a new range.
    struct StateSlot {
        std::size_t offset = 0, count = 0;
    };
    std::unordered_map<const btBuoyancyAction*, StateSlot> hydroState, dragState;
    std::size_t hydroStateUsed = 0, dragStateUsed = 0;
    DeviceBuffer dHydroState, dDragState;
    std::size_t stateFor(std::unordered_map<const btBuoyancyAction*, StateSlot>& map, std::size_t& used,
                         const btBuoyancyAction* a, std::size_t count) {
        StateSlot& s = map[a];
        if (s.count != count) {
            s.offset = used;
            s.count = count;
            used += count;
        }
        return s.offset;
    }
    /// Grow a state buffer to `used` entries; a new buffer starts cold (zero displacement).
    void ensureState(DeviceBuffer& b, std::size_t used) {
        if (b.reserve(ctx, used * 2 * realSize)) q.enqueueFillBuffer(b.buffer, cl_uchar(0), 0, b.bytes);
    }

    void addTiles(std::size_t body, std::size_t first, std::size_t count, std::size_t state) {
        const std::size_t t0 = tiles.size() / 4;
        const std::size_t per = std::size_t(std::max(opt.tileSamples, 64));
        for (std::size_t s = 0; s < count; s += per)
            tiles.insert(tiles.end(),
                         {cl_int(body), cl_int(first + s), cl_int(std::min(per, count - s)), cl_int(state + s)});
        bodyTiles.insert(bodyTiles.end(), {cl_int(t0), cl_int(tiles.size() / 4)});
    }
    void pushPose(const Eigen::Isometry3d& pose, const Eigen::Vector3d& com) {
        const Eigen::Matrix3d R = pose.linear();
        const Eigen::Vector3d t = pose.translation() - com;
        const double b[15] = {R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1),
                              R(2, 2), t.x(),   t.y(),   t.z(),   com.x(),  com.y(),  com.z()};
        params.insert(params.end(), b, b + 15);
    }
    /// Launch `kernel` over the tiles, reduce per body, read nterms sums per body into `out`.
    void launch(cl::Kernel& kernel, DeviceBuffer& samples, DeviceBuffer& state, int nterms, std::size_t nb) {
        upload(dParams, params);
        uploadInts(dTiles, tiles);
        uploadInts(dBodyTiles, bodyTiles);
        if (grid.empty()) grid.assign(1, 0.0);
        uploadIfChanged(dWater, wp);
        uploadIfChanged(dGrid, grid);
        const std::size_t nt = tiles.size() / 4;
        dPartials.reserve(ctx, nt * nterms * realSize);
        dOut.reserve(ctx, nb * nterms * realSize);
        kernel.setArg(0, samples.buffer);
        kernel.setArg(1, dParams.buffer);
        kernel.setArg(2, dTiles.buffer);
        kernel.setArg(3, cl_int(waterType));
        kernel.setArg(4, dWater.buffer);
        kernel.setArg(5, dGrid.buffer);
        setReal(kernel, 6, world->getTime());
        kernel.setArg(7, dPartials.buffer);
        kernel.setArg(8, cl::Local(local * nterms * realSize));
        kernel.setArg(9, state.buffer);
        q.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(nt * local), cl::NDRange(local));
        kReduce.setArg(0, dPartials.buffer);
        kReduce.setArg(1, dBodyTiles.buffer);
        kReduce.setArg(2, cl_int(nterms));
        kReduce.setArg(3, cl_int(nb));
        kReduce.setArg(4, dOut.buffer);
        const std::size_t g = (nb + 63) / 64 * 64;
        q.enqueueNDRangeKernel(kReduce, cl::NullRange, cl::NDRange(g), cl::NDRange(64));
        read(dOut, nb * nterms, out);
    }

    void computeHydro() {
        hydroDone = substep;
        bodies.clear();
        index.clear();
        fallback.clear();
        const btWaterSurface* water = world->getWater();
        if (!water) return;
        const double time = world->getTime();
        if (!packWater(*water, time)) return;
        double flatH = 0;
        const bool flat = water->isFlat(time, flatH);
        const bool waves = water->isTimeVarying();
        params.clear();
        tiles.clear();
        bodyTiles.clear();
        for (btBuoyancyAction* a : world->getActions()) {
            // The gating of btBuoyancyAction::updateAction: bodies it would compute with the sampled method.
            const btRigidBody* b = a->getRigidBody();
            if (!b->getBroadphaseHandle() || b->getInvMass() == btScalar(0)) continue;
            if (!b->isActive() && !waves) continue;
            const btBuoyancyShape& shape = *a->getShape();
            if (shape.getMethod() == btBuoyancyMethod::ExactMesh || !a->getSettings().buoyancyEnabled) continue;
            // In the water frame, as btBuoyancyAction::updateAction (the action maps the results back).
            const btWaterFrame& frame = world->getWaterFrame();
            const Eigen::Isometry3d pose = frame.toWater(toEigen(b->getWorldTransform() * a->getMeshInComFrame()));
            const Eigen::Vector3d com = frame.toWaterPoint(toEigen(b->getCenterOfMassPosition()));
            if (!pose.matrix().allFinite() || !com.allFinite()) continue;
            const btBuoyancyDeformable* def = a->getDeformable().get();
            const Eigen::Vector3d bc = pose * (def ? def->getBoundsCentre() : shape.getBoundsCentre());
            const double br = def ? def->getBoundsRadius() : shape.getBoundsRadius();
            double lo = 0, hi = 0;
            water->heightBounds(bc.x() - br, bc.z() - br, bc.x() + br, bc.z() + br, time, lo, hi);
            if (bc.y() - br >= hi) continue;             // dry
            if (flat && bc.y() + br <= flatH && !def) continue;  // the action's closed form (design.md 2.5)
            if (a->getSamplesInUse().size() == 0) continue;
            const std::size_t slot = hydroSlotFor(*a);
            index[a] = bodies.size();
            bodies.emplace_back();
            bodies.back().action = a;
            bodies.back().pose = pose;
            bodies.back().com = com;
            bodies.back().hydroSlot = slot;
            pushPose(pose, com);
            params.resize(bodies.size() * kBodyStride, 0.0);
            addTiles(bodies.size() - 1, hydroSlots[slot].offset, hydroSlots[slot].count,
                     stateFor(hydroState, hydroStateUsed, a, hydroSlots[slot].count));
        }
        if (bodies.empty()) return;
        syncHydroSamples();
        ensureState(dHydroState, hydroStateUsed);
        launch(kHydro, dHydro, dHydroState, kHydroTerms, bodies.size());
        ++stats.hydroBatches;
        stats.bodiesComputed += bodies.size();
        const double rg = world->getFluidDensity() * world->getGravity();
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            const double* o = &out[i * kHydroTerms];
            buoyancy::HydrostaticsResult& h = bodies[i].h;
            h.submerged_volume = o[0];
            h.centre_of_buoyancy = h.submerged_volume != 0
                                       ? Eigen::Vector3d(bodies[i].com + Eigen::Vector3d(o[1], o[2], o[3]) / o[0])
                                       : Eigen::Vector3d::Zero();
            h.force = rg * Eigen::Vector3d(o[4], o[5], o[6]);
            h.torque = rg * Eigen::Vector3d(o[7], o[8], o[9]);
            h.waterline_area = -o[10];
            h.wetted_area = o[11];
            bodies[i].valid = std::isfinite(h.submerged_volume) && h.force.allFinite() && h.torque.allFinite() &&
                              h.centre_of_buoyancy.allFinite();
        }
    }

    void computeDrag() {
        dragDone = substep;
        if (bodies.empty() || !waterDrag) return;
        params.clear();
        tiles.clear();
        bodyTiles.clear();
        std::vector<std::size_t> which;
        const double rho = world->getFluidDensity();
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            Body& b = bodies[i];
            const btBuoyancySettings& s = b.action->getSettings();
            if (!b.valid ||
                !(s.dragCoefficient > 0 || s.skinFriction > 0 || s.linearDamping > 0 || s.radiationDamping > 0))
                continue;
            const buoyancy::DragClusters& c = b.action->getDragClusters();
            if (c.size() == 0) continue;
            b.action->dragEvaluationVelocity(b.h, dt, b.v, b.w);
            // The same linear damping as the CPU path: the viscous part plus the radiation damping faded by depth.
            const double damping = b.action->linearDampingNow(b.h, b.pose);
            const std::size_t slot = dragSlotFor(c);
            const std::size_t k = which.size();
            which.push_back(i);
            pushPose(b.pose, b.com);
            const double extra[9] = {b.v.x(), b.v.y(), b.v.z(), b.w.x(), b.w.y(), b.w.z(),
                                     0.5 * rho * s.dragCoefficient, 0.5 * rho * s.skinFriction,
                                     rho * damping};
            params.insert(params.end(), extra, extra + 9);
            params.resize((k + 1) * kBodyStride, 0.0);
            addTiles(k, dragSlots[slot].offset, dragSlots[slot].count,
                     stateFor(dragState, dragStateUsed, b.action, dragSlots[slot].count));
        }
        if (which.empty()) return;
        if (dragDirty) {
            dDrag.reserve(ctx, hostDrag.size() * realSize);
            write(dDrag, hostDrag.data(), hostDrag.size());
            dragDirty = false;
        }
        ensureState(dDragState, dragStateUsed);
        launch(kDrag, dDrag, dDragState, kDragTerms, which.size());
        ++stats.dragBatches;
        for (std::size_t k = 0; k < which.size(); ++k) {
            Body& b = bodies[which[k]];
            const double* o = &out[k * kDragTerms];
            b.F = Eigen::Vector3d(o[0], o[1], o[2]);
            b.T = Eigen::Vector3d(o[3], o[4], o[5]);
            b.u = o[9] > 0 ? Eigen::Vector3d(Eigen::Vector3d(o[6], o[7], o[8]) / o[9]) : Eigen::Vector3d::Zero();
            b.linearPower = o[10];
            b.dragValid = b.F.allFinite() && b.T.allFinite() && b.u.allFinite() && std::isfinite(b.linearPower);
        }
    }
};

std::unique_ptr<btOpenClBuoyancyBackend> btOpenClBuoyancyBackend::create(btBuoyancyWorld& world,
                                                                         const btOpenClOptions& options,
                                                                         std::string* message) {
    auto fail = [&](const std::string& why) -> std::unique_ptr<btOpenClBuoyancyBackend> {
        if (message) *message = "OpenCL: " + why + "; using the CPU path";
        return nullptr;
    };
    if (options.tileSamples < 64) return fail("tileSamples must be >= 64 (got " + std::to_string(options.tileSamples) + ")");
    if (options.workGroupSize < 1 || options.workGroupSize > 256)
        return fail("workGroupSize must be in 1..256 (got " + std::to_string(options.workGroupSize) + ")");
    auto impl = std::make_unique<Impl>();
    impl->world = &world;
    impl->opt = options;
    std::string stage = "listing platforms";
    try {
        std::vector<cl::Platform> platforms;
        try {
            cl::Platform::get(&platforms);
        } catch (const cl::Error&) {
            platforms.clear();  // CL_PLATFORM_NOT_FOUND_KHR from the ICD loader
        }
        if (platforms.empty())
            return fail("no OpenCL platform found (install a driver/ICD, e.g. Debian's pocl-opencl-icd)");
        struct Candidate {
            cl::Platform platform;
            cl::Device device;
        };
        std::vector<Candidate> all;
        stage = "listing devices";
        for (const cl::Platform& p : platforms) {
            std::vector<cl::Device> devices;
            try {
                p.getDevices(CL_DEVICE_TYPE_ALL, &devices);
            } catch (const cl::Error&) {
                continue;  // a platform without devices
            }
            for (const cl::Device& d : devices) all.push_back({p, d});
        }
        if (all.empty()) return fail("no OpenCL device found on " + std::to_string(platforms.size()) + " platform(s)");
        int pick = options.deviceIndex;
        if (pick < 0) {
            if (const char* env = std::getenv("BULLET_BUOYANCY_OPENCL_DEVICE")) {
                char* end = nullptr;
                const long v = std::strtol(env, &end, 10);
                if (end == env || *end != '\0' || v < 0)
                    return fail(std::string("BULLET_BUOYANCY_OPENCL_DEVICE='") + env + "' is not a device number");
                pick = int(v);
            }
        }
        if (pick < 0) {
            pick = 0;
            for (std::size_t i = 0; i < all.size(); ++i)
                if (all[i].device.getInfo<CL_DEVICE_TYPE>() & CL_DEVICE_TYPE_GPU) {
                    pick = int(i);
                    break;
                }
        }
        if (pick >= int(all.size()))
            return fail("device " + std::to_string(pick) + " asked, only " + std::to_string(all.size()) + " exist");
        impl->dev = all[pick].device;
        impl->platName = all[pick].platform.getInfo<CL_PLATFORM_NAME>();
        impl->devName = impl->dev.getInfo<CL_DEVICE_NAME>();
        const bool fp64 = impl->dev.getInfo<CL_DEVICE_EXTENSIONS>().find("cl_khr_fp64") != std::string::npos;
        if (options.precision == btOpenClOptions::Precision::Double && !fp64)
            return fail("double precision asked but device '" + impl->devName + "' has no cl_khr_fp64");
        impl->dbl = options.precision == btOpenClOptions::Precision::Float ? false : fp64;
        impl->realSize = impl->dbl ? 8 : 4;
        // One context and built program per (device, precision) for the whole process: a kernel build takes
        // seconds on PoCL, and every world (and test) after the first reuses it.
        static std::mutex cacheMutex;
        struct CachedProgram {
            cl_device_id device;
            bool dbl;
            cl::Context ctx;
            cl::Program prog;
        };
        static std::vector<CachedProgram> cache;
        std::lock_guard<std::mutex> lock(cacheMutex);
        const CachedProgram* hit = nullptr;
        for (const CachedProgram& c : cache)
            if (c.device == impl->dev() && c.dbl == impl->dbl) hit = &c;
        if (hit) {
            impl->ctx = hit->ctx;
            impl->prog = hit->prog;
        } else {
            stage = "creating the context";
            impl->ctx = cl::Context(impl->dev);
            stage = "building the kernels";
            impl->prog = cl::Program(impl->ctx, std::string(buoyancy::opencl::kKernelSource));
            const std::string opts =
                std::string("-cl-std=CL1.2 ") +
                (impl->dbl ? "-DBB_REAL=double -DBB_REAL_IS_DOUBLE=1" : "-DBB_REAL=float -DBB_REAL_IS_DOUBLE=0");
            try {
                impl->prog.build({impl->dev}, opts.c_str());
            } catch (const cl::Error& e) {
                std::string log;
                try {
                    log = impl->prog.getBuildInfo<CL_PROGRAM_BUILD_LOG>(impl->dev);
                } catch (const cl::Error&) {
                }
                return fail("kernel build failed on '" + impl->devName + "' (" + clError(e) + "); build log:\n" + log);
            }
            cache.push_back({impl->dev(), impl->dbl, impl->ctx, impl->prog});
        }
        stage = "creating the command queue";
        impl->q = cl::CommandQueue(impl->ctx, impl->dev);
        stage = "creating the kernels";
        impl->kHydro = cl::Kernel(impl->prog, "bb_hydro_tiles");
        impl->kDrag = cl::Kernel(impl->prog, "bb_drag_tiles");
        impl->kReduce = cl::Kernel(impl->prog, "bb_reduce_bodies");
        impl->kRebake = cl::Kernel(impl->prog, "bb_rebake");
        std::size_t limit = impl->dev.getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
        for (cl::Kernel* k : {&impl->kHydro, &impl->kDrag, &impl->kRebake})
            limit = std::min(limit, k->getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(impl->dev));
        const std::size_t localMem = impl->dev.getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
        limit = std::min(limit, localMem / (std::max(kHydroTerms, kDragTerms) * impl->realSize + 64));
        std::size_t local = 1;
        while (local * 2 <= std::min<std::size_t>(limit, std::size_t(options.workGroupSize))) local *= 2;
        if (local < 64 && limit >= 64) local = 64;
        impl->local = local;
        if (impl->kReduce.getWorkGroupInfo<CL_KERNEL_WORK_GROUP_SIZE>(impl->dev) < 64)
            return fail("device '" + impl->devName + "' allows fewer than 64 work-items per group");
    } catch (const cl::Error& e) {
        return fail(stage + ": " + clError(e));
    }
    std::unique_ptr<btOpenClBuoyancyBackend> backend(new btOpenClBuoyancyBackend(std::move(impl)));
    if (message) *message = backend->describe();
    return backend;
}

btOpenClBuoyancyBackend::btOpenClBuoyancyBackend(std::unique_ptr<Impl> impl) : m_impl(std::move(impl)) {}
btOpenClBuoyancyBackend::~btOpenClBuoyancyBackend() = default;

void btOpenClBuoyancyBackend::beginSubstep(double dt) {
    std::lock_guard<std::mutex> lock(m_impl->mutex);
    ++m_impl->substep;
    m_impl->dt = dt;
}

bool btOpenClBuoyancyBackend::hydrostatics(const btBuoyancyAction& action, const Eigen::Isometry3d& pose,
                                           const Eigen::Vector3d& com, buoyancy::HydrostaticsResult& out) {
    Impl& d = *m_impl;
    std::lock_guard<std::mutex> lock(d.mutex);  // once per body and substep, not per sample
    if (!d.enabled) return false;
    if (d.hydroDone != d.substep) {
        try {
            d.computeHydro();
        } catch (const cl::Error& e) {
            d.bodies.clear();
            d.index.clear();
            d.fallback = "OpenCL error in the hydrostatics batch: " + clError(e);
        } catch (const std::exception& e) {
            d.bodies.clear();
            d.index.clear();
            d.fallback = std::string("hydrostatics batch: ") + e.what();
        }
    }
    const auto it = d.index.find(&action);
    if (it == d.index.end() || !d.bodies[it->second].valid || d.bodies[it->second].pose.matrix() != pose.matrix() ||
        d.bodies[it->second].com != com) {
        ++d.stats.declined;
        return false;
    }
    out = d.bodies[it->second].h;
    ++d.stats.hydroAnswers;
    return true;
}

bool btOpenClBuoyancyBackend::drag(const btBuoyancyAction& action, const Eigen::Vector3d& com, const Eigen::Vector3d& v,
                                   const Eigen::Vector3d& w, Eigen::Vector3d& force, Eigen::Vector3d& torque,
                                   Eigen::Vector3d& meanWaterVelocity, double& linearDampingPower) {
    Impl& d = *m_impl;
    std::lock_guard<std::mutex> lock(d.mutex);
    if (!d.enabled || d.hydroDone != d.substep) return false;
    if (d.dragDone != d.substep) {
        try {
            d.computeDrag();
        } catch (const cl::Error& e) {
            for (auto& b : d.bodies) b.dragValid = false;
            d.fallback = "OpenCL error in the drag batch: " + clError(e);
        } catch (const std::exception& e) {
            for (auto& b : d.bodies) b.dragValid = false;
            d.fallback = std::string("drag batch: ") + e.what();
        }
    }
    const auto it = d.index.find(&action);
    if (it == d.index.end()) return false;
    const Impl::Body& b = d.bodies[it->second];
    if (!b.dragValid || b.com != com || b.v != v || b.w != w) {
        ++d.stats.declined;
        return false;
    }
    force = b.F;
    torque = b.T;
    meanWaterVelocity = b.u;
    linearDampingPower = b.linearPower;
    ++d.stats.dragAnswers;
    return true;
}

std::string btOpenClBuoyancyBackend::describe() const {
    return "OpenCL: " + m_impl->devName + " (" + m_impl->platName + "), " +
           (m_impl->dbl ? "double (cl_khr_fp64)" : "float");
}
bool btOpenClBuoyancyBackend::usesDouble() const { return m_impl->dbl; }
void btOpenClBuoyancyBackend::setEnabled(bool enabled) {
    m_impl->enabled = enabled;
    m_impl->hydroDone = m_impl->dragDone = ~0ull;  // nothing computed while paused is reused
}
bool btOpenClBuoyancyBackend::isEnabled() const { return m_impl->enabled; }
std::string btOpenClBuoyancyBackend::deviceName() const { return m_impl->devName; }
const std::string& btOpenClBuoyancyBackend::lastFallbackReason() const { return m_impl->fallback; }
const btOpenClBuoyancyBackend::Stats& btOpenClBuoyancyBackend::stats() const { return m_impl->stats; }

void btOpenClBuoyancyBackend::rebakeOnDevice(const buoyancy::RebakeMap& map, const std::vector<Eigen::Vector3d>& vertices,
                                             buoyancy::SurfaceSamples& out) {
    if (vertices.size() != map.vertexCount)
        throw std::invalid_argument("rebakeOnDevice: " + std::to_string(vertices.size()) + " vertices given, the mesh has " +
                                    std::to_string(map.vertexCount));
    Impl& d = *m_impl;
    try {
        MeshSlot s;
        d.uploadMap(s, map);
        std::vector<double> v;
        for (const Eigen::Vector3d& p : vertices) v.insert(v.end(), {p.x(), p.y(), p.z()});
        d.upload(s.vertices, v);
        DeviceBuffer result;
        result.reserve(d.ctx, map.size() * kSampleStride * d.realSize);
        d.runRebake(s, map, result, 0);
        std::vector<double> host;
        d.read(result, map.size() * kSampleStride, host);
        const std::size_t n = map.size();
        out = buoyancy::SurfaceSamples();
        out.texture_size = map.texture_size;
        out.method = map.method;
        out.reserve(n);
        for (std::size_t i = 0; i < n; ++i) {
            const double* r = &host[i * kSampleStride];
            out.push(r[0], r[1], r[2], r[3], r[4], r[5], r[6], map.texel[i], map.triangle[i]);
        }
    } catch (const cl::Error& e) {
        throw std::runtime_error("rebakeOnDevice: " + clError(e));
    }
}

#endif  // BULLET_BUOYANCY_HAVE_OPENCL
