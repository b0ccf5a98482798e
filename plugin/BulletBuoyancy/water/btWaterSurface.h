#pragma once
/// @file btWaterSurface.h
/// The water-surface seam (design.md 2.8): anything that answers "height (and velocity) at x, z, t".
/// Bodies query it once per substep in batch form, so a surface costs one virtual call per body, not one
/// per sample. World y is up; the water is a height field y = f(x, z, t).

#include <BulletBuoyancy/water/btWaterDeviceDescription.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

/// A rectangular lattice of horizontal cells: vertical lines x = originX + i·spacingX and z = originZ + j·spacingZ
/// for every integer i, j (world, m).
struct btWaterLattice {
    double originX = 0.0;   ///< x of one lattice line, m
    double originZ = 0.0;   ///< z of one lattice line, m
    double spacingX = 0.0;  ///< distance between lines along x, m, > 0
    double spacingZ = 0.0;  ///< distance between lines along z, m, > 0
};

class btWaterSurface;

/// Per-caller memory kept between batch queries (one per body and point set, owned by the caller, never used by
/// two threads at once). A surface whose query is an iterative solve keeps its last solution here to warm-start
/// the next query (Gerstner: each point's horizontal displacement x − x₀). Contents are surface-specific; the
/// surface resets them when `owner` or `n` do not match. Surfaces that need nothing ignore it.
struct btWaterQueryCache {
    const btWaterSurface* owner = nullptr;  ///< surface that filled the arrays (nullptr: empty)
    std::size_t n = 0;                      ///< number of points the arrays hold
    std::vector<double> a, b;               ///< per-point state, surface-specific
    /// Forget everything (the next query starts cold).
    void reset() {
        owner = nullptr;
        n = 0;
    }
};

/// Abstract water surface. Implementations must be thread-safe for concurrent const calls.
class btWaterSurface {
public:
    virtual ~btWaterSurface() = default;

    /// A number naming this surface object and the parameters it answers with: different for every surface object
    /// created (copies included) and renewed by every setter that changes its answers (touchRevision). Two surfaces
    /// reached at the same address with the same revision answer alike.
    std::uint64_t getRevision() const { return m_revision; }

    /// A copy of this surface that answers every query bit for bit as it does, for queries made ahead of time on
    /// another thread while the caller is free to change or destroy this one (btBuoyancyWorld queries the heights of
    /// the next exact evaluations' wave patches while Bullet steps; btBuoyancyWorld::getLastQueriedAhead). The copy is
    /// made when the surface or its revision is new to the world, never per substep. Default: nullptr (no query is made
    /// ahead on this surface). A subclass that overrides a query must override this too, or leave it nullptr.
    virtual std::unique_ptr<btWaterSurface> cloneForQueriesAhead() const { return nullptr; }

    /// Surface heights f(x_i, z_i, t) for n points.
    /// @param[in] x,z   #n world coordinates, m
    /// @param[in] t     simulation time, s
    /// @param[out] outHeight  #n heights, m (world y)
    virtual void heights(const double* x, const double* z, std::size_t n, double t, double* outHeight) const = 0;

    /// Water velocity at n points below the surface (currents, orbital velocity), m/s. Default: still water.
    virtual void velocities(const double* x, const double* y, const double* z, std::size_t n, double t,
                            double* outVx, double* outVy, double* outVz) const;

    /// The water's acceleration Du/Dt at n points below the surface (design.md 2.7, "The water's acceleration"), in the
    /// same coordinates as velocities(): what accelerates a small body carried by the water (its added mass acts on
    /// the acceleration relative to it). Default: the local acceleration ∂u/∂t at the fixed points, a central
    /// difference of velocities() at t ± kAccelerationTimeStep (two velocity queries per call, no allocation); the
    /// convective part (u·∇)u, second order in the wave slope for waves, is left out, and a surface whose velocities
    /// do not depend on t (a steady current, a simulation stepped elsewhere) gets zero.
    /// @param[in] x,y,z  #n coordinates, m
    /// @param[in] t      simulation time, s
    /// @param[out] outAx,outAy,outAz  #n accelerations, m/s²
    virtual void accelerations(const double* x, const double* y, const double* z, std::size_t n, double t,
                               double* outAx, double* outAy, double* outAz) const;

    /// Time step of the default accelerations()' central difference, s.
    static constexpr double kAccelerationTimeStep = 1e-3;

