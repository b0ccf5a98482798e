/// @file OpenClBatches.cpp
/// The OpenCL backend's batches: once per substep, every eligible body's hydrostatics (and drag) in one launch over
/// tiles of samples, reduced per body and read back.

#include <BulletBuoyancy/bullet/opencl/OpenClBackendImpl.h>

#include <cmath>

using namespace buoyancy::opencl;

std::size_t btOpenClBuoyancyBackend::Impl::stateFor(std::unordered_map<const btBuoyancyDeviceBody*, StateSlot>& map,
                                                    std::size_t& used, const btBuoyancyDeviceBody* a,
                                                    std::size_t count) {
    StateSlot& s = map[a];
    if (s.count != count) {
        s.offset = used;
        s.count = count;
        used += count;
    }
    return s.offset;
}

void btOpenClBuoyancyBackend::Impl::ensureState(DeviceBuffer& b, std::size_t used) {
    if (b.reserve(ctx, used * 2 * realSize)) q.enqueueFillBuffer(b.buffer, cl_uchar(0), 0, b.bytes);
}

void btOpenClBuoyancyBackend::Impl::addTiles(std::size_t body, std::size_t first, std::size_t count,
                                             std::size_t state) {
    const std::size_t t0 = tiles.size() / 4;
    const std::size_t per = std::size_t(std::max(opt.tileSamples, 64));
    for (std::size_t s = 0; s < count; s += per)
        tiles.insert(tiles.end(),
                     {cl_int(body), cl_int(first + s), cl_int(std::min(per, count - s)), cl_int(state + s)});
    bodyTiles.insert(bodyTiles.end(), {cl_int(t0), cl_int(tiles.size() / 4)});
}

void btOpenClBuoyancyBackend::Impl::pushPose(const Eigen::Isometry3d& pose, const Eigen::Vector3d& com) {
    const Eigen::Matrix3d R = pose.linear();
    const Eigen::Vector3d t = pose.translation() - com;
    const double b[15] = {R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1),
                          R(2, 2), t.x(),   t.y(),   t.z(),   com.x(),  com.y(),  com.z()};
    params.insert(params.end(), b, b + 15);
}

void btOpenClBuoyancyBackend::Impl::launch(cl::Kernel& kernel, DeviceBuffer& samples, DeviceBuffer& state,
                                           int nterms, std::size_t nb) {
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

void btOpenClBuoyancyBackend::Impl::computeHydro() {
    hydroDone = substep;
    bodies.clear();
    index.clear();
    fallback.clear();
    const btWaterSurface* water = world->getWater();
    if (!water) return;
    const double time = world->getTime();
    if (!packWater(*water, time)) return;
    params.clear();
    tiles.clear();
    bodyTiles.clear();
    for (const btBuoyancyDeviceBody* a : world->getDeviceBodies()) {
        btBuoyancyDeviceRecord record;
        if (!a->deviceRecord(*water, time, record) || !record.samples || record.samples->size() == 0) continue;
        const std::size_t slot = hydroSlotFor(record);
        index[a] = bodies.size();
        bodies.emplace_back();
        Body& body = bodies.back();
        body.body = a;
        body.pose = record.pose;
        body.com = record.com;
        body.record = std::move(record);
        body.hydroSlot = slot;
        pushPose(body.pose, body.com);
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

void btOpenClBuoyancyBackend::Impl::computeDrag() {
    dragDone = substep;
    if (bodies.empty() || !waterDrag) return;
    params.clear();
    tiles.clear();
    bodyTiles.clear();
    std::vector<std::size_t> which;
    const double rho = world->getFluidDensity();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
        Body& b = bodies[i];
        const btBuoyancyDeviceRecord& r = b.record;
        if (!b.valid || !r.dragOn || !r.dragClusters) continue;
        const buoyancy::DragClusters& c = *r.dragClusters;
        if (c.size() == 0) continue;
        b.body->dragEvaluationVelocity(b.h, dt, b.v, b.w);
        // The same linear damping as the CPU path: the viscous part plus the radiation damping faded by depth.
        const double damping = b.body->linearDampingNow(b.h, b.pose);
        const std::size_t slot = dragSlotFor(c);
        const std::size_t k = which.size();
        which.push_back(i);
        pushPose(b.pose, b.com);
        const double extra[9] = {b.v.x(), b.v.y(), b.v.z(), b.w.x(), b.w.y(), b.w.z(),
                                 0.5 * rho * r.dragCoefficient, 0.5 * rho * r.skinFriction,
                                 rho * damping};
        params.insert(params.end(), extra, extra + 9);
        params.resize((k + 1) * kBodyStride, 0.0);
        addTiles(k, dragSlots[slot].offset, dragSlots[slot].count,
                 stateFor(dragState, dragStateUsed, b.body, dragSlots[slot].count));
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
