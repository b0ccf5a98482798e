/// @file OpenClWaterPacking.cpp
/// The OpenCL backend's water: the surface's own device description packed for kernels/water.cl.

#include <BulletBuoyancy/bullet/opencl/OpenClBackendImpl.h>

#include <cmath>

using namespace buoyancy::opencl;

bool btOpenClBuoyancyBackend::Impl::packWater(const btWaterSurface& water, double t) {
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
