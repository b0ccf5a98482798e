// The `buoyancy` command-line tool: one executable, one subcommand per job.
//   buoyancy hydrostatics MESH [...]   dry mass properties and hydrostatics (flat water, or --water FILE.json)
//   buoyancy run SCENE.json --out DIR  headless scene runner (trajectory CSV)
//   buoyancy bench [--quick] [--out DIR]  speed against error benchmark
// Exit codes (every subcommand): 0 success, 2 bad input or usage, 3 internal failure.

#include "cli/BenchCommand.h"
#include "scene/SceneErrors.h"
#include "cli/HydrostaticsCommand.h"
#include "cli/RunCommand.h"

#ifdef BUOYANCY_HAVE_RENDER
#include "render/PngRecorder.h"  // `run --png`; absent when OpenGL/EGL/stb were not found
#endif

#include <CLI/CLI.hpp>

#include <exception>
#include <functional>
#include <iostream>
#include <string>

int main(int argc, char** argv) {
    using namespace buoyancy::cli;
    CLI::App app{"buoyancy: real-time buoyancy for Bullet Physics (hydrostatics, scene runner, benchmark)", "buoyancy"};
    app.set_version_flag("--version", std::string("buoyancy ") + BUOYANCY_VERSION, "Print the version and exit");
    app.require_subcommand(1);

    HydrostaticsOptions hydro;
    addHydrostaticsCommand(app, hydro);
    RunOptions run;
    addRunCommand(app, run);
#ifdef BUOYANCY_HAVE_RENDER
    run.pngSink = buoyancy::render::makePngSink;
#endif
    BenchOptions bench;
    addBenchCommand(app, bench);

    // CLI11 only says "A subcommand is required" for a misspelt one: name it.
    if (argc > 1 && argv[1][0] != '-' && app.get_subcommands(std::function<bool(CLI::App*)>([&](CLI::App* s) { return s->get_name() == argv[1]; })).empty()) {
        std::cerr << "error: unknown command '" << argv[1] << "' (hydrostatics, run, bench)\n";
        return kExitBadInput;
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::CallForVersion& e) {
        return app.exit(e);  // prints "buoyancy <version>" on stdout, exit 0
    } catch (const CLI::ParseError& e) {
        app.exit(e);  // prints the parser's message on stderr
        return kExitBadInput;
    }

    try {
        if (app.got_subcommand("hydrostatics")) return runHydrostatics(hydro);
        if (app.got_subcommand("run")) return runScene(run);
        if (app.got_subcommand("bench")) return runBench(bench);
    } catch (const UsageError& e) {
        std::cerr << "error: " << e.what() << '\n';
        return kExitBadInput;
    } catch (const std::exception& e) {
        std::cerr << "internal error: " << e.what() << '\n';
        return kExitInternal;
    }
    return kExitBadInput;
}
