// The saved-state byte format of the core (state/StateBlob.h): values written by StateWriter read back bit for bit;
// the header holds the kind and the precision byte the caller gives; a reader that expects another precision or kind
// refuses the blob with a message naming both, in the caller's words when it gives them (StateNames).
#include <BulletBuoyancy/state/StateBlob.h>

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

using Catch::Matchers::Contains;
using buoyancy::StateReader;
using buoyancy::StateWriter;

namespace {

const char* testKindName(std::uint8_t kind) { return kind == 1 ? "Alpha" : kind == 2 ? "Beta" : "unknown"; }

std::vector<unsigned char> sampleBlob(std::uint8_t kind, std::uint8_t precisionBytes) {
    StateWriter out(kind, precisionBytes);
    out.u8(7);
    out.boolean(true);
    out.i32(-5);
    out.u64(std::numeric_limits<std::uint64_t>::max());
    out.f64(-0.1);
    out.f32(2.5f);
    out.f64Vector({1.0, std::nan(""), -0.0});
    return out.bytes();
}

}  // namespace

TEST_CASE("state blob: the values read back bit for bit, the header holds the caller's kind and precision",
          "[state]") {
    for (const std::uint8_t precision : {std::uint8_t(4), std::uint8_t(8)}) {
        const std::vector<unsigned char> blob = sampleBlob(2, precision);
        REQUIRE(blob.size() >= 24);
        CHECK(std::string(blob.begin(), blob.begin() + 4) == "BBST");
        CHECK(blob[4] == buoyancy::kStateFormatVersion);
        CHECK(blob[5] == 0);
        CHECK(blob[6] == precision);
        CHECK(blob[7] == 2);
        StateReader in(blob.data(), blob.size(), 2, precision, "test");
        CHECK(in.u8("byte") == 7);
        CHECK(in.boolean("flag"));
        CHECK(in.i32("signed") == -5);
        CHECK(in.u64("unsigned") == std::numeric_limits<std::uint64_t>::max());
        CHECK(in.f64("double") == -0.1);
        CHECK(in.f32("float") == 2.5f);
        const std::vector<double> v = in.f64Vector("vector");
        REQUIRE(v.size() == 3);
        CHECK(v[0] == 1.0);
        CHECK(std::isnan(v[1]));
        CHECK((v[2] == 0.0 && std::signbit(v[2])));
        CHECK(in.remaining() == 0);
        CHECK_NOTHROW(in.finish());
    }
    // The same values with another precision byte differ in that byte only.
    const std::vector<unsigned char> a = sampleBlob(2, 4), b = sampleBlob(2, 8);
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) CHECK((i == 6 || a[i] == b[i]));
}

TEST_CASE("state blob: a reader refuses another precision or kind, naming both", "[state]") {
    const std::vector<unsigned char> blob = sampleBlob(1, 8);
    CHECK_THROWS_AS(StateReader(blob.data(), blob.size(), 1, 4, "reader"), std::invalid_argument);
    CHECK_THROWS_WITH(StateReader(blob.data(), blob.size(), 1, 4, "reader"),
                      Contains("reader: saved by a double-precision build (scalar of 8 bytes)") &&
                          Contains("this build is float-precision"));
    CHECK_THROWS_WITH(StateReader(blob.data(), blob.size(), 2, 8, "reader"),
                      Contains("reader: the blob is a kind 1 state, expected a kind 2 state"));
    // In the caller's words.
    buoyancy::StateNames names;
    names.kind = &testKindName;
    names.scalar = "Real";
    CHECK_THROWS_WITH(StateReader(blob.data(), blob.size(), 1, 4, "reader", names),
                      Contains("saved by a double-precision build (Real of 8 bytes)"));
    CHECK_THROWS_WITH(StateReader(blob.data(), blob.size(), 2, 8, "reader", names),
                      Contains("the blob is a Alpha state (kind 1), expected a Beta state"));
    // The precision is checked before the kind (a blob of the other build is named as such).
    CHECK_THROWS_WITH(StateReader(blob.data(), blob.size(), 2, 4, "reader"), Contains("precision"));
}
