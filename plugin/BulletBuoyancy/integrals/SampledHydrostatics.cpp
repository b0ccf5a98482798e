/// @file SampledHydrostatics.cpp
/// Hydrostatics from surface samples (declared in Hydrostatics.h): design.md 2.2 (fields that vanish
/// on the water surface, so only wetted samples are summed — deliberately not the paper's eq. 11, whose
/// fields miss the cap term) and 2.3 (pressure force and torque).

#include <BulletBuoyancy/integrals/CompensatedSum.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/geometry/SampleFormulas.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace buoyancy {

void SampleWorkspace::resize(std::size_t n) {
    for (auto* v : {&wx, &wy, &wz, &wax, &way, &waz, &waterHeight, &warea})
        if (v->size() != n) v->resize(n);
}

void transformSamples(const SurfaceSamples& samples, const Eigen::Isometry3d& pose, SampleWorkspace& ws) {
    const std::size_t n = samples.size();
    if (samples.py.size() != n || samples.pz.size() != n || samples.ax.size() != n || samples.ay.size() != n ||
        samples.az.size() != n)
        throw std::invalid_argument("transformSamples: sample arrays have different lengths");
    ws.resize(n);
    // p_w = R p + t, A_w = R A (area vectors are normals × area: rotate only): SampleFormulas.h, shared with
    // the OpenCL kernels.
    const Eigen::Matrix3d Rm = pose.linear();
    const double R[9] = {Rm(0, 0), Rm(0, 1), Rm(0, 2), Rm(1, 0), Rm(1, 1), Rm(1, 2), Rm(2, 0), Rm(2, 1), Rm(2, 2)};
    const double t[3] = {pose.translation().x(), pose.translation().y(), pose.translation().z()};
    for (std::size_t i = 0; i < n; ++i) {
        double p[3], A[3];
        formulas::bb_transform_sample(R, t, samples.px[i], samples.py[i], samples.pz[i], samples.ax[i],
                                      samples.ay[i], samples.az[i], p, A);
        ws.wx[i] = p[0];
        ws.wy[i] = p[1];
        ws.wz[i] = p[2];
        ws.wax[i] = A[0];
        ws.way[i] = A[1];
        ws.waz[i] = A[2];
    }
    if (samples.area.size() == n)
        std::copy(samples.area.begin(), samples.area.end(), ws.warea.begin());
    else
        ws.warea.clear();  // fall back to |A_i| in the integration
}

HydrostaticsResult integrateWettedSamples(const SampleWorkspace& ws, double fluidDensity, double gravity,
                                          const Eigen::Vector3d& torqueReference) {
    const std::size_t n = ws.wx.size();
    if (ws.wy.size() != n || ws.wz.size() != n || ws.wax.size() != n || ws.way.size() != n || ws.waz.size() != n ||
        ws.waterHeight.size() != n)
        throw std::invalid_argument("integrateWettedSamples: workspace arrays have different lengths");
    const bool haveArea = ws.warea.size() == n;
    const double rx = torqueReference.x(), ry = torqueReference.y(), rz = torqueReference.z();

    // Per wetted sample, with d = y − f < 0 (d = 0 for dry samples zeroes every term, no branch) and
    // coordinates relative to the reference r (the fields stay valid under translation):
    //   V   += A^y d                      (field (0, y − f, 0))
    //   ∫x  += A^y x' d,  ∫z += A^y z' d  (fields (0, x'(y − f), 0), (0, z'(y − f), 0))
    //   ∫y  += A^y (y'² − f'²)/2 = A^y d (y' + f')/2
    //   F   += −P A = ρg d A              (P = ρg (f − y), design.md 2.3)
    //   τ   += p' × (−P A) = ρg d (p' × A)
    // 0:V 1-3:∫p' 4-6:Σ d A 7-9:Σ d p'×A 10:Σ_wet A^y 11:wetted area
    detail::CompensatedSum<12> acc;
    for (std::size_t b = 0; b < n; b += detail::kSumBlock) {
        const std::size_t e = std::min(n, b + detail::kSumBlock);
        double part[12] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
        for (std::size_t i = b; i < e; ++i) {
            // The per-sample terms live in SampleFormulas.h, shared with the OpenCL kernels.
            const double f = ws.waterHeight[i];
            formulas::bb_hydro_accumulate(ws.wx[i] - rx, ws.wy[i] - ry, ws.wz[i] - rz, f - ry,
                                          formulas::bb_wet_depth(ws.wy[i], f), ws.wax[i], ws.way[i], ws.waz[i],
                                          haveArea ? ws.warea[i] : -1.0, part);
        }
        acc.add(part);
    }
    const double rg = fluidDensity * gravity;
    HydrostaticsResult r;
    r.submerged_volume = acc.value(0);
    if (r.submerged_volume != 0)
        r.centre_of_buoyancy = torqueReference + Eigen::Vector3d(acc.value(1), acc.value(2), acc.value(3)) /
                                                     r.submerged_volume;
    r.force = rg * Eigen::Vector3d(acc.value(4), acc.value(5), acc.value(6));
    r.torque = rg * Eigen::Vector3d(acc.value(7), acc.value(8), acc.value(9));
    r.waterline_area = -acc.value(10);
    r.wetted_area = acc.value(11);
    return r;
}

