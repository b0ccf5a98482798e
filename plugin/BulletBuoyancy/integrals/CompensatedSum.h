#pragma once
/// @file CompensatedSum.h
/// Internal: K running sums with Neumaier compensation, fed block by block (plain sums inside a block of
/// samples, compensated addition of each block's partial sums), so long sums of ~10⁶ samples keep
/// O(block · ε) instead of O(n · ε) relative error without slowing the per-sample loop.

#include <array>
#include <cmath>
#include <cstddef>

namespace buoyancy {
namespace detail {

/// Samples summed plainly before a partial sum is folded into the compensated total.
constexpr std::size_t kSumBlock = 256;

/// K compensated accumulators (Neumaier 1974, improved Kahan summation).
template <std::size_t K>
struct CompensatedSum {
    std::array<double, K> sum{};  ///< running totals
    std::array<double, K> comp{}; ///< running compensation (lost low-order parts)

    /// Add one value per accumulator.
    void add(const double* v) {
        for (std::size_t k = 0; k < K; ++k) {
            const double t = sum[k] + v[k];
            if (std::abs(sum[k]) >= std::abs(v[k]))
                comp[k] += (sum[k] - t) + v[k];
            else
                comp[k] += (v[k] - t) + sum[k];
            sum[k] = t;
        }
    }
    /// Compensated total of accumulator k.
    double value(std::size_t k) const { return sum[k] + comp[k]; }
};

}  // namespace detail
}  // namespace buoyancy
