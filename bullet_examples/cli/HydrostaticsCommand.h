#pragma once
/// @file HydrostaticsCommand.h
/// `buoyancy hydrostatics MESH …`: dry mass properties and hydrostatics of a posed mesh, in flat water or in any
/// water a scene file can describe (`--water FILE.json`) at a given time.

#include <CLI/CLI.hpp>

#include <vector>
#include <optional>
#include <string>

namespace buoyancy::cli {

/// Options of `buoyancy hydrostatics` (defaults as documented in the README).
struct HydrostaticsOptions {
    std::string mesh;                         ///< mesh file (allow-listed formats)
    double scale = 1.0;                       ///< uniform scale applied after import
    std::vector<double> rotate{0, 1, 0, 0};    ///< axis x, y, z and angle in degrees (about the mesh origin)
    std::vector<double> translate{0, 0, 0};    ///< m, applied after the rotation
    std::optional<double> water_height;       ///< flat water level, m (world y); 0 when absent; not with water_file
    std::optional<double> water_density;      ///< kg/m³; 1000 when absent; not with water_file
    std::optional<std::string> water_file;    ///< JSON file holding a scene's "water" object; absent: flat water
    std::optional<double> time;               ///< the water's time, s (default 0); only with water_file
    double gravity = 9.81;                    ///< m/s²
    std::string method = "default";           ///< texel-centre | exact-coverage | exact-mesh | default
    std::optional<int> texture;               ///< N (texture N×N); ignored with a warning for exact-mesh
    double error_budget = 0;                  ///< automatic level of detail: worst volume error allowed, % (0: none)
    double import_timeout = 10.0;             ///< s, time limit of the child process that runs assimp
    bool json = false;                        ///< print one JSON object instead of a table
    bool repair = false;                      ///< repair what is safe to repair (holes, orientation, faces given twice)
    bool convex_hull = false;                 ///< replace the model by the convex hull of its vertices
};

/// Register the subcommand on `app`; when it is chosen, `run` is set to the function to call after parsing.
void addHydrostaticsCommand(CLI::App& app, HydrostaticsOptions& options);

/// Run it: prints to stdout, warnings and errors to stderr; returns the exit code (SceneErrors.h).
int runHydrostatics(const HydrostaticsOptions& options);

}  // namespace buoyancy::cli
