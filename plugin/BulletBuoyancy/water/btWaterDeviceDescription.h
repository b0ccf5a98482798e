#pragma once
/// @file btWaterDeviceDescription.h
/// What a water surface tells a device backend about itself (btWaterSurface::describeForDevice, design.md 2.8): one of
/// the kinds the device kernels evaluate, with its parameters at one time. The backend packs it for its kernels; it
/// never needs to know the surface's class, so a new surface reaches the device by describing itself as one of
/// these kinds, and any other surface keeps its bodies on the CPU with the reason it gives.

#include <string>
#include <vector>

/// A water surface as the device kernels see it at one time. Fields belong to the kind named in their comment.
struct btWaterDeviceDescription {
    /// The kinds of water the device kernels evaluate.
    enum class Kind {
        None,       ///< not evaluated on a device (the reason says why): its bodies use the CPU
        Flat,       ///< flat water at `level` with a uniform current
        Gerstner,   ///< a sum of Gerstner waves about `meanLevel`, inverted by Newton's method
        HeightGrid  ///< heights sampled on a rectangular grid, bilinear between samples
    };
    Kind kind = Kind::None;  ///< what the surface is on the device
    std::string reason;      ///< Kind::None: why the surface is not evaluated on a device (one line)

    double level = 0.0;     ///< Flat: water height, m
    double currentX = 0.0;  ///< Flat: uniform current along x, m/s
    double currentZ = 0.0;  ///< Flat: uniform current along z, m/s

    double meanLevel = 0.0;              ///< Gerstner: mean water height, m
    std::vector<double> waveConstants;   ///< Gerstner: 7 per wave (btGerstnerWaterSurface::packedWaveConstants)
    int maxIterations = 0;               ///< Gerstner: Newton iteration limit of the inversion, ≥ 1

    int sizeX = 0;            ///< HeightGrid: samples along x, ≥ 2
    int sizeZ = 0;            ///< HeightGrid: samples along z, ≥ 2
    double spacing = 0.0;     ///< HeightGrid: distance between samples, m, > 0
    double originX = 0.0;     ///< HeightGrid: world x of sample (0, 0), m
    double originZ = 0.0;     ///< HeightGrid: world z of sample (0, 0), m
    bool periodic = false;    ///< HeightGrid: wrap around (true) or clamp at the border (false)
    std::vector<double> heights;  ///< HeightGrid: world heights, index j·sizeX + i, m
    /// HeightGrid: water-velocity samples, same layout as `heights`, m/s; all three empty for still water.
    std::vector<double> velocityX, velocityY, velocityZ;
    /// HeightGrid: false when the water's velocity is not in the description: the drag stays on the CPU.
    bool velocityOnDevice = true;
};
