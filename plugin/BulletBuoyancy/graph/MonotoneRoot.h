#pragma once
/// @file MonotoneRoot.h
/// Root of an increasing function on a bracket [lo, hi] with f(lo) ≤ 0 ≤ f(hi): the Illinois variant of
/// regula falsi (Dowell & Jarratt 1971), with a bisection step whenever the bracket shrinks slowly.
/// Always stays bracketed; typically 6–12 evaluations to a tolerance of 1e-13 of the bracket.

namespace buoyancy {

/// @param f    callable double → double, increasing
/// @param tol  stop when the bracket is narrower than this (same unit as x)
template <class F>
double monotoneRoot(const F& f, double lo, double hi, double flo, double fhi, double tol) {
    if (!(flo < 0)) return lo;
    if (!(fhi > 0)) return hi;
    int side = 0;
    for (int it = 0; it < 200 && hi - lo > tol; ++it) {
        double x = lo - flo * (hi - lo) / (fhi - flo);
        if (!(x > lo && x < hi)) x = 0.5 * (lo + hi);
        const double fx = f(x);
        if (fx == 0) return x;
        const double width = hi - lo;
        if (fx < 0) {
            lo = x;
            flo = fx;
            if (side == -1) fhi *= 0.5;
            side = -1;
        } else {
            hi = x;
            fhi = fx;
            if (side == 1) flo *= 0.5;
            side = 1;
        }
        if (hi - lo > 0.75 * width) {
            const double mid = 0.5 * (lo + hi);
            const double fm = f(mid);
            if (fm == 0) return mid;
            if (fm < 0) {
                lo = mid;
                flo = fm;
            } else {
                hi = mid;
                fhi = fm;
            }
            side = 0;
        }
    }
    const double x = lo - flo * (hi - lo) / (fhi - flo);
    return (x >= lo && x <= hi) ? x : 0.5 * (lo + hi);
}

}  // namespace buoyancy
