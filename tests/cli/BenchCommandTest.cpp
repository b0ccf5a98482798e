// The bench subcommand's own options: bad values are refused before any part runs, naming the option.

#include "CliRunner.h"

#include <catch2/catch.hpp>

#include <string>

using buoyancy_test::runCli;
using buoyancy_test::scratchDir;
using Catch::Matchers::Contains;

TEST_CASE("buoyancy bench: --opencl-bodies refuses what is not a body count and names the option", "[cli]") {
    const std::string dir = scratchDir("bench_opencl_bodies");
    for (const char* bad : {"0", "x", "10,", "1,,10", "100001", "-5", "3.5", "1e3"}) {
        // fig9 would run for seconds: the refusal must come before it.
        const auto r = runCli({"bench", "--quick", "--parts", "fig9,opencl", "--opencl-bodies", bad, "--out", dir});
        INFO("--opencl-bodies " << bad << " stderr: " << r.err);
        CHECK(r.exit_code == 2);
        CHECK_THAT(r.err, Contains("--opencl-bodies"));
        CHECK_THAT(r.err, !Contains("bench:"));  // no part started
    }
}

TEST_CASE("buoyancy bench: --opencl-bodies sets the body counts of the opencl rows", "[cli]") {
    const std::string dir = scratchDir("bench_opencl_rows");
    const auto r = runCli({"bench", "--quick", "--parts", "opencl", "--opencl-bodies", "2,3", "--out", dir});
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    // The CPU rows always run (the OpenCL rows only where a device exists): one per body count.
    CHECK_THAT(r.err, Contains("opencl scaling: cpu 2 bodies"));
    CHECK_THAT(r.err, Contains("opencl scaling: cpu 3 bodies"));
    CHECK_THAT(r.err, !Contains("opencl scaling: cpu 1 bodies"));
    CHECK_THAT(r.err, !Contains("opencl scaling: cpu 10 bodies"));
}
