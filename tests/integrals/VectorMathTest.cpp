// The lane tests of the SIMD helpers (plugin/BulletBuoyancy/geometry/VectorMath.h) that the vertex, triangle, drag and
// wave kernels branch on: any and all at 2, 4 and 8 lanes, against every pattern of set lanes, each decided here lane
// by lane.
#include <BulletBuoyancy/geometry/VectorMath.h>

#include <catch2/catch.hpp>
#include <cstdint>

using namespace buoyancy::vmath;

namespace {
/// Every pattern of N lanes (bit l of the pattern: lane l all ones, else zero) given to any and all.
template <class V>
void checkEveryPattern() {
    constexpr unsigned N = Traits<V>::N;
    for (unsigned pattern = 0; pattern < (1u << N); ++pattern) {
        Mask<V> m{};
        for (unsigned l = 0; l < N; ++l) m[l] = (pattern >> l & 1u) ? ~std::uint64_t(0) : 0;
        INFO("lanes " << N << ", pattern " << pattern);
        CHECK(any(m) == (pattern != 0));
        CHECK(all(m) == (pattern == (1u << N) - 1));
    }
}
}  // namespace

TEST_CASE("vector masks: any and all at every width, every pattern of lanes", "[integrals][vector]") {
    checkEveryPattern<v2d>();
    checkEveryPattern<v4d>();
    checkEveryPattern<v8d>();
    // Masks as the kernels make them: from lane-wise comparisons.
    const v8d a = {0, 1, 2, 3, 4, 5, 6, 7};
    CHECK(any(mask<v8d>(a > 6.5)));
    CHECK_FALSE(any(mask<v8d>(a > 7.5)));
    CHECK(all(mask<v8d>(a >= 0.0)));
    CHECK_FALSE(all(mask<v8d>(a >= 0.5)));
}
