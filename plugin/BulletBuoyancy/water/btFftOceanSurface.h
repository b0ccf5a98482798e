#pragma once
/// @file btFftOceanSurface.h
/// A periodic ocean patch synthesised from a wave spectrum and evolved in time (Tessendorf, "Simulating
/// Ocean Water", SIGGRAPH course notes 2001), design.md 2.8. The field is recomputed with
/// Eigen's FFT module once per time value (cached by t), never per query; queries are bilinear lookups.
///
/// Conventions (all documented here so a test can rebuild them independently):
/// - grid N×N over a square patch of side L (period L in x and z); wavevectors k = 2π/L·(m, n) with
///   m, n ∈ [−N/2, N/2); the k = 0 mode and the Nyquist row/column (m or n = −N/2) are zero.
/// - directional variance density Ψ(k) (m⁴, ∫Ψ d²k = variance of the elevation):
///   Ψ(k) = F(k)·D(θ)/k, D(θ) = (2/π) cos²(θ − θ_w) downwind (k·w > 0), 0 upwind (∫D dθ = 1);
///   Phillips: F(k) = (α/2) k⁻³ exp(−1/(k L_w)²), L_w = U²/g (α = phillipsAlpha);
///   JONSWAP: F(k) = S(ω) dω/dk with ω = sqrt(g k), S(ω) = α g² ω⁻⁵ exp(−5/4 (ω_p/ω)⁴) γ^r,
///   r = exp(−(ω − ω_p)²/(2 σ² ω_p²)), σ = 0.07 (ω ≤ ω_p) or 0.09, ω_p = 0.855 g/U (fully developed).
/// - amplitudes h0(k) = (ξ_r + i ξ_i)·sqrt(Ψ(k) Δk² / 4), ξ standard normal from the seed (mt19937_64 +
///   Box–Muller, identical on every platform), so E[Σ h²]/N² = Σ_k Ψ(k) Δk² (Parseval).
/// - h̃(k, t) = h0(k) e^{−iωt} + conj(h0(−k)) e^{iωt}, ω = sqrt(g k) (each mode travels along its k);
///   elevation η(x, t) = Σ_k h̃(k, t) e^{ik·x}; the surface is y = h + η.
/// - choppiness λ ≥ 0 moves the point at rest position x₀ to x = x₀ − λ D(x₀), D = Σ_k (−i k/|k|) h̃ e^{ik·x}
///   (the Gerstner form); the height at a given x inverts this by fixed-point iteration.

#include <BulletBuoyancy/water/btWaterSurface.h>

#include <complex>
#include <cstdint>
#include <shared_mutex>
#include <vector>

/// Parameters of btFftOceanSurface.
struct btFftOceanSettings {
    enum class Spectrum { Phillips, Jonswap };
    int resolution = 128;          ///< N, samples per side, even, 4..4096
    double patchSize = 64.0;       ///< L, m, > 0 (the ocean repeats with this period)
    double windSpeed = 10.0;       ///< U, m/s, > 0
    double windDirectionX = 1.0;   ///< wind direction (normalised), world x
    double windDirectionZ = 0.0;   ///< world z
    Spectrum spectrum = Spectrum::Phillips;
    double choppiness = 0.0;       ///< λ, ≥ 0 (0: no horizontal displacement); typical 0.5–1
    std::uint64_t seed = 1;        ///< random seed of the amplitudes
    double height = 0.0;           ///< mean level h, m
    double gravity = 9.81;         ///< g, m/s², > 0
    double phillipsAlpha = 0.0081; ///< α of the spectrum (Phillips' constant), > 0
    double jonswapGamma = 3.3;     ///< γ, peak enhancement of JONSWAP, ≥ 1
};

/// FFT ocean patch (periodic in x and z).
class btFftOceanSurface : public btWaterSurface {
public:
    /// @throws std::invalid_argument naming the bad setting
    explicit btFftOceanSurface(const btFftOceanSettings& settings);

