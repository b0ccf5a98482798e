// VertexPassKernels.inl: the passes of VertexHydrostatics.cpp and the water patch's batch heights, for one SIMD width, included once per
// instruction set inside its own namespace (force-inlined into a function built for it). Expects the vector type V
// to be defined by the includer. Not a header of its own: no include guard, no public declarations.

/// Lane l = base[index[l]] (one load per lane: on the CPUs measured, faster than the gather instructions).
BB_VM_INLINE V gatherLanes(const double* base, const std::int32_t* index) {
    V r;
    for (int l = 0; l < Traits<V>::N; ++l) r[l] = base[index[l]];
    return r;
}

/// The four a_j of every lane (a[l][j]) as four vectors A[j] (lane l of A[j] = a[l][j]): a transpose by shuffles at
/// 8 and 4 lanes (no lane's value changes), lane by lane at 2.
template <class W>
BB_VM_INLINE void transposeRows(const v4d* a, W A[4]) {
    constexpr int N = Traits<W>::N;
    if constexpr (N == 8) {
        // Pairs of lanes side by side, then the j of four lanes together, then of all eight.
        using V = W;
        const V p0 = __builtin_shufflevector(a[0], a[1], 0, 1, 2, 3, 4, 5, 6, 7);
        const V p1 = __builtin_shufflevector(a[2], a[3], 0, 1, 2, 3, 4, 5, 6, 7);
        const V p2 = __builtin_shufflevector(a[4], a[5], 0, 1, 2, 3, 4, 5, 6, 7);
        const V p3 = __builtin_shufflevector(a[6], a[7], 0, 1, 2, 3, 4, 5, 6, 7);
        const V q01 = __builtin_shufflevector(p0, p1, 0, 4, 8, 12, 1, 5, 9, 13);   // j = 0, 1 of lanes 0–3
        const V q23 = __builtin_shufflevector(p0, p1, 2, 6, 10, 14, 3, 7, 11, 15);  // j = 2, 3 of lanes 0–3
        const V r01 = __builtin_shufflevector(p2, p3, 0, 4, 8, 12, 1, 5, 9, 13);   // j = 0, 1 of lanes 4–7
        const V r23 = __builtin_shufflevector(p2, p3, 2, 6, 10, 14, 3, 7, 11, 15);  // j = 2, 3 of lanes 4–7
        A[0] = __builtin_shufflevector(q01, r01, 0, 1, 2, 3, 8, 9, 10, 11);
        A[1] = __builtin_shufflevector(q01, r01, 4, 5, 6, 7, 12, 13, 14, 15);
        A[2] = __builtin_shufflevector(q23, r23, 0, 1, 2, 3, 8, 9, 10, 11);
        A[3] = __builtin_shufflevector(q23, r23, 4, 5, 6, 7, 12, 13, 14, 15);
    } else if constexpr (N == 4) {
        using V = W;
        const V t0 = __builtin_shufflevector(a[0], a[1], 0, 4, 2, 6);  // j = 0, 2 of lanes 0–1
        const V t1 = __builtin_shufflevector(a[0], a[1], 1, 5, 3, 7);  // j = 1, 3 of lanes 0–1
        const V t2 = __builtin_shufflevector(a[2], a[3], 0, 4, 2, 6);  // j = 0, 2 of lanes 2–3
        const V t3 = __builtin_shufflevector(a[2], a[3], 1, 5, 3, 7);  // j = 1, 3 of lanes 2–3
        A[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
        A[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
        A[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
        A[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
    } else {
        double lanes[4][N];
        for (int l = 0; l < N; ++l)
            for (int j = 0; j < 4; ++j) lanes[j][l] = a[l][j];
        for (int j = 0; j < 4; ++j) A[j] = load<W>(lanes[j]);
    }
}

/// A patch's cells as the interpolation reads them, splat once per pass (a local copy: the passes' stores cannot
/// alias it, so the loops do not reload it).
struct PatchLanes {
    V x0, z0, invH, lo, hi;
    int last, perRow;
    const double* coef;
};
BB_VM_INLINE PatchLanes patchLanes(const WaterPatch::CellGrid& g) {
    return PatchLanes{splat<V>(g.x0), splat<V>(g.z0), splat<V>(g.invH), splat<V>(1.0), splat<V>(double(g.nodes - 2)),
                      g.nodes - 3, g.nodes - 3, g.coefficients};
}

/// The patch's interpolant at world (x, z), lane by lane with the operations of WaterPatch::height (the clamp to the
/// border cells included; x, z finite).
BB_VM_INLINE V interpolate(const PatchLanes& g, const V& x, const V& z) {
    constexpr int N = Traits<V>::N;
    typedef std::int32_t VI __attribute__((vector_size(4 * N)));  // one int per lane
    const V lo = g.lo, hi = g.hi;
    const int last = g.last, perRow = g.perRow;
    const double* coef = g.coef;
    // std::min(std::max(u, lo), hi), lane by lane.
    V uc = (x - g.x0) * g.invH, vc = (z - g.z0) * g.invH;
    uc = select<V>(mask<V>(uc < lo), lo, uc);
    uc = select<V>(mask<V>(hi < uc), hi, uc);
    vc = select<V>(mask<V>(vc < lo), lo, vc);
    vc = select<V>(mask<V>(hi < vc), hi, vc);
    // Cell and local coordinates, every lane at once: i = min(⌊uc⌋, last) (uc ≥ 1: truncation is the floor),
    // tu = uc − i (exact), cell = 16 ((j − 1) perRow + i − 1).
    const VI lastI = VI{} + last;
    VI ci = __builtin_convertvector(uc, VI), cj = __builtin_convertvector(vc, VI);
    ci = ci < lastI ? ci : lastI;
    cj = cj < lastI ? cj : lastI;
    const V tu = uc - __builtin_convertvector(ci, V), tv = vc - __builtin_convertvector(cj, V);
    const VI cellV = ((cj - 1) * perRow + (ci - 1)) * 16;
    std::int32_t cell[N];
    double tuLane[N];
    std::memcpy(cell, &cellV, sizeof cell);
    store<V>(tuLane, tu);
    // Lane by lane, the cell's 16 coefficients read as four rows of 4 (contiguous loads, no per-lane inserts):
    // a_j = ((C[12+j] tu + C[8+j]) tu + C[4+j]) tu + C[j] for the four j at once; then the a_j of all lanes side by
    // side and the cubic in tv for every lane at once, with the operations (and so the roundings) of
    // WaterPatch::height.
    v4d a[N];
    for (int l = 0; l < N; ++l) {
        const double* C = coef + cell[l];
        const double w = tuLane[l];
        const v4d u4 = {w, w, w, w};  // a broadcast (tu ≥ 0: the same as splat's + 0)
        a[l] = ((load<v4d>(C + 12) * u4 + load<v4d>(C + 8)) * u4 + load<v4d>(C + 4)) * u4 + load<v4d>(C);
    }
    V A[4];
    transposeRows<V>(a, A);
    return ((A[3] * tv + A[2]) * tv + A[1]) * tv + A[0];
}

/// Pass 1 for the vertices [0, n − n mod N) (vertexDepthsOnPatch); returns the first vertex not done, or SIZE_MAX when
/// an interpolated height was not finite.
BB_VM_INLINE std::size_t depthsKernel(const VertexShares& s, const double R[9], const double t[3],
                                      const WaterPatch::CellGrid& g, double waterHigh, double* D) {
    constexpr int N = Traits<V>::N;
    const std::size_t n = s.vertexCount();
    const V r00 = splat<V>(R[0]), r01 = splat<V>(R[1]), r02 = splat<V>(R[2]);
    const V r10 = splat<V>(R[3]), r11 = splat<V>(R[4]), r12 = splat<V>(R[5]);
    const V r20 = splat<V>(R[6]), r21 = splat<V>(R[7]), r22 = splat<V>(R[8]);
    const V tx = splat<V>(t[0]), ty = splat<V>(t[1]), tz = splat<V>(t[2]);
    const V high = splat<V>(waterHigh), dry = splat<V>(std::numeric_limits<double>::infinity()), zero = V{};
    const double* qx = s.qx.data();
    const double* qy = s.qy.data();
    const double* qz = s.qz.data();
    const PatchLanes lanes = patchLanes(g);
    Mask<V> bad{};
    std::size_t i = 0;
    for (; i + N <= n; i += N) {
        const V px = load<V>(qx + i), py = load<V>(qy + i), pz = load<V>(qz + i);
        const V y = r10 * px + r11 * py + r12 * pz + ty;
        const V x = r00 * px + r01 * py + r02 * pz + tx;
        const V z = r20 * px + r21 * py + r22 * pz + tz;
        const V f = interpolate(lanes, x, z);
        bad |= mask<V>((f * zero) != zero);  // NaN or ±∞
        store<V>(D + i, select<V>(mask<V>(y > high), dry, y - f));
    }
    return any(bad) ? SIZE_MAX : i;
}

/// The interpolant at the points [0, n − n mod N) (interpolatePatchHeights); returns the first point not done.
BB_VM_INLINE std::size_t heightsKernel(const WaterPatch::CellGrid& g, const double* x, const double* z, std::size_t n,
                                       double* out) {
    constexpr int N = Traits<V>::N;
    std::size_t i = 0;
    const PatchLanes lanes = patchLanes(g);
    for (; i + N <= n; i += N) store<V>(out + i, interpolate(lanes, load<V>(x + i), load<V>(z + i)));
    return i;
}

/// Pass 3 for the triangles [0, n − n mod N) (sumWetTriangles); returns the first triangle not done.
BB_VM_INLINE std::size_t trianglesKernel(const VertexShares& s, const double* D, double S[3],
                                         std::int32_t* straddling, std::size_t& listed) {
    constexpr int N = Traits<V>::N;
    const std::size_t n = s.triangleCount();
    const V zero = V{};
    V sx = zero, sy = zero, sz = zero;
    const std::int32_t* c0 = s.corner[0].data();
    const std::int32_t* c1 = s.corner[1].data();
    const std::int32_t* c2 = s.corner[2].data();
    std::size_t i = 0;
    for (; i + N <= n; i += N) {
        const V d0 = gatherLanes(D, c0 + i), d1 = gatherLanes(D, c1 + i), d2 = gatherLanes(D, c2 + i);
        const Mask<V> w0 = mask<V>(d0 <= zero), w1 = mask<V>(d1 <= zero), w2 = mask<V>(d2 <= zero);
        const Mask<V> anyWet = w0 | w1 | w2;
        if (!any(anyWet)) continue;
        const Mask<V> z0 = mask<V>(d0 == zero), z1 = mask<V>(d1 == zero), z2 = mask<V>(d2 == zero);
        // Exactly two corners on the water (the third then below: wet): clipped like the straddling ones.
        const Mask<V> twoOnWater = (z0 & z1 & ~z2) | (z0 & ~z1 & z2) | (~z0 & z1 & z2);
        const Mask<V> whole = w0 & w1 & w2 & ~twoOnWater;
        const V sum = select<V>(whole, d0 + d1 + d2, zero), s2 = sum * sum;
        sx += s2 * load<V>(s.ax.data() + i);
        sy += s2 * load<V>(s.ay.data() + i);
        sz += s2 * load<V>(s.az.data() + i);
        const Mask<V> list = anyWet & ~whole;
        if (any(list))
            for (int l = 0; l < N; ++l)
                if (list[l]) straddling[listed++] = std::int32_t(i + l);
    }
    for (int l = 0; l < N; ++l) {
        S[0] += sx[l];
        S[1] += sy[l];
        S[2] += sz[l];
    }
    return i;
}

/// v1 where lone[1], v2 where lone[2], v0 elsewhere (the value at the lone corner L).
BB_VM_INLINE V pickLone(const Mask<V> lone[3], const V& v0, const V& v1, const V& v2) {
    return select<V>(lone[1], v1, select<V>(lone[2], v2, v0));
}

/// Pass 4 for the listed triangles list[0, count) (sumStraddlingTriangles), N at a time: a lane past the end repeats
/// the last triangle with weight 0. The formulas of sumStraddlingTriangles lane by lane, the lone corner chosen by
/// masks.
BB_VM_INLINE void straddlingKernel(const VertexShares& s, const double* D, const std::int32_t* list, std::size_t count,
                                   const double u[3], const double X[3], const double Z[3], double xr, double zr,
                                   StraddlingSums& out) {
    constexpr int N = Traits<V>::N;
    const V zero = V{}, one = splat<V>(1.0), two = splat<V>(2.0), three = splat<V>(3.0);
    const V ux = splat<V>(u[0]), uy = splat<V>(u[1]), uz = splat<V>(u[2]);
    const V Xx = splat<V>(X[0]), Xy = splat<V>(X[1]), Xz = splat<V>(X[2]);
    const V Zx = splat<V>(Z[0]), Zy = splat<V>(Z[1]), Zz = splat<V>(Z[2]);
    const V xrv = splat<V>(xr), zrv = splat<V>(zr);
    V F[3] = {zero, zero, zero}, T[3] = {zero, zero, zero}, Q[3] = {zero, zero, zero}, B[3] = {zero, zero, zero};
    V d2Sum = zero, areaSum = zero, wl[6] = {zero, zero, zero, zero, zero, zero};
    for (std::size_t k = 0; k < count; k += N) {
        std::int32_t tri[N], corner[3][N];
        V weight;
        for (int l = 0; l < N; ++l) {
            const bool inside = k + std::size_t(l) < count;
            tri[l] = list[inside ? k + std::size_t(l) : count - 1];
            weight[l] = inside ? 1.0 : 0.0;
            for (int c = 0; c < 3; ++c) corner[c][l] = s.corner[c][std::size_t(tri[l])];
        }
        V q[3][3], d[3];  // q[corner][axis]
        for (int c = 0; c < 3; ++c) {
            q[c][0] = gatherLanes(s.qx.data(), corner[c]);
            q[c][1] = gatherLanes(s.qy.data(), corner[c]);
            q[c][2] = gatherLanes(s.qz.data(), corner[c]);
            d[c] = gatherLanes(D, corner[c]);
        }
        const V A[3] = {gatherLanes(s.ax.data(), tri), gatherLanes(s.ay.data(), tri), gatherLanes(s.az.data(), tri)};
        const V absA = gatherLanes(s.absArea.data(), tri);
        const V Au = A[0] * ux + A[1] * uy + A[2] * uz;
        const V sum[3] = {q[0][0] + q[1][0] + q[2][0], q[0][1] + q[1][1] + q[2][1], q[0][2] + q[1][2] + q[2][2]};
        V sdWet = zero, sd2Wet = zero, wet = zero, sdAll = zero, sd2All = zero, dry = zero;
        V sdwWet[3] = {zero, zero, zero}, sdwAll[3] = {zero, zero, zero};
        for (int c = 0; c < 3; ++c) {
            const V isWet = select<V>(mask<V>(d[c] <= zero), one, zero);
            dry += one - isWet;
            sdAll += d[c];
            sd2All += d[c] * d[c];
            sdWet += isWet * d[c];
            sd2Wet += isWet * d[c] * d[c];
            wet += isWet;
            for (int a = 0; a < 3; ++a) {
                const V dw = d[c] * (q[c][a] + sum[a]);
                sdwAll[a] += dw;
                sdwWet[a] += isWet * dw;
            }
        }
        // The lone corner L (masks), and its successor L+1 and predecessor L−1 in winding order.
        const Mask<V> noDry = mask<V>(dry == zero), oneDry = mask<V>(dry == one);
        Mask<V> lone[3];
        for (int c = 0; c < 3; ++c) {
            const Mask<V> sideMatches = ~(mask<V>(d[c] > zero) ^ oneDry);
            lone[c] = (noDry & mask<V>(d[c] != zero)) | (~noDry & sideMatches);
        }
        const V dL = pickLone(lone, d[0], d[1], d[2]), dP = pickLone(lone, d[1], d[2], d[0]);
        const V dM = pickLone(lone, d[2], d[0], d[1]);
        V qL[3], Ep[3], Em[3];
        const V lDry = select<V>(mask<V>(dL > zero), one, zero);
        const V tp = dL / (dL - dP), tm = dL / (dL - dM);
        for (int a = 0; a < 3; ++a) {
            qL[a] = pickLone(lone, q[0][a], q[1][a], q[2][a]);
            const V qP = pickLone(lone, q[1][a], q[2][a], q[0][a]), qM = pickLone(lone, q[2][a], q[0][a], q[1][a]);
            Ep[a] = qL[a] + tp * (qP - qL[a]);
            Em[a] = qL[a] + tm * (qM - qL[a]);
        }
        const V f = tp * tm, sign = one - two * lDry;
        const V sd3 = weight * (sign * dL * f - sdWet + lDry * sdAll);
        V sdw12[3];
        for (int a = 0; a < 3; ++a)
            sdw12[a] = weight * (sign * f * dL * (two * qL[a] + Ep[a] + Em[a]) - sdwWet[a] + lDry * sdwAll[a]);
        const V share3 = weight * (three * (sign * f + lDry) - wet);
        for (int a = 0; a < 3; ++a) {
            F[a] += sd3 * A[a];
            Q[a] += Au * sdw12[a];
            B[a] += share3 * A[a];
        }
        T[0] += sdw12[1] * A[2] - sdw12[2] * A[1];
        T[1] += sdw12[2] * A[0] - sdw12[0] * A[2];
        T[2] += sdw12[0] * A[1] - sdw12[1] * A[0];
        d2Sum += weight * Au * (two * sign * f * dL * dL - sd2Wet + lDry * (sd2All + sdAll * sdAll));
        areaSum += share3 * absA;
        // The waterline segment (WaterlineSums::add), start → end.
        const V xp = Xx * Ep[0] + Xy * Ep[1] + Xz * Ep[2] - xrv, zp = Zx * Ep[0] + Zy * Ep[1] + Zz * Ep[2] - zrv;
        const V xm = Xx * Em[0] + Xy * Em[1] + Xz * Em[2] - xrv, zm = Zx * Em[0] + Zy * Em[1] + Zz * Em[2] - zrv;
        const Mask<V> isDry = mask<V>(lDry > zero);
        const Mask<V> none = isDry & mask<V>(dP == zero) & mask<V>(dM == zero);
        const V xe = select<V>(isDry, xm, xp), ze = select<V>(isDry, zm, zp);
        const V xn = select<V>(none, xe, select<V>(isDry, xp, xm)), zn = select<V>(none, ze, select<V>(isDry, zp, zm));
        const V c = weight * (zn * xe - xn * ze);
        wl[0] += c;
        wl[1] += (xn + xe) * c;
        wl[2] += (zn + ze) * c;
        wl[3] += (xn * xn + xn * xe + xe * xe) * c;
        wl[4] += (two * xn * zn + xn * ze + xe * zn + two * xe * ze) * c;
        wl[5] += (zn * zn + zn * ze + ze * ze) * c;
    }
    for (int l = 0; l < N; ++l) {
        for (int a = 0; a < 3; ++a) {
            out.F[a] += F[a][l];
            out.T[a] += T[a][l];
            out.Q[a] += Q[a][l];
            out.B[a] += B[a][l];
        }
        out.D2 += d2Sum[l];
        out.area += areaSum[l];
        out.waterline.area2 += wl[0][l];
        out.waterline.x6 += wl[1][l];
        out.waterline.z6 += wl[2][l];
        out.waterline.xx12 += wl[3][l];
        out.waterline.xz24 += wl[4][l];
        out.waterline.zz12 += wl[5][l];
    }
}

/// Pass 2: add the shares of the vertices [0, n − n mod N) with D ≤ 0 to out[kShareSums] (layout: see ShareSum); returns the
/// first vertex not summed. A lane with D > 0 (or +∞, not computed) adds exact zeros.
BB_VM_INLINE std::size_t sharesKernel(const VertexShares& s, const double* D, std::size_t n, double* out) {
    constexpr int N = Traits<V>::N;
    const V zero = V{}, one = splat<V>(1.0);
    V acc[kShareSums];
    for (V& a : acc) a = zero;
    std::size_t i = 0;
    for (; i + N <= n; i += N) {
        const V d0 = load<V>(D + i);
        const Mask<V> wet = mask<V>(d0 <= 0);
        if (!any(wet)) continue;
        const V d = select<V>(wet, d0, zero), w = select<V>(wet, one, zero), d2 = d * d;
        const V bx = load<V>(s.bx.data() + i), by = load<V>(s.by.data() + i), bz = load<V>(s.bz.data() + i);
        acc[kFx] += d * bx;
        acc[kFy] += d * by;
        acc[kFz] += d * bz;
        acc[kTx] += d * load<V>(s.tx.data() + i);
        acc[kTy] += d * load<V>(s.ty.data() + i);
        acc[kTz] += d * load<V>(s.tz.data() + i);
        acc[kGx] += d2 * bx;
        acc[kGy] += d2 * by;
        acc[kGz] += d2 * bz;
        acc[kBx] += w * bx;
        acc[kBy] += w * by;
        acc[kBz] += w * bz;
        acc[kArea] += w * load<V>(s.area.data() + i);
        for (int k = 0; k < 9; ++k) acc[kM + k] += d * load<V>(s.m[k].data() + i);
    }
    for (int k = 0; k < kShareSums; ++k)
        for (int l = 0; l < N; ++l) out[k] += acc[k][l];
    return i;
}
