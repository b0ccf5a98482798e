// DragKernelBody.inl: the vector drag sum of DragKernel.cpp for one width, included once per instruction set inside
// its own namespace (with GCC, inside a `#pragma GCC target` region). Expects the vector type V and BB_DRAG_SQRT(x)
// (lane-wise square root of a V) to be defined by the includer. Not a header of its own: no include guard, no public
// declarations.

/// Lane-wise square root.
BB_VM_INLINE V vsqrt(const V& x) { return BB_DRAG_SQRT(x); }

/// Lane-wise bb_drag_accumulate at the point r (relative to the centre of mass) with area vector (Ax, Ay, Az) and
/// area `area` already scaled by the wet fraction (0 in dry lanes, which then add nothing).
BB_VM_INLINE void pointDrag(const V r[3], const V& A0, const V& A1, const V& A2, const V& a, const V v[3],
                            const V w[3], const V u[3], const DragMotion& m, V acc[11]) {
    const V zero = V{};
    const V vi0 = v[0] + (w[1] * r[2] - w[2] * r[1]) - u[0];
    const V vi1 = v[1] + (w[2] * r[0] - w[0] * r[2]) - u[1];
    const V vi2 = v[2] + (w[0] * r[1] - w[1] * r[0]) - u[2];
    acc[6] += a * u[0];
    acc[7] += a * u[1];
    acc[8] += a * u[2];
    acc[9] += a;
    V f0 = zero, f1 = zero, f2 = zero;
    const V av = A0 * vi0 + A1 * vi1 + A2 * vi2;
    if (m.kd > 0) {  // pressure drag on front-facing parts
        const V k = select<V>(mask<V>(av > 0), m.kd * av, zero);
        f0 -= k * vi0;
        f1 -= k * vi1;
        f2 -= k * vi2;
    }
    if (m.kl > 0 || m.kf > 0) {
        const V an = vsqrt(A0 * A0 + A1 * A1 + A2 * A2);
        const Mask<V> has = mask<V>(an > 0);
        const V safe = select<V>(has, an, splat<V>(1.0));
        if (m.kl > 0) {  // linear pressure damping along the normal
            const V c = select<V>(has, m.kl * av / safe, zero);
            f0 -= c * A0;
            f1 -= c * A1;
            f2 -= c * A2;
            acc[10] -= c * av;  // its power f·v_i
        }
        if (m.kf > 0) {  // skin friction on the tangential part
            const V n0 = A0 / safe, n1 = A1 / safe, n2 = A2 / safe;
            const V vn = vi0 * n0 + vi1 * n1 + vi2 * n2;
            const V t0 = vi0 - vn * n0, t1 = vi1 - vn * n1, t2 = vi2 - vn * n2;
            const V tt = vsqrt(t0 * t0 + t1 * t1 + t2 * t2);
            const V c = select<V>(has, m.kf * a * tt, zero);
            f0 -= c * t0;
            f1 -= c * t1;
            f2 -= c * t2;
        }
    }
    acc[0] += f0;
    acc[1] += f1;
    acc[2] += f2;
    acc[3] += r[1] * f2 - r[2] * f1;
    acc[4] += r[2] * f0 - r[0] * f2;
    acc[5] += r[0] * f1 - r[1] * f0;
}

