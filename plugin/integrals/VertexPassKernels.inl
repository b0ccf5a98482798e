// VertexPassKernels.inl: passes 1 and 3 of VertexHydrostatics.cpp on waves, and the water patch's batch heights, for one SIMD width, included once per
// instruction set inside its own namespace (force-inlined into a function built for it). Expects the vector type V
// to be defined by the includer. Not a header of its own: no include guard, no public declarations.

/// Lane l = base[index[l]] (one load per lane: on the CPUs measured, faster than the gather instructions).
BB_VM_INLINE V gatherLanes(const double* base, const std::int32_t* index) {
    V r;
    for (int l = 0; l < Traits<V>::N; ++l) r[l] = base[index[l]];
    return r;
}

/// The patch's interpolant at world (x, z), lane by lane with the operations of WaterPatch::height (the clamp to the
/// border cells included; x, z finite).
BB_VM_INLINE V interpolate(const WaterPatch::CellGrid& g, const V& x, const V& z) {
    constexpr int N = Traits<V>::N;
    const V lo = splat<V>(1.0), hi = splat<V>(double(g.nodes - 2));
    const int last = g.nodes - 3, perRow = g.nodes - 3;
    const double* coef = g.coefficients;
    // std::min(std::max(u, lo), hi), lane by lane.
    V uc = (x - splat<V>(g.x0)) * splat<V>(g.invH), vc = (z - splat<V>(g.z0)) * splat<V>(g.invH);
    uc = select<V>(mask<V>(uc < lo), lo, uc);
    uc = select<V>(mask<V>(hi < uc), hi, uc);
    vc = select<V>(mask<V>(vc < lo), lo, vc);
    vc = select<V>(mask<V>(hi < vc), hi, vc);
    // Cell and local coordinates: i = min(⌊uc⌋, last) (uc ≥ 1), cell = 16 ((j − 1) perRow + i − 1).
    std::int32_t cell[N];
    V tu, tv;
    for (int l = 0; l < N; ++l) {
        const int ci = std::min(int(uc[l]), last), cj = std::min(int(vc[l]), last);
        tu[l] = uc[l] - ci;
        tv[l] = vc[l] - cj;
        cell[l] = 16 * ((cj - 1) * perRow + (ci - 1));
    }
    const V a0 = ((gatherLanes(coef + 12, cell) * tu + gatherLanes(coef + 8, cell)) * tu +
                  gatherLanes(coef + 4, cell)) * tu + gatherLanes(coef + 0, cell);
    const V a1 = ((gatherLanes(coef + 13, cell) * tu + gatherLanes(coef + 9, cell)) * tu +
                  gatherLanes(coef + 5, cell)) * tu + gatherLanes(coef + 1, cell);
    const V a2 = ((gatherLanes(coef + 14, cell) * tu + gatherLanes(coef + 10, cell)) * tu +
                  gatherLanes(coef + 6, cell)) * tu + gatherLanes(coef + 2, cell);
    const V a3 = ((gatherLanes(coef + 15, cell) * tu + gatherLanes(coef + 11, cell)) * tu +
                  gatherLanes(coef + 7, cell)) * tu + gatherLanes(coef + 3, cell);
    return ((a3 * tv + a2) * tv + a1) * tv + a0;
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
    Mask<V> bad{};
    std::size_t i = 0;
    for (; i + N <= n; i += N) {
        const V px = load<V>(qx + i), py = load<V>(qy + i), pz = load<V>(qz + i);
        const V y = r10 * px + r11 * py + r12 * pz + ty;
        const V x = r00 * px + r01 * py + r02 * pz + tx;
        const V z = r20 * px + r21 * py + r22 * pz + tz;
        const V f = interpolate(g, x, z);
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
    for (; i + N <= n; i += N) store<V>(out + i, interpolate(g, load<V>(x + i), load<V>(z + i)));
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
