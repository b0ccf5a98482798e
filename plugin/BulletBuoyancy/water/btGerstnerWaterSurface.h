#pragma once
/// @file btGerstnerWaterSurface.h
/// A sum of Gerstner (trochoidal) waves (design.md 2.8). Wave i has amplitude A_i, wavelength
/// λ_i, wavenumber k_i = 2π/λ_i, deep-water dispersion ω_i² = g k_i, unit direction d_i in the x–z plane,
/// steepness Q_i and phase φ_i. The water particle at rest position x₀ = (x₀, z₀) is at
///     x = x₀ − Σ Q_i A_i d_i sin θ_i,   y = h + Σ A_i cos θ_i,   θ_i = k_i d_i·x₀ − ω_i t + φ_i.
/// The surface is a height field only while Σ Q_i A_i k_i < 1 (else it loops): such waves are rejected.
/// The height at a given (x, z) inverts the horizontal displacement by Newton's method (see restPosition).
/// The batch queries (heights, velocities and their cached forms) run 2, 4 or 8 points at a time in SIMD lanes
/// (VectorMath.h; SSE2, or AVX2 / AVX-512 picked at run time): one vector sin/cos per wave at the start guess,
/// then each Newton step updates sin θ and cos θ by the rotation through its small phase change instead of
/// evaluating them again, and a step small enough ends the solve as a third-order (Chebyshev) step. Warm-started
/// from the cache, which extrapolates each point's displacement linearly in time, a body's points cost one
/// sin/cos per wave and one step.

#include <BulletBuoyancy/water/btWaterSurface.h>

#include <vector>

/// One Gerstner wave.
struct btGerstnerWave {
    double amplitude = 0.5;    ///< A, m, ≥ 0
    double wavelength = 40.0;  ///< λ, m, > 0
    double directionX = 1.0;   ///< direction of travel in the x–z plane (normalised by the surface), world x
    double directionZ = 0.0;   ///< world z
    double steepness = 0.5;    ///< Q, dimensionless, ≥ 0 (0: a pure sine wave, no horizontal motion)
    double phase = 0.0;        ///< φ, radians
};

/// Gerstner waves around the mean level h.
class btGerstnerWaterSurface : public btWaterSurface {
public:
    /// @param waves    the waves (may be empty: flat water at h)
    /// @param height   mean water level h, m (world y)
    /// @param gravity  g = |gravity|, m/s² (9.81), > 0; sets ω_i = sqrt(g k_i)
    /// @throws std::invalid_argument naming the bad wave and field ("waves[2].wavelength: ..."), and when
    ///         Σ Q_i A_i k_i ≥ 1 (the surface loops and is no longer a height field)
    explicit btGerstnerWaterSurface(const std::vector<btGerstnerWave>& waves, double height = 0.0,
                                    double gravity = 9.81);