    /// heights() with per-caller warm-start memory: same results (to the surface's documented tolerance), faster
    /// when the points move little between calls. Default: ignores the cache.
    virtual void heightsCached(const double* x, const double* z, std::size_t n, double t, double* outHeight,
                               btWaterQueryCache& cache) const {
        (void)cache;
        heights(x, z, n, t, outHeight);
    }

    /// velocities() with per-caller warm-start memory (after heightsCached at the same points and time, a
    /// Gerstner surface needs no further iteration). Default: ignores the cache.
    virtual void velocitiesCached(const double* x, const double* y, const double* z, std::size_t n, double t,
                                  double* outVx, double* outVy, double* outVz, btWaterQueryCache& cache) const {
        (void)cache;
        velocities(x, y, z, n, t, outVx, outVy, outVz);
    }

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

    /// True when a height query is costlier than interpolating a small per-body grid of heights (an iterative solve,
    /// such as the Gerstner surface's inversion of its horizontal displacement): bodies then query the nodes of a
    /// patch over their footprint once per substep and interpolate (design.md 2.5, btBuoyancySettings::waterPatchNodes).
    /// False (the default) for surfaces that answer by a lookup or a closed form: the patch would cost more and smooth
    /// their short ripples away.
    virtual bool prefersHeightPatch() const { return false; }

    /// Shortest horizontal length scale of the surface's shape (the shortest wavelength), m; 0 when unknown. Sizes the
    /// per-body wave patch (btBuoyancySettings::waterPatchNodesPerWavelength).
    virtual double shortestWavelength() const { return 0.0; }

    /// Scale of the height field's third horizontal derivatives at time t, 1/m²: the largest |D³f[d, d, d]| over unit
    /// horizontal directions d, as an estimate (not a strict bound). The exact-mesh evaluation on waves samples the
    /// water over each wet triangle finely enough for this (design.md 2.5: a triangle of size h is split while
    /// scale × h³ is large against the body's thickness). 0: the surface is flat or quadratic. Default: from
    /// shortestWavelength() λ and heightBounds() over the origin, (f_max − f_min)/2 · (2π/λ)³; 0 when λ is unknown.
    virtual double heightThirdDerivativeScale(double t) const;

    /// True when, at time t, the height field is bilinear in every cell of the rectangular lattice `out` (a user
    /// grid, an FFT ocean without horizontal displacement): within a cell it is a + b x + c z + d x z, with slope
    /// kinks only on the lattice lines. The exact-mesh evaluation then cuts triangles along those lines and is exact
    /// for this water (design.md 2.5). Default: false.
    virtual bool bilinearLattice(double t, btWaterLattice& out) const {
        (void)t;
        (void)out;
        return false;
    }

    /// Describe the surface at time t for a device backend (btWaterDeviceDescription): fill `out` as one of the kinds the
    /// device evaluates and return true, or return false with `out.reason` set (its bodies then use the CPU).
    /// `out` may hold a previous description: every field of the kind returned is written (reusing its storage).
    /// Default: false, "surface type not evaluated on the device".
    virtual bool describeForDevice(double t, btWaterDeviceDescription& out) const;

    /// Convenience single-point query, m.
    double height(double x, double z, double t) const {
        double h = 0;
        heights(&x, &z, 1, t, &h);
        return h;
    }

protected:
    btWaterSurface() : m_revision(nextRevision()) {}
    /// A copy is another surface object: it gets its own revision.
    btWaterSurface(const btWaterSurface&) : m_revision(nextRevision()) {}
    btWaterSurface& operator=(const btWaterSurface&) {
        m_revision = nextRevision();
        return *this;
    }
    /// Renew the revision: call from every setter that changes the surface's answers.
    void touchRevision() { m_revision = nextRevision(); }

private:
    static std::uint64_t nextRevision();
    std::uint64_t m_revision;
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
    /// Zero: the level and the current are steady, m/s².
    void accelerations(const double* x, const double* y, const double* z, std::size_t n, double t, double* outAx,
                       double* outAy, double* outAz) const override;
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& outMin,
                      double& outMax) const override;
    bool isFlat(double t, double& outHeight) const override;
    bool describeForDevice(double t, btWaterDeviceDescription& out) const override;

    /// Water level, m.
    double level() const { return m_height; }
    /// Move the water level, m.
    void setLevel(double height) { m_height = height; }

private:
    double m_height;
    double m_currentX;
    double m_currentZ;
};
