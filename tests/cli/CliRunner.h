#pragma once
// Runs the `buoyancy` executable as a user would and captures exit code, stdout and stderr.

#include <string>
#include <vector>

namespace buoyancy_test {

struct CliResult {
    int exit_code = -1;
    std::string out;
    std::string err;
};

/// Run BUOYANCY_CLI_PATH with the given arguments (no shell involved).
CliResult runCli(const std::vector<std::string>& args);

/// A fresh scratch directory for one test.
std::string scratchDir(const std::string& name);

/// Write an OBJ file of a closed axis-aligned box centred at the origin (2 triangles per face, no UVs).
void writeBoxObj(const std::string& path, double sx, double sy, double sz);

}  // namespace buoyancy_test