HydrostaticsResult sampledHydrostatics(const SurfaceSamples& samples, const Eigen::Isometry3d& pose,
                                       const btWaterSurface& water, double time, double fluidDensity,
                                       double gravity, const Eigen::Vector3d& torqueReference,
                                       SampleWorkspace& ws, btWaterQueryCache* cache, const WaterPatch* patch) {
    if (!std::isfinite(fluidDensity) || fluidDensity < 0)
        throw std::invalid_argument("sampledHydrostatics: fluid density must be finite and ≥ 0, got " +
                                    std::to_string(fluidDensity));
    if (!std::isfinite(gravity)) throw std::invalid_argument("sampledHydrostatics: gravity is not finite");
    transformSamples(samples, pose, ws);
    const std::size_t n = samples.size();
    if (n == 0) return HydrostaticsResult{};

    // Fast path (design.md 2.5): body entirely above the highest water point → nothing is wet.
    double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity()};
    double hi[3] = {-lo[0], -lo[0], -lo[0]};
    for (std::size_t i = 0; i < n; ++i) {
        lo[0] = std::min(lo[0], ws.wx[i]);
        hi[0] = std::max(hi[0], ws.wx[i]);
        lo[1] = std::min(lo[1], ws.wy[i]);
        lo[2] = std::min(lo[2], ws.wz[i]);
        hi[2] = std::max(hi[2], ws.wz[i]);
    }
    double hMin = 0, hMax = 0;
    water.heightBounds(lo[0], lo[2], hi[0], hi[2], time, hMin, hMax);
    if (lo[1] >= hMax) return HydrostaticsResult{};

    double flatH = 0;
    if (patch && !water.isFlat(time, flatH))  // interpolated from the body's grid (design.md 2.5)
        patch->heights(ws.wx.data(), ws.wz.data(), n, ws.waterHeight.data());
    else if (cache)  // one batch call per body
        water.heightsCached(ws.wx.data(), ws.wz.data(), n, time, ws.waterHeight.data(), *cache);
    else
        water.heights(ws.wx.data(), ws.wz.data(), n, time, ws.waterHeight.data());
    HydrostaticsResult r = integrateWettedSamples(ws, fluidDensity, gravity, torqueReference);
    if (!std::isfinite(r.submerged_volume) || !r.force.allFinite() || !r.torque.allFinite() ||
        !r.centre_of_buoyancy.allFinite())
        throw std::runtime_error("sampledHydrostatics: non-finite result (non-finite pose, samples or water heights)");
    return r;
}

}  // namespace buoyancy
