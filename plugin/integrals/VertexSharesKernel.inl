// VertexSharesKernel.inl: pass 2 of VertexHydrostatics.cpp (the shares of the vertices under water) for one SIMD
// width, included once per instruction set inside its own namespace (force-inlined into a function built for it).
// Expects the vector type V to be defined by the includer. Not a header of its own: no include guard, no public
// declarations.

/// Add the shares of the vertices [0, n − n mod N) with D ≤ 0 to out[kShareSums] (layout: see ShareSum); returns the
/// first vertex not summed. A lane with D > 0 (or +∞, not computed) adds exact zeros.
BB_VM_INLINE std::size_t sumWetShares(const VertexShares& s, const double* D, std::size_t n, double* out) {
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
