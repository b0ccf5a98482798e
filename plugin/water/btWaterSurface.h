#pragma once
/// @file btWaterSurface.h
/// The water-surface seam (DESIGN-NOTES 2.8): anything that answers "height (and velocity) at x, z, t".
/// Bodies query it once per substep in batch form, so a surface costs one virtual call per body, not one
/// per sample. World y is up; the water is a height field y = f(x, z, t).

#include <cstddef>

/// Abstract water surface. Implementations must be thread-safe for concurrent const calls.
class btWaterSurface {
public:
    virtual ~btWaterSurface() = default;

    /// Surface heights f(x_i, z_i, t) for n points.
    /// @param[in] x,z   #n world coordinates, m
    /// @param[in] t     simulation time, s
    /// @param[out] outHeight  #n heights, m (world y)
    virtual void heights(const double* x, const double* z, std::size_t n, double t, double* outHeight) const = 0;

    /// Water velocity at n points below the surface (currents, orbital velocity), m/s. Default: still water.
    virtual void velocities(const double* x, const double* y, const double* z, std::size_t n, double t,
                            double* outVx, double* outVy, double* outVz) const;

    /// Lower and upper bound of the surface height over the world x–z rectangle [minX,maxX]×[minZ,maxZ] at
    /// time t, m. A body entirely above outMax or below outMin is skipped or takes a constant result.
    virtual void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& outMin,
                              double& outMax) const = 0;

    /// True when the surface is the horizontal plane y = outHeight at time t (exact clipping applies).
    virtual bool isFlat(double t, double& outHeight) const {
        (void)t;
        (void)outHeight;
        return false;
    }

    /// True when the surface changes over time (bodies in it are kept awake).
    virtual bool isTimeVarying() const { return false; }

    /// Convenience single-point query, m.
    double height(double x, double z, double t) const {
        double h = 0;
        heights(&x, &z, 1, t, &h);
        return h;
    }
};

/// Flat, still (or uniformly flowing) water at y = height.
class btFlatWaterSurface : public btWaterSurface {
public:
    /// @param height  water level, m (world y); typical 0
    /// @param currentX,currentZ  uniform horizontal current, m/s; typical 0
    explicit btFlatWaterSurface(double height = 0.0, double currentX = 0.0, double currentZ = 0.0)
        : m_height(height), m_currentX(currentX), m_currentZ(currentZ) {}

    void heights(const double* x, const double* z, std::size_t n, double t, double* outHeight) const override;
    void velocities(const double* x, const double* y, const double* z, std::size_t n, double t, double* outVx,
                    double* outVy, double* outVz) const override;
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& outMin,
                      double& outMax) const override;
    bool isFlat(double t, double& outHeight) const override;

    /// Water level, m.
    double level() const { return m_height; }
    /// Move the water level, m.
    void setLevel(double height) { m_height = height; }

private:
    double m_height;
    double m_currentX;
    double m_currentZ;
};
