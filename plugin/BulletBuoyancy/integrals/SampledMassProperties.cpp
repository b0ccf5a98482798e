/// @file SampledMassProperties.cpp
/// Mass properties from surface samples (declared in MassProperties.h): design.md 2.1, the paper's
/// eqs. 4–8 with the corrections listed there (centre divided by the mass; inertia ρ[(tr S)E − S] about the
/// origin then parallel axis; shell mass from the unsigned area, not eq. 5's A^y).

#include <BulletBuoyancy/integrals/CompensatedSum.h>
#include <BulletBuoyancy/integrals/MassProperties.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace buoyancy {

namespace {

void checkSamples(const SurfaceSamples& s, const char* fn) {
    const std::size_t n = s.px.size();
    if (n == 0) throw std::invalid_argument(std::string(fn) + ": no surface samples");
    if (s.py.size() != n || s.pz.size() != n || s.ax.size() != n || s.ay.size() != n || s.az.size() != n ||
        s.area.size() != n)
        throw std::invalid_argument(std::string(fn) + ": sample arrays have different lengths");
}

void checkPositive(double v, const char* fn, const char* what) {
    if (!std::isfinite(v) || v <= 0)
        throw std::invalid_argument(std::string(fn) + ": " + what + " must be positive and finite, got " +
                                    std::to_string(v));
}

/// Mean sample position: the integration origin (keeps the polynomial moments well conditioned).
Eigen::Vector3d samplesMean(const SurfaceSamples& s) {
    detail::CompensatedSum<3> acc;
    const std::size_t n = s.size();
    for (std::size_t b = 0; b < n; b += detail::kSumBlock) {
        const std::size_t e = std::min(n, b + detail::kSumBlock);
        double part[3] = {0, 0, 0};
        for (std::size_t i = b; i < e; ++i) {
            part[0] += s.px[i];
            part[1] += s.py[i];
            part[2] += s.pz[i];
        }
        acc.add(part);
    }
    return Eigen::Vector3d(acc.value(0), acc.value(1), acc.value(2)) / double(n);
}

/// Volume, first and second moments ∫1, ∫r, ∫rrᵀ of the enclosed solid about `o`, and the surface area,
/// from the divergence fields of design.md 2.1 (paper eqs. 4, 6, 8).
struct SolidSums {
    double volume, area;
    Eigen::Vector3d first;
    Eigen::Matrix3d second;
};

SolidSums solidSums(const SurfaceSamples& s, const Eigen::Vector3d& o) {
    // 0:V  1-3:∫x,∫y,∫z  4-6:∫x²,∫y²,∫z²  7:∫xy  8:∫yz  9:∫zx  10:area
    detail::CompensatedSum<11> acc;
    const std::size_t n = s.size();
    for (std::size_t b = 0; b < n; b += detail::kSumBlock) {
        const std::size_t e = std::min(n, b + detail::kSumBlock);
        double part[11] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
        for (std::size_t i = b; i < e; ++i) {
            const double x = s.px[i] - o.x(), y = s.py[i] - o.y(), z = s.pz[i] - o.z();
            const double Ax = s.ax[i], Ay = s.ay[i], Az = s.az[i];
            const double xx = x * x, yy = y * y, zz = z * z;
            part[0] += Ay * y;                // F = (0, y, 0)
            part[1] += Ax * xx * 0.5;         // F = (x²/2, 0, 0)
            part[2] += Ay * yy * 0.5;
            part[3] += Az * zz * 0.5;
            part[4] += Ax * xx * x / 3.0;     // F = (x³/3, 0, 0)
            part[5] += Ay * yy * y / 3.0;
            part[6] += Az * zz * z / 3.0;
            part[7] += Ax * xx * y * 0.5;     // F = (x²y/2, 0, 0): ∇·F = xy
            part[8] += Ay * yy * z * 0.5;     // F = (0, y²z/2, 0): ∇·F = yz
            part[9] += Az * zz * x * 0.5;     // F = (0, 0, z²x/2): ∇·F = zx
            part[10] += s.area[i];
        }
        acc.add(part);
    }
    SolidSums r;
    r.volume = acc.value(0);
    r.first = Eigen::Vector3d(acc.value(1), acc.value(2), acc.value(3));
    r.second(0, 0) = acc.value(4);
    r.second(1, 1) = acc.value(5);
    r.second(2, 2) = acc.value(6);
    r.second(0, 1) = r.second(1, 0) = acc.value(7);
    r.second(1, 2) = r.second(2, 1) = acc.value(8);
    r.second(0, 2) = r.second(2, 0) = acc.value(9);
    r.area = acc.value(10);
    return r;
}

/// Shell mass properties from per-sample masses m_i = σ_i |area_i| (σ_i = sigma(i), kg/m²).
template <class Sigma>
MassProperties shellFromSigma(const SurfaceSamples& s, Sigma sigma, const char* fn) {
    const Eigen::Vector3d o = samplesMean(s);
    // 0:M  1-3:Σm p  4-9: Σ m pp (xx yy zz xy yz zx)
    detail::CompensatedSum<10> acc;
    const std::size_t n = s.size();
    for (std::size_t b = 0; b < n; b += detail::kSumBlock) {
        const std::size_t e = std::min(n, b + detail::kSumBlock);
        double part[10] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
        for (std::size_t i = b; i < e; ++i) {
            const double m = sigma(i) * s.area[i];
            const double x = s.px[i] - o.x(), y = s.py[i] - o.y(), z = s.pz[i] - o.z();
            part[0] += m;
            part[1] += m * x;
            part[2] += m * y;
            part[3] += m * z;
            part[4] += m * x * x;
            part[5] += m * y * y;
            part[6] += m * z * z;
            part[7] += m * x * y;
            part[8] += m * y * z;
            part[9] += m * z * x;
        }
        acc.add(part);
    }
    const double M = acc.value(0);
    if (!std::isfinite(M) || M <= 0)
        throw std::invalid_argument(std::string(fn) + ": shell mass " + std::to_string(M) + " kg is not positive");
    Eigen::Matrix3d S;
    S << acc.value(4), acc.value(7), acc.value(9), acc.value(7), acc.value(5), acc.value(8), acc.value(9),
        acc.value(8), acc.value(6);
    const Eigen::Vector3d c = Eigen::Vector3d(acc.value(1), acc.value(2), acc.value(3)) / M;
    const Eigen::Matrix3d Sc = S - M * c * c.transpose();  // parallel axis to the shell's centre of mass
    const SolidSums sol = solidSums(s, o);
    MassProperties r;
    r.mass = M;
    r.volume = sol.volume;  // enclosed volume (informative for a shell)
    r.area = sol.area;
    r.centre = o + c;
    r.inertia = Sc.trace() * Eigen::Matrix3d::Identity() - Sc;  // Σ m_i(|p|²E − ppᵀ) about the centre
    return r;
}

}  // namespace

