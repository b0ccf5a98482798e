/// @file btOpenClBuoyancyBackend.cpp
/// Host side of the OpenCL backend. Per substep, at the first action's request:
///   1. collect every eligible body of the world (btBuoyancyDeviceBody::deviceRecord),
///   2. upload per-body parameters and the tile list (samples of every mesh live in one device buffer, shared by
///      the bodies using that mesh; deformable meshes are re-baked on the device when their vertices changed),
///   3. launch bb_hydro_tiles (one work-group per tile of ≤ tileSamples samples) and bb_reduce_bodies, read back
///      12 sums per body;
/// and at the first drag request: the same with bb_drag_tiles on each action's drag clusters, at each body's
/// btBuoyancyDeviceBody::dragEvaluationVelocity. The formulas are geometry/SampleFormulas.h, shared with the CPU.
/// This file chooses the device, builds the kernels and holds the public calls; the jobs behind them are in
/// opencl/ (OpenClBackendImpl.h lists them). Compiled only with OpenCL (btOpenClBuoyancyBackendStub.cpp otherwise).

#include <BulletBuoyancy/bullet/opencl/OpenClBackendImpl.h>

#include <BulletBuoyancy/bullet/BuoyancyKernelSource.h>
#include <BulletBuoyancy/bullet/btBulletConvert.h>

#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cmath>
#include <cstdlib>
#include <stdexcept>

using namespace buoyancy::opencl;
using buoyancy::toEigen;

bool btOpenClBuoyancyBackend::compiledIn() { return true; }

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

bool btOpenClBuoyancyBackend::hydrostatics(const btBuoyancyDeviceBody& body, const Eigen::Isometry3d& pose,
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
    const auto it = d.index.find(&body);
    if (it == d.index.end() || !d.bodies[it->second].valid || d.bodies[it->second].pose.matrix() != pose.matrix() ||
        d.bodies[it->second].com != com) {
        ++d.stats.declined;
        return false;
    }
    out = d.bodies[it->second].h;
    ++d.stats.hydroAnswers;
    return true;
}

bool btOpenClBuoyancyBackend::drag(const btBuoyancyDeviceBody& body, const Eigen::Vector3d& com, const Eigen::Vector3d& v,
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
    const auto it = d.index.find(&body);
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

