/// @file OpenClSampleSlots.cpp
/// The OpenCL backend's sample slots: every mesh's samples and every action's drag clusters in one device buffer each,
/// and the re-bake of deformable meshes on the device (kernels/rebake.cl).

#include <BulletBuoyancy/bullet/opencl/OpenClBackendImpl.h>

using namespace buoyancy::opencl;

void btOpenClBuoyancyBackend::Impl::fingerprint(const std::vector<double>& a, const std::vector<double>& b,
                                                double* out) {
    out[0] = double(a.size());
    out[1] = a.empty() ? 0.0 : a.front();
    out[2] = b.empty() ? 0.0 : b.back();
}

std::size_t btOpenClBuoyancyBackend::Impl::hydroSlotFor(const btBuoyancyDeviceRecord& r) {
    const void* key = r.samplesOwner.get();
    for (std::size_t i = 0; i < hydroSlots.size(); ++i)
        if (hydroSlots[i].key == key) return i;
    const buoyancy::SurfaceSamples& s = *r.samples;
    MeshSlot slot;
    slot.key = key;
    slot.keep = r.samplesOwner;
    slot.deformable = r.deformable;
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

std::size_t btOpenClBuoyancyBackend::Impl::dragSlotFor(const buoyancy::DragClusters& c) {
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

void btOpenClBuoyancyBackend::Impl::syncHydroSamples() {
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

void btOpenClBuoyancyBackend::Impl::uploadMap(MeshSlot& s, const buoyancy::RebakeMap& map) {
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

void btOpenClBuoyancyBackend::Impl::runRebake(MeshSlot& s, const buoyancy::RebakeMap& map, DeviceBuffer& outBuf,
                                              std::size_t first) {
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