    void heights(const double* x, const double* z, std::size_t n, double t, double* outHeight) const override;
    /// Linear (Airy) surface velocity of every mode (horizontal ω k̂ h̃, vertical ∂η/∂t), evaluated at the
    /// rest position and scaled by min(1, e^{k_p (y − h)}) with the spectral peak wavenumber k_p.
    void velocities(const double* x, const double* y, const double* z, std::size_t n, double t, double* outVx,
                    double* outVy, double* outVz) const override;
    /// Linear (Airy) acceleration ∂u/∂t of every mode (horizontal −i ω² k̂ h̃, vertical −ω² h̃), from three more fields
    /// computed once per time value like the velocity's (two inverse FFTs: x and y share one), evaluated at the rest position and scaled by
    /// min(1, e^{k_p (y − h)}) like velocities(), m/s².
    void accelerations(const double* x, const double* y, const double* z, std::size_t n, double t, double* outAx,
                       double* outAy, double* outAz) const override;
    /// h + min/max of the field at time t over the whole patch.
    void heightBounds(double minX, double minZ, double maxX, double maxZ, double t, double& outMin,
                      double& outMax) const override;
    bool isTimeVarying() const override { return true; }
    /// The shortest wave the samples hold (Nyquist): 2 L / N, m.
    double shortestWavelength() const override { return 2.0 * m_dx; }
    /// From the samples at time t: the largest third difference along x or z over dx³, divided by J³ (J the
    /// smallest Jacobian determinant of the horizontal displacement; 1 without choppiness), 1/m².
    double heightThirdDerivativeScale(double t) const override;
    /// Without choppiness the height is the bilinear lookup of the N×N samples: the lattice of spacing L/N through
    /// the origin. With choppiness the lookup is at the inverted rest position: not bilinear in x, z (false).
    bool describeForDevice(double t, btWaterDeviceDescription& out) const override;
    bool bilinearLattice(double t, btWaterLattice& out) const override;

    /// Variance density Ψ(kx, kz) of the spectrum chosen, m⁴ (see the file comment).
    double spectrumDensity(double kx, double kz) const;
    /// The elevation samples η (without h) at time t, N×N, index j·N + i at (i·L/N, j·L/N), m.
    std::vector<double> elevationField(double t) const;
    /// Iteration limit of the choppy inversion (fixed point, contraction while λ|∇D| < 1).
    static constexpr int kMaxIterations = 30;
    const btFftOceanSettings& settings() const { return m_s; }
    /// Spectral peak wavenumber k_p, rad/m.
    double peakWavenumber() const { return m_kPeak; }

private:
    using Complex = std::complex<double>;
    void ensureHeights(double t) const;   // requires m_mutex held exclusively
    void ensureVelocity(double t) const;  // requires m_mutex held exclusively
    void ensureAcceleration(double t) const;  // requires m_mutex held exclusively
    /// Which fields a query reads: the heights (and displacements) alone, or with the velocity or acceleration ones.
    enum class Fields { Heights, Velocity, Acceleration };
    /// Run `read` with the fields of time t (the heights, and the velocity or acceleration fields as `fields` says)
    /// in place: under a shared lock when they already are (concurrent queries at one time, e.g. a world's bodies in
    /// one substep, read at once), else under the exclusive lock after computing them.
    template <class Read>
    void withFields(double t, Fields fields, Read&& read) const;
    void inverseFft2(std::vector<Complex>& data) const;
    double sampleField(const std::vector<double>& f, double x, double z) const;
    void restPosition(double x, double z, double& x0, double& z0) const;  // requires fields at t
    /// The vector field (fx, fy, fz) at the n points, decayed with depth as the peak wavenumber's mode (velocities,
    /// accelerations). Requires fields at t.
    void sampleDecayed(const std::vector<double>& fx, const std::vector<double>& fy, const std::vector<double>& fz,
                       const double* x, const double* y, const double* z, std::size_t n, double* outX, double* outY,
                       double* outZ) const;

    btFftOceanSettings m_s;
    int m_n;
    double m_dk, m_dx, m_windX, m_windZ, m_kPeak;
    std::vector<Complex> m_h0;       // N×N
    std::vector<double> m_omega;     // N×N
    mutable std::shared_mutex m_mutex;  ///< exclusive: computing the fields; shared: reading them
    mutable double m_tHeights, m_tVelocity, m_tAcceleration;
    mutable std::vector<double> m_eta, m_dispX, m_dispZ, m_velX, m_velY, m_velZ, m_accX, m_accY, m_accZ;
    mutable double m_etaMin = 0, m_etaMax = 0;
    mutable double m_thirdDerivativeScale = 0;  // 1/m², at m_tHeights
    mutable std::vector<Complex> m_work;
    mutable std::vector<Complex> m_modes;  ///< the velocity's or acceleration's modes before each component (scratch)
    /// m_modes = s(ω) (h0 e^{−iωt} ± conj(h0(−k)) e^{iωt}) for every mode, with s(ω) = ω and "−" (the velocity's
    /// modes) or s(ω) = −ω² and "+" (the acceleration's).
    void fillTimeModes(double t, bool acceleration) const;
};
