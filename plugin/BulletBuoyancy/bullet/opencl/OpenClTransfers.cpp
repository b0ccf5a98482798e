/// @file OpenClTransfers.cpp
/// The OpenCL backend's transfers in the device's scalar: doubles are converted to float on a float device.

#include <BulletBuoyancy/bullet/opencl/OpenClBackendImpl.h>

using namespace buoyancy::opencl;

void btOpenClBuoyancyBackend::Impl::write(DeviceBuffer& b, const double* data, std::size_t n,
                                          std::size_t offsetReals, bool blocking) {
    if (n == 0) return;
    const cl_bool block = blocking ? CL_TRUE : CL_FALSE;
    if (dbl) {
        q.enqueueWriteBuffer(b.buffer, block, offsetReals * 8, n * 8, data);
    } else {
        b.staging.assign(data, data + n);
        q.enqueueWriteBuffer(b.buffer, block, offsetReals * 4, n * 4, b.staging.data());
    }
}

void btOpenClBuoyancyBackend::Impl::uploadIfChanged(DeviceBuffer& b, const std::vector<double>& v) {
    if (b.bytes >= v.size() * realSize && b.last == v) return;
    b.last = v;
    b.reserve(ctx, v.size() * realSize);
    write(b, b.last.data(), b.last.size());
}

void btOpenClBuoyancyBackend::Impl::upload(DeviceBuffer& b, const std::vector<double>& v, bool blocking) {
    b.reserve(ctx, v.size() * realSize);
    write(b, v.data(), v.size(), 0, blocking);
}

void btOpenClBuoyancyBackend::Impl::uploadInts(DeviceBuffer& b, const std::vector<cl_int>& v, bool blocking) {
    b.reserve(ctx, v.size() * sizeof(cl_int));
    if (!v.empty())
        q.enqueueWriteBuffer(b.buffer, blocking ? CL_TRUE : CL_FALSE, 0, v.size() * sizeof(cl_int), v.data());
}

void btOpenClBuoyancyBackend::Impl::read(DeviceBuffer& b, std::size_t n, std::vector<double>& dst) {
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

void btOpenClBuoyancyBackend::Impl::setReal(cl::Kernel& k, int arg, double value) {
    if (dbl)
        k.setArg(arg, value);
    else
        k.setArg(arg, float(value));
}
