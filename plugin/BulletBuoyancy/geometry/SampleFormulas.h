#ifndef BULLET_BUOYANCY_SAMPLE_FORMULAS_H
#define BULLET_BUOYANCY_SAMPLE_FORMULAS_H
/// @file SampleFormulas.h
/// The per-sample formulas of the buoyancy integrals, written once in the common subset of C++ and OpenCL C
/// so the CPU path (SampledHydrostatics.cpp, btBuoyancyAction's drag) and the OpenCL kernels (kernels/*.cl,
/// which get this file prepended at build time, cmake/EmbedKernels.cmake) cannot drift (the
/// Bullet3 `shared/` header style, STYLE.md). Plain functions on scalars with output pointers; no Eigen, no
/// std:: in the bodies.
///
/// Macro layer: in C++ the scalar bb_real is double and everything lives in namespace buoyancy::formulas;
/// in OpenCL C the host defines BB_REAL (double on devices with cl_khr_fp64, else float) and the functions
/// are `static inline` at program scope. Pointer parameters are private (stack) memory in OpenCL C 1.2: copy
/// global data into locals before calling.

#ifdef __OPENCL_VERSION__
#ifndef BB_REAL
#error "SampleFormulas.h: the OpenCL build options must define BB_REAL (double or float)"
#endif
#if BB_REAL_IS_DOUBLE
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#endif
typedef BB_REAL bb_real;
// No fused multiply-add contraction: the device rounds like the CPU build (which does not contract by default).
#pragma OPENCL FP_CONTRACT OFF
#define BB_FN static inline
#define BB_SQRT sqrt
#define BB_NS_BEGIN
#define BB_NS_END
#else
#include <cmath>
#define BB_FN inline
#define BB_SQRT std::sqrt
#define BB_NS_BEGIN namespace buoyancy { namespace formulas {
#define BB_NS_END }}
#endif

/// std::min / std::max semantics (a NaN in the first argument is kept), the same in both languages.
#define BB_MIN(a, b) ((b) < (a) ? (b) : (a))
#define BB_MAX(a, b) ((a) < (b) ? (b) : (a))

BB_NS_BEGIN

#ifndef __OPENCL_VERSION__
/// Scalar of the CPU path (the device uses double or float, see above).
typedef double bb_real;
#endif

/// Number of hydrostatic sums per body (see bb_hydro_accumulate).
#define BB_HYDRO_TERMS 12
/// Number of drag sums per body (see bb_drag_accumulate).
#define BB_DRAG_TERMS 11

/// Rigid transform of one sample (design.md 1): p' = R p + t, A' = R A (area vectors are normal × area:
/// they rotate only). R is row-major (R[3 r + c]); t is the translation, m. With t = translation − reference
/// the result is relative to the reference point (the device does this so float keeps its digits).
/// @param[out] outP  3 coordinates, m   @param[out] outA  3 components, m²
BB_FN void bb_transform_sample(const bb_real* R, const bb_real* t, bb_real px, bb_real py, bb_real pz,
                               bb_real ax, bb_real ay, bb_real az, bb_real* outP, bb_real* outA) {
    outP[0] = R[0] * px + R[1] * py + R[2] * pz + t[0];
    outP[1] = R[3] * px + R[4] * py + R[5] * pz + t[1];
    outP[2] = R[6] * px + R[7] * py + R[8] * pz + t[2];
    outA[0] = R[0] * ax + R[1] * ay + R[2] * az;
    outA[1] = R[3] * ax + R[4] * ay + R[5] * az;
    outA[2] = R[6] * ax + R[7] * ay + R[8] * az;
}

/// Signed depth term of design.md 2.2: d = min(y − f, 0), m (negative when wet, 0 when dry, so a dry sample
/// zeroes every hydrostatic term without a branch). y and f in the same frame (world, or both relative to
/// the reference point).
BB_FN bb_real bb_wet_depth(bb_real y, bb_real f) { return BB_MIN(y - f, (bb_real)0); }

/// Hydrostatic pressure P = ρ g (f − y) on a wetted sample, Pa (design.md 2.3); 0 when dry.
BB_FN bb_real bb_pressure(bb_real rhoG, bb_real y, bb_real f) { return -rhoG * bb_wet_depth(y, f); }