MassProperties solidMassProperties(const SurfaceSamples& samples, double density) {
    checkSamples(samples, "solidMassProperties");
    checkPositive(density, "solidMassProperties", "density");
    const Eigen::Vector3d o = samplesMean(samples);
    const SolidSums sol = solidSums(samples, o);
    if (!std::isfinite(sol.volume) || sol.volume <= 0)
        throw std::invalid_argument("solidMassProperties: enclosed volume " + std::to_string(sol.volume) +
                                    " m³ is not positive (open surface or inward area vectors?)");
    // Corrected eq. 6: centre = first moment / V (not ρ × first moment).
    const Eigen::Vector3d c = sol.first / sol.volume;
    // Corrected eq. 8: I = ρ[(tr S)E − S]; shifting S to the centre, S_c = S − V c cᵀ, is the parallel-axis
    // theorem I_C = I_O − M(|c|²E − c cᵀ).
    const Eigen::Matrix3d Sc = sol.second - sol.volume * c * c.transpose();
    MassProperties r;
    r.volume = sol.volume;
    r.mass = density * sol.volume;
    r.area = sol.area;
    r.centre = o + c;
    r.inertia = density * (Sc.trace() * Eigen::Matrix3d::Identity() - Sc);
    return r;
}

MassProperties shellMassProperties(const SurfaceSamples& samples, double density, double thickness) {
    checkSamples(samples, "shellMassProperties");
    checkPositive(density, "shellMassProperties", "density");
    checkPositive(thickness, "shellMassProperties", "thickness");
    const double sigma = density * thickness;
    return shellFromSigma(samples, [sigma](std::size_t) { return sigma; }, "shellMassProperties");
}

MassProperties shellMassProperties(const SurfaceSamples& samples, const std::vector<double>& arealDensity) {
    checkSamples(samples, "shellMassProperties");
    if (arealDensity.size() != samples.size())
        throw std::invalid_argument("shellMassProperties: " + std::to_string(arealDensity.size()) +
                                    " areal densities for " + std::to_string(samples.size()) + " samples");
    for (std::size_t i = 0; i < arealDensity.size(); ++i)
        if (!std::isfinite(arealDensity[i]) || arealDensity[i] < 0)
            throw std::invalid_argument("shellMassProperties: areal density of sample " + std::to_string(i) +
                                        " is negative or not finite");
    return shellFromSigma(samples, [&arealDensity](std::size_t i) { return arealDensity[i]; },
                          "shellMassProperties");
}

}  // namespace buoyancy