    /// Each point's rest position is found from a cold start (x₀ = x), see restPosition. Accuracy: the inversion
    /// ends with a step ≤ finishTolerance(), so the remaining error of the height is ≲ 1e-14 Σ A_i, plus the
    /// rounding of the phases far from the origin (≈ 1e-16 k |x| A / (1 − Σ Q A k)); tests/water/
    /// GerstnerBatchTest.cpp checks ≤ 1e-12 Σ A against an independent long-double evaluation.
    void heights(const double* x, const double* z, std::size_t n, double t, double* outHeight) const override;
    /// Orbital velocity of linear wave theory: the surface particle velocity of each wave (∂/∂t of the
    /// parametric surface above) scaled by min(1, e^{k_i (y − h)}), evaluated at the rest position of (x, z).
    void velocities(const double* x, const double* y, const double* z, std::size_t n, double t, double* outVx,
                    double* outVy, double* outVz) const override;
    /// The acceleration of the trochoidal wave's particle that is at (x, y, z), m/s²: its rest position (x₀, z₀) and
    /// rest height y₀ solve x = x₀ − Σ Q A e d sin θ, y = y₀ + Σ A e cos θ with e = e^{k_i min(0, y₀ − h)} (Newton's
    /// method), and a = Σ (Q A ω² e d sin θ, −A ω² e cos θ), towards the centre of its orbit. At the surface it is
    /// the second time derivative of the parametric surface; below, the particle's own phase and decay (velocities()
    /// takes the surface particle's phase: they differ at second order in the slope), so that along a closed orbit
    /// it has no mean and a body carried by the water keeps its depth. One scalar solve per point from a cold start.
    void accelerations(const double* x, const double* y, const double* z, std::size_t n, double t, double* outAx,
                       double* outAy, double* outAz) const override;
    /// Fast path for bodies (one call per body per substep): the same inversion to the same accuracy, started
    /// from each point's displacement x − x₀ extrapolated linearly in time from the last two calls kept in
    /// `cache` (cache.a/b: [0, n) the last displacement, [n, 2n) the one before; a[2n], a[2n+1] their times,
    /// a[2n+2] how many of them are set).
    /// A point that moves smoothly is then ~1e-5 m from its solution and needs one sin/cos evaluation of the
    /// waves and one finishing step, instead of 3–4 evaluations from a cold start. Calls at the same time (as
    /// heightsCached then velocitiesCached) reuse the last solution. The cache is (re)initialised when its owner
    /// or size differ.
    void heightsCached(const double* x, const double* z, std::size_t n, double t, double* outHeight,
                       btWaterQueryCache& cache) const override;
    /// velocities() warm-started from `cache`: right after heightsCached at the same points and time every
    /// point is already converged, so each costs one evaluation of the waves (plus e^{k_i (y − h)} below h).
    /// Accuracy as heights(), relative to Σ A_i ω_i.
    void velocitiesCached(const double* x, const double* y, const double* z, std::size_t n, double t,
                          double* outVx, double* outVy, double* outVz, btWaterQueryCache& cache) const override;
    /// h ± Σ A_i (independent of the rectangle).
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& outMin,
                      double& outMax) const override;
    /// Flat only with no waves (or all amplitudes 0).
    bool isFlat(double t, double& outHeight) const override;
    bool isTimeVarying() const override { return m_amplitudeSum > 0; }
    /// The shortest wavelength among the waves of non-zero amplitude, m (0 with none).
    double shortestWavelength() const override { return m_shortestWavelength; }
    /// True while there are waves: each height query inverts the horizontal displacement by Newton's method.
    bool prefersHeightPatch() const override { return m_amplitudeSum > 0; }
    /// Σ A_i k_i³ / (1 − Σ Q_i A_i k_i)²: a wave's third derivative is A k³ at Q = 0 and grows near steep crests as
    /// the horizontal map x₀ → x compresses (its Jacobian is ≥ 1 − Σ Q A k; design.md 2.8).
    double heightThirdDerivativeScale(double t) const override;
    bool describeForDevice(double t, btWaterDeviceDescription& out) const override;
    /// A copy (the waves are immutable; setSimdLanes renews the revision). Only for this class itself: a subclass that
    /// overrides a query gets nullptr unless it overrides this too.
    std::unique_ptr<btWaterSurface> cloneForQueriesAhead() const override;

    /// Forward parametric surface: the point (x, y, z) of the particle at rest position (x0, z0) at time t, m.
    void surfacePoint(double x0, double z0, double t, double& outX, double& outY, double& outZ) const;

    /// Rest position (x0, z0) of the particle that is at horizontal position (x, z) at time t: solves
    /// x0 − Σ Q A d sin θ(x0) = x by Newton's method (Jacobian I − Σ Q A k cos θ d dᵀ, invertible while
    /// Σ Q A k < 1), starting from x0 = x, until a Newton step is ≤ stepTolerance() (which it still applies), so
    /// the remaining error of x0 is ≤ κ·tol² with κ = ½ Σ Q A k² / (1 − Σ Q A k). Hard limit kMaxIterations (a
    /// fixed-point step, a contraction with factor Σ Q A k, replaces any Newton step that does not reduce the
    /// residual). The scalar reference of the batch queries (which take it for the rare point their vector
    /// path does not settle).
    /// @param outIterations  optional: Newton steps used (3–5 from a cold start for Σ Q A k ≤ 0.6)
    void restPosition(double x, double z, double t, double& outX0, double& outZ0, int* outIterations = nullptr) const;

    /// Newton (or fallback) steps restPosition (and the batch queries' scalar fallback) take at most.
    static constexpr int kMaxIterations = 50;
    /// Newton-step size below which the inversion stops, m: tol = sqrt(1e-14 / (κ k_max)) (capped at
    /// 1e-3 / k_max), so the neglected κ tol² moves heights and velocities by ≤ 1e-14 of their amplitude sums;
    /// a point at distance |x| from the origin uses at least a few ulps of |x| / (1 − Σ Q A k).
    double stepTolerance() const { return m_tolStep; }
    /// Newton-step size below which the batch queries end with one third-order step, m: the step then leaves an
    /// error ≤ C tol³ with C = 2 g (c₃/6 + g c₂²), g = 1/(1 − Σ Q A k), c_j = Σ Q A k^j; tol makes k_max C tol³ ≤
    /// 1e-14 (capped at 1e-3 / k_max).
    double finishTolerance() const { return m_tolFinish; }
    /// Points the batch queries process at once: 8 (AVX-512), 4 (AVX2) or 2 (SSE2, the baseline), the widest
    /// the CPU supports (checked at construction); the results are bit for bit the same at every width.
    int simdLanes() const { return m_lanes; }
    /// Use at most `lanes` SIMD lanes (2, 4 or 8; rounded down to what the CPU supports). For tests and benchmarks.
    void setSimdLanes(int lanes);
    /// Σ Q_i A_i k_i (< 1 for every accepted surface).
    double loopFactor() const { return m_loop; }
    /// Mean level h, m.
    double meanLevel() const { return m_height; }
    /// Σ A_i, m.
    double amplitudeSum() const { return m_amplitudeSum; }
    /// The per-wave constants the queries use, for device backends (btOpenClBuoyancyBackend): 7 values
    /// per wave: A (m), k (1/m), ω (1/s), d_x, d_z (unit direction), Q·A (m), φ (rad).
    std::vector<double> packedWaveConstants() const {
        std::vector<double> out;
        for (const Wave& w : m_waves) out.insert(out.end(), {w.a, w.k, w.omega, w.dx, w.dz, w.qa, w.phase});
        return out;
    }