/// Add one sample's hydrostatic terms (design.md 2.2 fields that vanish on the water surface — not the
/// paper's eq. 11, whose fields miss the cap term — and the pressure force/torque of 2.3 divided by ρg).
/// Coordinates are relative to the torque reference r: (x, y, z) = p − r, fr = f − r_y, d = bb_wet_depth.
///   part[0]  += A^y d                  (V_sub,  field (0, y − f, 0), = −A^y (f − y), paper eq. 10)
///   part[1]  += A^y d x                (∫x dv)
///   part[2]  += A^y d (y + fr)/2       (∫y dv, field (0, (y² − f²)/2, 0))
///   part[3]  += A^y d z                (∫z dv)
///   part[4..6] += d A                  (F / ρg: F = −Σ P A, P = ρ g (f − y))
///   part[7..9] += d (p × A)            (τ / ρg about r)
///   part[10] += [wet] A^y              (−waterline area)
///   part[11] += [wet] area             (wetted area; area < 0 means "use |A|")
/// @param area  unsigned sample area, m² (≥ |A|), or a negative number to use |A|
BB_FN void bb_hydro_accumulate(bb_real x, bb_real y, bb_real z, bb_real fr, bb_real d, bb_real Ax, bb_real Ay,
                               bb_real Az, bb_real area, bb_real* part) {
    const bb_real wet = d < 0 ? (bb_real)1 : (bb_real)0;
    const bb_real Ayd = Ay * d;
    part[0] += Ayd;
    part[1] += Ayd * x;
    part[2] += Ayd * (bb_real)0.5 * (y + fr);
    part[3] += Ayd * z;
    part[4] += d * Ax;
    part[5] += Ayd;
    part[6] += d * Az;
    part[7] += d * (y * Az - z * Ay);
    part[8] += d * (z * Ax - x * Az);
    part[9] += d * (x * Ay - y * Ax);
    part[10] += wet * Ay;
    part[11] += wet * (area >= 0 ? area : BB_SQRT(Ax * Ax + Ay * Ay + Az * Az));
}

/// Half the size of a drag sample, sqrt(area)/2, m: with the sample's tilt it gives the vertical half extent
/// over which drag ramps from dry to wet (bb_drag_wet_fraction).
BB_FN bb_real bb_drag_half_size(bb_real area) { return (bb_real)0.5 * BB_SQRT(BB_MAX(area, (bb_real)0)); }

/// Wet fraction of a drag sample of vertical half extent halfV, m (design.md 2.4's linear ramp, applied to
/// drag only, so a shallow draft still gets drag from the samples it half wets): 0…1 over ±halfV about the
/// sample's centre; a piece without vertical extent is wet by its centre.
/// @param depth  f − y at the sample's centre, m (positive under water)
BB_FN bb_real bb_drag_wet_ramp(bb_real halfV, bb_real depth) {
    if (halfV > 0) return BB_MIN((bb_real)1, BB_MAX((bb_real)0, (bb_real)0.5 + (bb_real)0.5 * depth / halfV));
    return depth > 0 ? (bb_real)1 : (bb_real)0;
}

/// Wet fraction of one fine drag sample: bb_drag_wet_ramp over the vertical half extent halfSize·sqrt(1 − n_y²)
/// of a square piece of half size halfSize (bb_drag_half_size) tilted with its normal n = A/|A|.
BB_FN bb_real bb_drag_wet_fraction(bb_real halfSize, bb_real Ax, bb_real Ay, bb_real Az, bb_real depth) {
    const bb_real an0 = BB_SQRT(Ax * Ax + Ay * Ay + Az * Az);
    const bb_real ny = an0 > 0 ? Ay / an0 : (bb_real)0;
    return bb_drag_wet_ramp(halfSize * BB_SQRT(BB_MAX((bb_real)0, (bb_real)1 - ny * ny)), depth);
}

/// Vertical half extent of a drag cluster (integrals/DragClusters.h): sqrt(3 r_yᵀ C r_y), m, with r_y the
/// world-y row of the rotation (R[3], R[4], R[5] row-major) and C the cluster's area-weighted spread
/// (C[0..5] = cxx, cxy, cxz, cyy, cyz, czz, m²); a uniform segment of length L has variance L²/12.
BB_FN bb_real bb_cluster_half_extent(const bb_real* R, const bb_real* C) {
    const bb_real r10 = R[3], r11 = R[4], r12 = R[5];
    const bb_real vy = r10 * (r10 * C[0] + r11 * C[1] + r12 * C[2]) + r11 * (r10 * C[1] + r11 * C[3] + r12 * C[4]) +
                       r12 * (r10 * C[2] + r11 * C[4] + r12 * C[5]);
    return BB_SQRT((bb_real)3 * BB_MAX(vy, (bb_real)0));
}

