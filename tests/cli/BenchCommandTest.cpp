// The bench subcommand's own options: bad values are refused before any part runs, naming the option.

#include "CliRunner.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

TEST_CASE("buoyancy bench: --scaling-bodies and --scaling-threads refuse what is not a count and name the option",
          "[cli]") {
    const std::string dir = scratchDir("bench_scaling_counts");
    for (const char* option : {"--scaling-bodies", "--scaling-threads"})
        for (const char* bad : {"0", "x", "2,", "1,,2", "100001", "-1", "1.5"}) {
            const auto r = runCli({"bench", "--quick", "--parts", "fig9,scaling", option, bad, "--out", dir});
            INFO(option << " " << bad << " stderr: " << r.err);
            CHECK(r.exit_code == 2);
            CHECK_THAT(r.err, Contains(option));
            CHECK_THAT(r.err, !Contains("bench:"));  // no part started
        }
}

TEST_CASE("buoyancy bench: --scaling-bodies and --scaling-threads choose the public-API rows of scaling.csv", "[cli]") {
    const std::string dir = scratchDir("bench_scaling_rows");
    const auto r = runCli({"bench", "--quick", "--parts", "scaling", "--scaling-bodies", "2,3", "--scaling-threads",
                           "1", "--out", dir});
    INFO("stderr: " << r.err);
    REQUIRE(r.exit_code == 0);
    std::ifstream csv(dir + "/scaling.csv");
    REQUIRE(csv);
    std::string header, line;
    std::getline(csv, header);
    std::vector<std::string> names;
    {
        std::stringstream ss(header);
        for (std::string c; std::getline(ss, c, ',');) names.push_back(c);
    }
    const auto column = [&](const std::string& name) {
        const auto it = std::find(names.begin(), names.end(), name);
        REQUIRE(it != names.end());
        return std::size_t(it - names.begin());
    };
    const std::size_t bodies = column("bodies"), threads = column("threads"), driver = column("driver");
    const std::size_t predicted = column("predicted_share"), load = column("load_average");
    std::vector<int> seen;
    while (std::getline(csv, line)) {
        std::vector<std::string> cells;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
        REQUIRE(cells.size() == names.size());
        seen.push_back(std::stoi(cells[bodies]));
        CHECK(cells[threads] == "1");
        CHECK(cells[driver] == "world");
        const double share = std::stod(cells[predicted]);
        CHECK(share >= 0.0);
        CHECK(share <= 1.0);
        CHECK(std::stod(cells[load]) >= 0.0);  // /proc/loadavg exists on the machines we test on
    }
    CHECK(seen == std::vector<int>{2, 3});
}
