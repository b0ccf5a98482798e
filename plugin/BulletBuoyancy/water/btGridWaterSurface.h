#pragma once
/// @file btGridWaterSurface.h
/// A user-supplied height grid (and optional water-velocity grid), bilinear, periodic or clamped
/// (design.md 2.8). For users who run their own water simulation: replace the heights every
/// frame with setHeights (not concurrently with queries).
///
/// Layout: sample (i, j), i = 0..nx−1 along x, j = 0..nz−1 along z, is at world
/// (originX + i·spacing, originZ + j·spacing) and stored at index j·nx + i (rows = z, columns = x).
/// Periodic: the grid repeats with period nx·spacing in x and nz·spacing in z (sample nx wraps to 0).
/// Clamped: outside the grid the nearest edge value holds.

#include <BulletBuoyancy/water/btWaterSurface.h>

#include <vector>

/// Bilinear height (and velocity) grid.
class btGridWaterSurface : public btWaterSurface {
public:
    /// @param nx,nz     samples along x and z, ≥ 2 each
    /// @param spacing   distance between samples, m, > 0
    /// @param originX,originZ  world position of sample (0, 0), m
    /// @param heights   nx·nz heights, m (world y), finite
    /// @param periodic  wrap around (true) or clamp to the edges (false)
    /// @throws std::invalid_argument naming the bad parameter
    btGridWaterSurface(int nx, int nz, double spacing, double originX, double originZ, std::vector<double> heights,
                       bool periodic);

    /// Replace every height (same size), e.g. once per frame. @throws std::invalid_argument (unchanged)
    void setHeights(const std::vector<double>& heights);
    /// Water velocity samples (3 arrays of nx·nz, m/s), interpolated like the heights; empty arrays: still
    /// water. @throws std::invalid_argument for a wrong size or a non-finite value
    void setVelocities(std::vector<double> vx, std::vector<double> vy, std::vector<double> vz);
    /// Mark the grid as changing over time (bodies in it are kept awake). Default false.
    void setTimeVarying(bool varying) { m_timeVarying = varying; }

    void heights(const double* x, const double* z, std::size_t n, double t, double* outHeight) const override;
    void velocities(const double* x, const double* y, const double* z, std::size_t n, double t, double* outVx,
                    double* outVy, double* outVz) const override;
    /// Min/max of the samples of every cell touching the rectangle (bilinear values lie between them).
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& outMin,
                      double& outMax) const override;
    bool isTimeVarying() const override { return m_timeVarying; }
    /// The sample lattice (bilinear in every cell; outside a clamped grid the edge values hold, still bilinear).
    bool describeForDevice(double t, btWaterDeviceDescription& out) const override;
    bool bilinearLattice(double t, btWaterLattice& out) const override {
        (void)t;
        out.originX = m_originX;
        out.originZ = m_originZ;
        out.spacingX = out.spacingZ = m_spacing;
        return true;
    }

    int sizeX() const { return m_nx; }
    int sizeZ() const { return m_nz; }
    double spacing() const { return m_spacing; }
    const std::vector<double>& heightSamples() const { return m_h; }
    /// World position of sample (0, 0), m, and the wrap mode, for device backends.
    double originX() const { return m_originX; }
    double originZ() const { return m_originZ; }
    bool isPeriodic() const { return m_periodic; }
    /// Water-velocity samples (empty: still water), m/s, same layout as heightSamples().
    const std::vector<double>& velocitySamplesX() const { return m_vx; }
    const std::vector<double>& velocitySamplesY() const { return m_vy; }
    const std::vector<double>& velocitySamplesZ() const { return m_vz; }

private:
    /// Bilinear lookup of `field` at (x, z).
    double sample(const std::vector<double>& field, double x, double z) const;
    /// Sample index along one axis (wrapped or clamped).
    int wrap(long long i, int n) const;
    void updateRange();

    int m_nx, m_nz;
    double m_spacing, m_originX, m_originZ;
    std::vector<double> m_h, m_vx, m_vy, m_vz;
    bool m_periodic;
    bool m_timeVarying = false;
    double m_min = 0, m_max = 0;
};