/// Add one sample's drag (design.md 2.6, paper eq. 12) to part[BB_DRAG_TERMS]:
/// relative velocity v_i = v + ω × r − u; with the wetted area vector A = wet·A_i and area a = wet·area_i:
///   pressure drag on front-facing samples  F −= ½ρC_d (A·v_i) v_i   (= −½ρC_d (A·v̂)|v|² v̂),  A·v_i > 0
///   linear pressure damping               F −= ρ b (A·v_i) Â
///   skin friction on the tangential part   F −= ½ρC_f a |v_t| v_t
///   part[0..2] += F, part[3..5] += r × F, part[6..8] += a u, part[9] += a,
///   part[10] += the linear damping's power F_lin·v_i = −ρ b (A·v_i)² / |A| (≤ 0; its share of the drag's power tells
///   the implicit drag solve how much of the drag is linear in the velocity, design.md 2.6).
/// @param r      sample position relative to the centre of mass, m
/// @param v,w    body linear (m/s) and angular (rad/s) velocity   @param u  water velocity at the sample, m/s
/// @param wet    wet fraction 0…1 (bb_drag_wet_fraction); 0 adds nothing
/// @param kd,kf,kl  ½ρC_d, ½ρC_f, ρb (kg/m³, kg/m³, kg/m²/s·…: see btBuoyancySettings)
BB_FN void bb_drag_accumulate(const bb_real* r, const bb_real* v, const bb_real* w, const bb_real* u,
                              bb_real Ax, bb_real Ay, bb_real Az, bb_real area, bb_real wet, bb_real kd,
                              bb_real kf, bb_real kl, bb_real* part) {
    if (!(wet > 0)) return;
    const bb_real vi0 = v[0] + (w[1] * r[2] - w[2] * r[1]) - u[0];
    const bb_real vi1 = v[1] + (w[2] * r[0] - w[0] * r[2]) - u[1];
    const bb_real vi2 = v[2] + (w[0] * r[1] - w[1] * r[0]) - u[2];
    const bb_real A0 = wet * Ax, A1 = wet * Ay, A2 = wet * Az;
    const bb_real a = wet * area;
    part[6] += a * u[0];
    part[7] += a * u[1];
    part[8] += a * u[2];
    part[9] += a;
    bb_real f0 = 0, f1 = 0, f2 = 0;
    const bb_real av = A0 * vi0 + A1 * vi1 + A2 * vi2;
    if (kd > 0 && av > 0) {
        f0 -= kd * av * vi0;
        f1 -= kd * av * vi1;
        f2 -= kd * av * vi2;
    }
    const bb_real an = BB_SQRT(A0 * A0 + A1 * A1 + A2 * A2);
    if (kl > 0 && an > 0) {
        const bb_real c = kl * av / an;
        f0 -= c * A0;
        f1 -= c * A1;
        f2 -= c * A2;
        part[10] -= c * av;
    }
    if (kf > 0 && an > 0) {
        const bb_real n0 = A0 / an, n1 = A1 / an, n2 = A2 / an;
        const bb_real vn = vi0 * n0 + vi1 * n1 + vi2 * n2;
        const bb_real t0 = vi0 - vn * n0, t1 = vi1 - vn * n1, t2 = vi2 - vn * n2;
        const bb_real c = kf * a * BB_SQRT(t0 * t0 + t1 * t1 + t2 * t2);
        f0 -= c * t0;
        f1 -= c * t1;
        f2 -= c * t2;
    }
    part[0] += f0;
    part[1] += f1;
    part[2] += f2;
    part[3] += r[1] * f2 - r[2] * f1;
    part[4] += r[2] * f0 - r[0] * f2;
    part[5] += r[0] * f1 - r[1] * f0;
}