private:
    /// Per-wave constants, precomputed once (θ = kdx·x₀ + kdz·z₀ + (φ − ω t)).
    struct Wave {
        double a, k, omega, dx, dz, qa, phase;
        double kdx, kdz;        ///< k d, 1/m
        double qadx, qadz;      ///< Q A d, m
        double jxx, jxz, jzz;   ///< Q A k d dᵀ (Jacobian term, times cos θ)
        double aw, qaw;         ///< A ω, Q A ω, m/s (velocity amplitudes)
        double qak2;            ///< Q A k², 1/m (second derivative of the displacement)
        double qawdx, qawdz;    ///< Q A ω d, m/s
    };
    /// Newton solve of x₀ − D(x₀) = (x, z) from the guess (x0, z0), updated in place; returns the steps taken.
    /// ySum = Σ A cos θ at the returned x₀; with Velocity, vel[0..2] = orbital velocity there at height
    /// yRel = y − h (decay e^{k min(0, yRel)}).
    template <bool Velocity>
    int solve(double x, double z, double t, double& x0, double& z0, double& ySum, double yRel, double* vel) const;
    /// The batch kernels (btGerstnerWaterSurface.cpp): one per SIMD width, picked at run time (m_lanes).
    struct Kernel;
    friend struct Kernel;
    /// The batch queries: heights (outH, may be null) and, with Velocity, velocities at n points. Warm start
    /// (disp non-null): disp = {x, z, previous x, previous z} displacement arrays; the guess is
    /// x₀ = x − (d + rho (d − d_prev)); with shift the previous displacement takes d before d takes x − x₀.
    template <bool Velocity>
    void batch(const double* x, const double* y, const double* z, std::size_t n, double t, double* const* disp,
               double rho, bool shift, double* outH, double* outVx, double* outVy, double* outVz) const;
    /// Warm-start arrays of `cache` for n points at time t: disp pointers, extrapolation factor and shift flag
    /// (see batch); (re)initialises the cache when it belongs to another surface or size.
    void warmStart(btWaterQueryCache& cache, std::size_t n, double t, double* disp[4], double& rho, bool& shift) const;
    /// Newton-step tolerance for a point at (x, z), m (stepTolerance() or the rounding floor there).
    double pointTolerance(double x, double z) const;
    std::vector<Wave> m_waves;
    double m_height;
    double m_amplitudeSum = 0;
    double m_shortestWavelength = 0;  ///< m
    double m_loop = 0;
    double m_tolStep = 1.0;   ///< stepTolerance(), m
    double m_tolFinish = 1.0; ///< finishTolerance(), m
    double m_noise = 0;       ///< rounding floor of a Newton step per metre of |x|: a few ulps / (1 − Σ Q A k)
    int m_lanes = 2;          ///< simdLanes()
};