BB_VM_INLINE std::size_t run(const DragClusterBatch& c, const DragMotion& m, double part[11]) {
    constexpr int N = Traits<V>::N;
    const V zero = V{}, one = splat<V>(1.0), half = splat<V>(0.5);
    const V v[3] = {splat<V>(m.v[0]), splat<V>(m.v[1]), splat<V>(m.v[2])};
    const V w[3] = {splat<V>(m.w[0]), splat<V>(m.w[1]), splat<V>(m.w[2])};
    const double* R = m.R;
    V acc[11];
    for (V& a : acc) a = zero;
    std::size_t i = 0;
    for (; i + N <= c.n; i += N) {
        // Wet fraction (bb_drag_wet_ramp): the linear ramp over the vertical half extent; a NaN gives 0.
        const V h = load<V>(c.halfHeight + i);
        const V depth = load<V>(c.waterHeight + i) - load<V>(c.y + i);
        const Mask<V> hasHalf = mask<V>(h > 0);
        const V ramp = min<V>(one, max<V>(zero, half + half * depth / select<V>(hasHalf, h, one)));
        const V wetRaw = select<V>(hasHalf, ramp, select<V>(mask<V>(depth > 0), one, zero));
        const Mask<V> wetMask = mask<V>(wetRaw > 0);
        if (!any(wetMask)) continue;
        const V wet = select<V>(wetMask, wetRaw, zero);
        const V Ax = load<V>(c.ax + i), Ay = load<V>(c.ay + i), Az = load<V>(c.az + i);
        const V area = load<V>(c.area + i);
        const V r[3] = {load<V>(c.x + i) - m.com[0], load<V>(c.y + i) - m.com[1], load<V>(c.z + i) - m.com[2]};
        const V u[3] = {load<V>(c.ux + i), load<V>(c.uy + i), load<V>(c.uz + i)};
        // Two-point rule (bb_drag_cluster_accumulate): d = R C b / sqrt(bᵀ C b), b = Rᵀ (n × ω).
        const V an = vsqrt(Ax * Ax + Ay * Ay + Az * Az);
        const Mask<V> hasArea = mask<V>(an > 0);
        const V ans = select<V>(hasArea, an, one);
        const V n0 = Ax / ans, n1 = Ay / ans, n2 = Az / ans;
        const V g0 = n1 * w[2] - n2 * w[1], g1 = n2 * w[0] - n0 * w[2], g2 = n0 * w[1] - n1 * w[0];
        const V b0 = R[0] * g0 + R[3] * g1 + R[6] * g2;
        const V b1 = R[1] * g0 + R[4] * g1 + R[7] * g2;
        const V b2 = R[2] * g0 + R[5] * g1 + R[8] * g2;
        const V Cxx = load<V>(c.cxx + i), Cxy = load<V>(c.cxy + i), Cxz = load<V>(c.cxz + i);
        const V Cyy = load<V>(c.cyy + i), Cyz = load<V>(c.cyz + i), Czz = load<V>(c.czz + i);
        const V c0 = Cxx * b0 + Cxy * b1 + Cxz * b2;
        const V c1 = Cxy * b0 + Cyy * b1 + Cyz * b2;
        const V c2 = Cxz * b0 + Cyz * b1 + Czz * b2;
        const V s2 = b0 * c0 + b1 * c1 + b2 * c2;
        const Mask<V> spread = hasArea & mask<V>(s2 > 1e-300);
        const V root = vsqrt(select<V>(spread, s2, one));
        const V is = select<V>(spread, one / root, zero);
        const V d0 = (R[0] * c0 + R[1] * c1 + R[2] * c2) * is;
        const V d1 = (R[3] * c0 + R[4] * c1 + R[5] * c2) * is;
        const V d2 = (R[6] * c0 + R[7] * c1 + R[8] * c2) * is;
        // Each half: half the area vector and area, times the wet fraction (bb_drag_accumulate's A = wet·A_i).
        const V hw = half * wet;
        const V A0 = hw * Ax, A1 = hw * Ay, A2 = hw * Az, a = hw * area;
        const V rm[3] = {r[0] - d0, r[1] - d1, r[2] - d2};
        pointDrag(rm, A0, A1, A2, a, v, w, u, m, acc);
        const V rp[3] = {r[0] + d0, r[1] + d1, r[2] + d2};
        pointDrag(rp, A0, A1, A2, a, v, w, u, m, acc);
    }
    for (int k = 0; k < 11; ++k)
        for (int l = 0; l < N; ++l) part[k] += acc[k][l];
    return i;
}


/// The clusters [0, n − n mod N) moved to the world (poseDragClusters); returns the first cluster not done.
BB_VM_INLINE std::size_t pose(const DragClusters& c, const double R[9], const double t[3], const DragClusterPose& o) {
    constexpr int N = Traits<V>::N;
    const std::size_t n = c.size();
    const V r00 = splat<V>(R[0]), r01 = splat<V>(R[1]), r02 = splat<V>(R[2]);
    const V r10 = splat<V>(R[3]), r11 = splat<V>(R[4]), r12 = splat<V>(R[5]);
    const V r20 = splat<V>(R[6]), r21 = splat<V>(R[7]), r22 = splat<V>(R[8]);
    const V tx = splat<V>(t[0]), ty = splat<V>(t[1]), tz = splat<V>(t[2]), three = splat<V>(3.0), zero = V{};
    // The arrays as local restrict pointers: a store through one of the outputs cannot then be taken to move the
    // others, so the loop does not reload them every iteration.
    const double* __restrict px = c.px.data();
    const double* __restrict py = c.py.data();
    const double* __restrict pz = c.pz.data();
    const double* __restrict pax = c.ax.data();
    const double* __restrict pay = c.ay.data();
    const double* __restrict paz = c.az.data();
    const double* __restrict pcxx = c.cxx.data();
    const double* __restrict pcxy = c.cxy.data();
    const double* __restrict pcxz = c.cxz.data();
    const double* __restrict pcyy = c.cyy.data();
    const double* __restrict pcyz = c.cyz.data();
    const double* __restrict pczz = c.czz.data();
    double* __restrict ox = o.x;
    double* __restrict oy = o.y;
    double* __restrict oz = o.z;
    double* __restrict oax = o.ax;
    double* __restrict oay = o.ay;
    double* __restrict oaz = o.az;
    double* __restrict oh = o.halfHeight;
    std::size_t i = 0;
    for (; i + N <= n; i += N) {
        const V x = load<V>(px + i), y = load<V>(py + i), z = load<V>(pz + i);
        store<V>(ox + i, r00 * x + r01 * y + r02 * z + tx);
        store<V>(oy + i, r10 * x + r11 * y + r12 * z + ty);
        store<V>(oz + i, r20 * x + r21 * y + r22 * z + tz);
        const V ax = load<V>(pax + i), ay = load<V>(pay + i), az = load<V>(paz + i);
        store<V>(oax + i, r00 * ax + r01 * ay + r02 * az);
        store<V>(oay + i, r10 * ax + r11 * ay + r12 * az);
        store<V>(oaz + i, r20 * ax + r21 * ay + r22 * az);
        const V cxx = load<V>(pcxx + i), cxy = load<V>(pcxy + i), cxz = load<V>(pcxz + i);
        const V cyy = load<V>(pcyy + i), cyz = load<V>(pcyz + i), czz = load<V>(pczz + i);
        const V vy = r10 * (r10 * cxx + r11 * cxy + r12 * cxz) + r11 * (r10 * cxy + r11 * cyy + r12 * cyz) +
                     r12 * (r10 * cxz + r11 * cyz + r12 * czz);
        store<V>(oh + i, vsqrt(three * max<V>(vy, zero)));
    }
    return i;
}