/// Add one drag cluster (integrals/DragClusters.h) with bb_drag_accumulate. Across a cluster the normal velocity
/// varies as n·(ω × d) = d·g with g = n × ω, so a cluster evaluated at its centroid alone would lose the drag
/// torque of a rotating face (a rolling log's faces: one half advances, the other retreats). Two points of half
/// the area at d = ±C g / sqrt(gᵀ C g) (C the cluster's spread) reproduce Σ a_i d_i (d_i·g) = area C g, so linear
/// damping's force and torque are exact for a flat cluster, and quadratic drag gets a two-point rule (design.md
/// 2.5, drag level of detail). Without spread along g: one point at the centroid.
/// @param R  rotation body → world, row-major   @param C  spread cxx, cxy, cxz, cyy, cyz, czz, body frame, m²
/// @param r  centroid relative to the COM, world, m; other parameters as bb_drag_accumulate (A, area: the whole cluster)
BB_FN void bb_drag_cluster_accumulate(const bb_real* R, const bb_real* C, const bb_real* r, const bb_real* v,
                                      const bb_real* w, const bb_real* u, bb_real Ax, bb_real Ay, bb_real Az,
                                      bb_real area, bb_real wet, bb_real kd, bb_real kf, bb_real kl, bb_real* part) {
    const bb_real an = BB_SQRT(Ax * Ax + Ay * Ay + Az * Az);
    if (an > 0) {
        const bb_real n0 = Ax / an, n1 = Ay / an, n2 = Az / an;
        const bb_real g0 = n1 * w[2] - n2 * w[1], g1 = n2 * w[0] - n0 * w[2], g2 = n0 * w[1] - n1 * w[0];  // n × ω
        const bb_real b0 = R[0] * g0 + R[3] * g1 + R[6] * g2;  // Rᵀ g: body frame
        const bb_real b1 = R[1] * g0 + R[4] * g1 + R[7] * g2;
        const bb_real b2 = R[2] * g0 + R[5] * g1 + R[8] * g2;
        const bb_real c0 = C[0] * b0 + C[1] * b1 + C[2] * b2;
        const bb_real c1 = C[1] * b0 + C[3] * b1 + C[4] * b2;
        const bb_real c2 = C[2] * b0 + C[4] * b1 + C[5] * b2;
        const bb_real s2 = b0 * c0 + b1 * c1 + b2 * c2;
        if (s2 > (bb_real)1e-300) {
            const bb_real is = (bb_real)1 / BB_SQRT(s2);
            const bb_real d0 = (R[0] * c0 + R[1] * c1 + R[2] * c2) * is;  // R C g / sqrt(gᵀ C g): world frame
            const bb_real d1 = (R[3] * c0 + R[4] * c1 + R[5] * c2) * is;
            const bb_real d2 = (R[6] * c0 + R[7] * c1 + R[8] * c2) * is;
            const bb_real h = (bb_real)0.5;
            bb_real rp[3];
            rp[0] = r[0] - d0;
            rp[1] = r[1] - d1;
            rp[2] = r[2] - d2;
            bb_drag_accumulate(rp, v, w, u, h * Ax, h * Ay, h * Az, h * area, wet, kd, kf, kl, part);
            rp[0] = r[0] + d0;
            rp[1] = r[1] + d1;
            rp[2] = r[2] + d2;
            bb_drag_accumulate(rp, v, w, u, h * Ax, h * Ay, h * Az, h * area, wet, kd, kf, kl, part);
            return;
        }
    }
    bb_drag_accumulate(r, v, w, u, Ax, Ay, Az, area, wet, kd, kf, kl, part);
}

/// Deformable re-bake (paper Fig. 17, plugin/BulletBuoyancy/bake/DeformableRebake.h): add one piece of a sample.
/// The piece is the fraction `weight` (piece UV area / triangle UV area) of the triangle with corners
/// (a, b, c); its 3D centroid is a + β1 (b − a) + β2 (c − a) because the UV→3D map is affine per triangle
/// (design.md 1.1), so the fixed (triangle, weight, β1, β2) map re-bakes any deformed pose exactly.
///   acc[0..2] += weight · ½ (b − a) × (c − a)      (area vector, m²)
///   acc[3]    += weight · |½ (b − a) × (c − a)|    (area, m²)
///   acc[4..6] += weight · |…| · centroid          (area-weighted centroid, m³; divide by acc[3])
BB_FN void bb_rebake_piece(const bb_real* a, const bb_real* b, const bb_real* c, bb_real weight, bb_real beta1,
                           bb_real beta2, bb_real* acc) {
    const bb_real e10 = b[0] - a[0], e11 = b[1] - a[1], e12 = b[2] - a[2];
    const bb_real e20 = c[0] - a[0], e21 = c[1] - a[1], e22 = c[2] - a[2];
    const bb_real A0 = (bb_real)0.5 * (e11 * e22 - e12 * e21);
    const bb_real A1 = (bb_real)0.5 * (e12 * e20 - e10 * e22);
    const bb_real A2 = (bb_real)0.5 * (e10 * e21 - e11 * e20);
    const bb_real ar = weight * BB_SQRT(A0 * A0 + A1 * A1 + A2 * A2);
    acc[0] += weight * A0;
    acc[1] += weight * A1;
    acc[2] += weight * A2;
    acc[3] += ar;
    acc[4] += ar * (a[0] + beta1 * e10 + beta2 * e20);
    acc[5] += ar * (a[1] + beta1 * e11 + beta2 * e21);
    acc[6] += ar * (a[2] + beta1 * e12 + beta2 * e22);
}

BB_NS_END

#endif  // BULLET_BUOYANCY_SAMPLE_FORMULAS_H
