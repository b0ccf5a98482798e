#include "cli/BenchCommand.h"

#include "cli/Progress.h"

#include "scene/SceneErrors.h"

#include "benchmark/BenchShapes.h"
#include "benchmark/Fig9.h"
#include "benchmark/LodStudy.h"
#include "benchmark/OpenClScaling.h"
#include "benchmark/PrimitiveTiming.h"
#include "benchmark/Scaling.h"
#include "benchmark/TemporalLod.h"
#include "benchmark/SpeedVsError.h"
#include "benchmark/Summary.h"

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>
#include <vector>

namespace buoyancy::cli {

void addBenchCommand(CLI::App& app, BenchOptions& options) {
    CLI::App* b = app.add_subcommand("bench", "Speed against error benchmark: CSVs and summary.md in DIR");
    b->add_flag("--quick", options.quick, "Reduced set for a smoke test (well under 30 s)");
    b->add_option("--out", options.out, "Output folder (created when missing)");
    b->add_option("--parts", options.parts,
                  "Parts to run, comma-separated: speed (flat water), waves (speed against error in waves), fig9, "
                  "scaling, lod, opencl, primitives");
    b->add_option("--opencl-bodies", options.openclBodies,
                  "Body counts of the opencl part, comma-separated, each 1 to 100000 (default 1,10,100,1000)");
    b->add_option("--scaling-bodies", options.scalingBodies,
                  "Body counts of the scaling part, comma-separated, each 1 to 100000: only the public-API rows at the "
                  "default settings, 3 windows each (default: the full set)");
    b->add_option("--scaling-threads", options.scalingThreads,
                  "Thread counts of the scaling part, comma-separated, each 1 to 1024 (default 1,2)");
}

namespace {

/// "1,10,100" → {1, 10, 100}, each in [1, most]; anything else is a UsageError naming `option`.
std::vector<int> parseCounts(const std::string& text, const std::string& option, long most, const char* what) {
    const std::string range = std::string(what) + " from 1 to " + std::to_string(most);
    std::vector<int> counts;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        std::size_t used = 0;
        long n = 0;
        try {
            n = std::stol(item, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != item.size() || n < 1 || n > most)
            throw UsageError(option + ": '" + item + "' is not a " + range + " (e.g. 1,10,100,1000)");
        counts.push_back(int(n));
    }
    if (counts.empty() || text.back() == ',')
        throw UsageError(option + ": '" + text + "' is not a comma-separated list of " + what + "s (e.g. 1,10,100,1000)");
    return counts;
}

}  // namespace

int runBench(const BenchOptions& o) {
    using namespace buoyancy::bench;
    bool speed = false, fig9 = false, scaling = false, opencl = false;
    bool lod = false, waves = false, primitives = false;
    {
        std::stringstream ss(o.parts);
        std::string p;
        while (std::getline(ss, p, ',')) {
            if (p == "speed") speed = true;
            else if (p == "waves") waves = true;
            else if (p == "fig9") fig9 = true;
            else if (p == "scaling") scaling = true;
            else if (p == "opencl") opencl = true;
            else if (p == "lod") lod = true;
            else if (p == "primitives") primitives = true;
            else throw UsageError("--parts: unknown part '" + p + "' (speed, waves, fig9, scaling, lod, opencl, primitives)");
        }
    }
    // Checked before any part runs, so a typo does not cost the parts before it.
    const std::vector<int> openclBodies =
        o.openclBodies.empty() ? std::vector<int>{} : parseCounts(o.openclBodies, "--opencl-bodies", 100000, "body count");
    const std::vector<int> scalingBodies = o.scalingBodies.empty()
                                               ? std::vector<int>{}
                                               : parseCounts(o.scalingBodies, "--scaling-bodies", 100000, "body count");
    const std::vector<int> scalingThreads = o.scalingThreads.empty()
                                                ? std::vector<int>{}
                                                : parseCounts(o.scalingThreads, "--scaling-threads", 1024, "thread count");
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(o.out, ec);
    if (ec || !fs::is_directory(o.out)) throw UsageError("--out: cannot create folder '" + o.out + "'");
    const auto t0 = std::chrono::steady_clock::now();
    std::ostream& log = std::cerr;
    log << "buoyancy bench" << (o.quick ? " --quick" : "") << ": writing to " << o.out << " ("
        << std::thread::hardware_concurrency() << " hardware threads)\n";

    // A line per part done (the parts' own lines go to stderr too, so no bar that they would break).
    const int parts = int(speed) + int(waves) + int(fig9) + int(scaling) + int(opencl) + int(lod) + int(primitives);
    ProgressReporter progress("bench", parts, " parts", ProgressReporter::Mode::Lines);
    int partsDone = 0;
    std::vector<SpeedErrorRow> rows;
    SpeedErrorOptions speedOptions;
    if (o.quick) {
        speedOptions.textures = {32, 128};
        speedOptions.drafts = {0.3, 0.7};
        speedOptions.heels = {0, 30};
        speedOptions.hullProbes = {32};
        speedOptions.gridProbes = {64};
        speedOptions.timing.minBatchSeconds = 2e-4;
        speedOptions.timing.batches = 2;
        speedOptions.waveTimes = {1.0, 3.0};
        speedOptions.waveOffsets = {-0.2, 0.2};
        speedOptions.waveGridProbes = {};
        speedOptions.oracleWaterlineLevels = 3;
    }
    if (speed) {
        std::vector<std::string> warnings;
        const std::vector<BenchShape> shapes = benchShapes(o.quick, warnings);
        for (const auto& w : warnings) log << "warning: " << w << '\n';
        rows = runSpeedVsError(shapes, speedOptions, log);
        progress.update(++partsDone);
    }
    if (waves) {  // the wave rows of the same table (docs/benchmarks/README.md, "Wave rows")
        std::vector<std::string> warnings;
        const std::vector<BenchShape> shapes = waveBenchShapes(warnings);
        for (const auto& w : warnings) log << "warning: " << w << '\n';
        const auto tw = std::chrono::steady_clock::now();
        for (const SpeedErrorRow& r : runSpeedVsErrorWaves(shapes, benchSeas(), speedOptions, log)) rows.push_back(r);
        log << "waves: " << std::chrono::duration<double>(std::chrono::steady_clock::now() - tw).count() << " s\n";
        progress.update(++partsDone);
    }
    if (speed || waves) writeSpeedVsErrorCsv((fs::path(o.out) / "speed_vs_error.csv").string(), rows);
    if (fig9) {
        Fig9Options fo;
        if (o.quick) {
            fo.textures = {32, 128};
            fo.depths = 11;
            fo.segments = 64;
            fo.rings = 32;
        }
        runFig9(fo, (fs::path(o.out) / "fig9_sphere_volume.csv").string(), log);
    }
    progress.update(++partsDone);
    std::vector<ScalingRow> scale;
    std::string breakdown, temporalMd;
    if (scaling) {
        ScalingOptions so;
        // 1,000 bodies get 240 substeps (1 s simulated): with 48 (0.2 s) the 2-thread rows of the temporal level of
        // detail moved by ±25 % from run to run (a tenth of a wave period decides how many predictions pass).
        so.maxBodySubsteps = 240000;
        // Through the public API (driver `world`), 100 to 4,000 boats, each row the median of 3 timed windows after
        // one warm-up; the benchmark's own OpenMP driver (`bench`) at 1,000 boats beside it.
        so.bodies = {1, 10, 100, 1000, 1500, 2000, 4000};
        // At ≈ 60 µs per boat-substep on one core (the curved-water model on these waves) 4,000 boats cost 0.06 s per
        // substep: each window times 60,000 body-substeps (1 s of 100 boats, 60 substeps of 1,000, 15 of 4,000) after
        // 1 s of warm-up, so the part stays within minutes.
        so.maxBodySubsteps = 60000;
        so.windows = 3;
        so.warmupSeconds = 1.0;
        if (o.quick) {
            so.windows = 1;
            so.bodies = {1, 10, 100};
            so.simSeconds = 1.0 / 30;
            so.maxBodySubsteps = 400;
            so.warmupSeconds = 1.0 / 60;
        }
        // The README demo's model is the boat hull (850 triangles); the scaling figure asks for ≥ 1,000 triangles,
        // so the scaling run uses it subdivided once (3,400 triangles, the same solid).
        if (!scalingThreads.empty()) so.threads = scalingThreads;
        const bool chosen = !scalingBodies.empty();
        if (chosen) {
            // Rows asked for by count: each window is a whole simulated second (every substep of the wave period's
            // phase the temporal level of detail sees), after 2 s of warm-up.
            so.bodies = scalingBodies;
            so.maxBodySubsteps = 1e12;
            so.warmupSeconds = 2.0;
        }
        const TriangleMesh boat = subdivideMesh(loadBoatHull());
        scale = runScaling(boat, "boat-x4", so, log);
        if (!o.quick && !chosen) {
            // The same fleets with the water over each triangle as a plane (the exact-mesh model before the
            // curved-water default, ≈ 4–5× cheaper on these waves): what the threads give at that cost.
            ScalingOptions plane = so;
            plane.bodies = {1000, 1500, 2000};
            plane.planeWater = true;
            plane.variant = "plane water";
            for (const ScalingRow& r : runScaling(boat, "boat-x4", plane, log)) scale.push_back(r);
            ScalingOptions bench = so;
            bench.bodies = {1000};
            bench.drivers = {"bench"};
            for (const ScalingRow& r : runScaling(boat, "boat-x4", bench, log)) scale.push_back(r);
        }
        if (!chosen) {
            // The 1,000-boat run with a longer temporal level of detail than the default's (hydrostaticsInterval; its
            // error is in temporal_lod.csv): what real time costs in accuracy.
            for (int k : {8, 12, 16}) {
                ScalingOptions tk = so;
                tk.bodies = {o.quick ? 10 : 1000};
                tk.threads = o.quick ? std::vector<int>{1} : std::vector<int>{1, 2};
                tk.settings.hydrostaticsInterval = k;
                tk.settings.hydrostaticsReuseTolerance = 0.002;
                tk.variant = "interval " + std::to_string(k) + " tolerance 0.2%";
                tk.windows = 1;
                for (const ScalingRow& r : runScaling(boat, "boat-x4", tk, log)) scale.push_back(r);
            }
            TemporalLodOptions to;
            if (o.quick) {
                to.configurations = {{1, 0.0}, {0, 0.0}, {4, 0.002}};
                to.bodies = 2;
                to.fleetBodies = 0;
                to.settleSeconds = 0.5;
                to.seconds = 0.5;
                to.energySeconds = 5.0;
            }
            const std::vector<TemporalLodRow> temporal = runTemporalLod(boat, "boat-x4", to, log);
            writeTemporalLodCsv((fs::path(o.out) / "temporal_lod.csv").string(), temporal);
            temporalMd = temporalLodMarkdown(temporal);
            // The same scene without the level of detail (the previous default), for the before/after ratio.
            ScalingOptions off = so;
            off.bodies = o.quick ? std::vector<int>{1, 10} : std::vector<int>{1, 100};
            off.threads = {1};
            off.maxBodySubsteps = o.quick ? so.maxBodySubsteps : 8000;  // ≈ 0.3 ms per body-substep without it
            off.settings.dragClusters = 0;
            off.settings.waterPatchNodes = 0;
            off.settings.waterVelocityProbes = 0;
            off.variant = "no-lod";
            off.windows = 1;
            off.warmupSeconds = 1.0 / 60;  // ≈ 0.3 ms per body-substep: a second of warm-up would take minutes
            for (const ScalingRow& r : runScaling(boat, "boat-x4", off, log)) scale.push_back(r);
        }
        breakdown = scalingBreakdownMarkdown(boat, log);
        writeScalingCsv((fs::path(o.out) / "scaling.csv").string(), scale);
    }
    progress.update(++partsDone);
    if (opencl) {  // OpenCL (PoCL here) next to the CPU path, docs/benchmarks/opencl_scaling.csv
        OpenClScalingOptions co;
        if (o.quick) {
            co.bodies = {1, 10};
            co.maxBodySubsteps = 200;
        }
        if (!openclBodies.empty()) co.bodies = openclBodies;
        const TriangleMesh boat = subdivideMesh(loadBoatHull());
        writeOpenClScalingCsv((fs::path(o.out) / "opencl_scaling.csv").string(), runOpenClScaling(boat, "boat-x4", co, log));
    }
    progress.update(++partsDone);
    std::string lodMd;
    if (lod) {
        std::vector<std::string> warnings;
        std::vector<BenchShape> shapes = benchShapes(o.quick, warnings);
        BenchShape boat;
        boat.name = "boat-x4";
        boat.mesh = subdivideMesh(loadBoatHull());
        shapes.push_back(boat);
        lodMd = "\n## Level of detail: error added and time saved (design.md 2.5)\n\n" +
                runLodStudy(shapes, {"sphere", "boat", "boat-x4", "torus"}, o.out, o.quick, log);
    }
    progress.update(++partsDone);
    std::string primitiveMd;
    if (primitives) {
        const std::vector<PrimitiveRow> prim = runPrimitiveTiming(o.quick, log);
        writePrimitiveCsv((fs::path(o.out) / "primitives.csv").string(), prim);
        primitiveMd = primitiveMarkdown(prim);
        progress.update(++partsDone);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::ostringstream md;
    md << "# Benchmark summary (generated by `buoyancy bench" << (o.quick ? " --quick" : "") << "`, "
       << static_cast<long>(seconds + 0.5) << " s)\n\n"
       << summaryMarkdown(rows, scale) << breakdown << temporalMd << lodMd << primitiveMd;
    {
        std::ofstream f(fs::path(o.out) / "summary.md");
        f << md.str();
        if (!f) throw UsageError("--out: cannot write summary.md in '" + o.out + "'");
    }
    std::cout << md.str();
    log << "bench: done in " << seconds << " s\n";
    return kExitOk;
}

}  // namespace buoyancy::cli
