#include "cli/RunCommand.h"

#include "cli/Progress.h"
#include "scene/NumberFormat.h"
#include "scene/SceneErrors.h"
#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"

#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyEvents.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace buoyancy::cli {

void addRunCommand(CLI::App& app, RunOptions& options) {
    CLI::App* run = app.add_subcommand("run", "Run a scene file headless and write DIR/trajectory.csv and DIR/events.csv");
    run->add_option("scene", options.scene, "Scene JSON file (docs/scene-format.md)")->required();
    run->add_option("--out", options.out, "Output folder (created when missing)")->required();
    run->add_option("--duration", options.duration, "Override the scene's duration, s")->check(CLI::NonNegativeNumber);
    run->add_option("--import-timeout", options.import_timeout, "Time limit of each mesh import, s")
        ->check(CLI::PositiveNumber);
    run->add_option("--png", options.png, "Also render a PNG per output interval into this folder (offscreen)");
    run->add_option("--size", options.size, "Picture size W H in pixels (with --png; default 960 540)")
        ->expected(2);
    run->add_flag("--quiet", options.quiet, "No progress, no level-of-detail lines and no summary (errors still print)");
}

namespace {

/// What the summary at the end needs of each body, gathered at every output row.
struct BodySummary {
    double minUp = HUGE_VAL, maxUp = -HUGE_VAL;  ///< lowest and highest centre of mass along y (up), m
    double sumSubmerged = 0.0;                   ///< Σ submerged volume over the rows, m³
    long rows = 0;                               ///< rows written
    double x = 0, y = 0, z = 0;                  ///< last mesh-origin position, m
    double height = 0;                           ///< last mesh-origin height along the water frame's up, m
};

void writeRows(std::FILE* f, double t, const Scene& scene, SceneWorld& w, std::vector<BodySummary>& summary,
               std::string& line) {
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
        const btBuoyantBody& b = *w.bodies[i];
        const btRigidBody* rb = b.getRigidBody();
        // From the body's own transform (not an interpolated motion state).
        const btTransform mesh = b.getMeshWorldTransform();
        const btQuaternion q = mesh.getRotation();
        const btVector3 c = rb->getCenterOfMassPosition();
        const btVector3 v = rb->getLinearVelocity();
        const btVector3 av = rb->getAngularVelocity();
        btBuoyancyResult r;
        if (w.actions[i]) r = w.actions[i]->getLastResult();
        const double waterVolume = i < w.floods.size() && w.floods[i] ? w.floods[i]->getWaterVolume() : 0.0;
        const double values[] = {mesh.getOrigin().x(), mesh.getOrigin().y(), mesh.getOrigin().z(), q.x(), q.y(), q.z(),
                                 q.w(), c.x(), c.y(), c.z(), v.x(), v.y(), v.z(), av.x(), av.y(), av.z(),
                                 r.submergedVolume, b.getMass(), waterVolume,
                                 r.buoyancyForce.x(), r.buoyancyForce.y(), r.buoyancyForce.z(),
                                 r.dragForce.x(), r.dragForce.y(), r.dragForce.z(),
                                 r.centreOfBuoyancy.x(), r.centreOfBuoyancy.y(), r.centreOfBuoyancy.z()};
        for (double x : values)
            if (!std::isfinite(x))
                throw InternalError("non-finite state of body \"" + scene.bodies[i].name + "\" at t = " + std::to_string(t));
        line.clear();
        appendShortestDecimal(line, t);
        line += ',';
        line += scene.bodies[i].name;
        for (double x : values) {
            line += ',';
            appendShortestDecimal(line, x);
        }
        line += '\n';
        std::fputs(line.c_str(), f);
        BodySummary& s = summary[i];
        // Heights along the water frame's up (world y for a +y-up scene).
        const btWaterFrame& frame = w.buoyancy->getWaterFrame();
        const double up = frame.toWaterPoint(Eigen::Vector3d(double(c.x()), double(c.y()), double(c.z()))).y();
        s.minUp = std::min(s.minUp, up);
        s.maxUp = std::max(s.maxUp, up);
        s.sumSubmerged += r.submergedVolume;
        ++s.rows;
        s.x = mesh.getOrigin().x();
        s.y = mesh.getOrigin().y();
        s.height = frame.toWaterPoint(Eigen::Vector3d(double(mesh.getOrigin().x()), double(mesh.getOrigin().y()),
                                                      double(mesh.getOrigin().z()))).y();
        s.z = mesh.getOrigin().z();
    }
}

/// One line per floating body's level of detail, or past 8 bodies one line per distinct level of detail with its
/// body count.
void printLevelsOfDetail(const Scene& scene, const SceneWorld& w) {
    constexpr std::size_t kLinesUpTo = 8;
    std::vector<std::pair<std::string, std::string>> picks;  // body name, description
    for (std::size_t i = 0; i < w.actions.size() && i < scene.bodies.size(); ++i)
        if (w.actions[i]) {
            const auto& shape = w.actions[i]->getShape();
            picks.emplace_back(scene.bodies[i].name,
                               btBuoyancyPickLevelOfDetail(scene.bodies[i].buoyancy, shape->getMesh().triangleCount())
                                       .description +
                                   ", drag on " + std::to_string(w.actions[i]->getDragClusters().size()) + " clusters");
        }
    if (picks.size() <= kLinesUpTo) {
        for (const auto& [name, description] : picks) std::cerr << "body " << name << ": level of detail " << description << '\n';
        return;
    }
    std::map<std::string, std::size_t> counts;
    for (const auto& pick : picks) {
        // The drag cluster count differs between meshes: group by the level of detail alone.
        const std::string& d = pick.second;
        counts[d.substr(0, d.rfind(", drag on "))] += 1;
    }
    std::cerr << picks.size() << " floating bodies; level of detail:\n";
    for (const auto& [description, count] : counts) std::cerr << "  " << count << " x " << description << '\n';
}

/// The table at the end of a run: each body's final position, the range of its centre of mass along y and half
/// of it (the heave amplitude), and its mean submerged volume; past 20 bodies the spread of those over the bodies.
void printSummary(const Scene& scene, const std::vector<BodySummary>& summary, double tEnd) {
    std::vector<std::size_t> shown;
    for (std::size_t i = 0; i < summary.size(); ++i)
        if (summary[i].rows > 0) shown.push_back(i);
    if (shown.empty()) return;
    std::printf("\nsummary (t = 0 .. %.4g s, %ld rows per body)\n", tEnd, summary[shown.front()].rows);
    constexpr std::size_t kRowsUpTo = 20;
    if (shown.size() <= kRowsUpTo) {
        int nameWidth = 4;
        for (std::size_t i : shown) nameWidth = std::max(nameWidth, static_cast<int>(scene.bodies[i].name.size()));
        std::printf("%-*s  %-30s  %-20s  %11s  %14s\n", nameWidth, "body", "final position (x, y, z) m",
                    "heave min..max m", "amplitude m", "mean V_sub m3");
        for (std::size_t i : shown) {
            const BodySummary& b = summary[i];
            char pos[96], heave[64];
            std::snprintf(pos, sizeof pos, "(%.2f, %.2f, %.2f)", forFixedDecimals(b.x, 2), forFixedDecimals(b.y, 2),
                          forFixedDecimals(b.z, 2));
            std::snprintf(heave, sizeof heave, "%.3f .. %.3f", forFixedDecimals(b.minUp, 3), forFixedDecimals(b.maxUp, 3));
            std::printf("%-*s  %-30s  %-20s  %11.3f  %14.4f\n", nameWidth, scene.bodies[i].name.c_str(), pos, heave,
                        forFixedDecimals(0.5 * (b.maxUp - b.minUp), 3), forFixedDecimals(b.sumSubmerged / b.rows, 4));
        }
        return;
    }
    auto spread = [&](const char* what, const char* unit, auto value) {
        std::vector<double> v;
        for (std::size_t i : shown) v.push_back(value(summary[i]));
        std::sort(v.begin(), v.end());
        std::printf("  %-24s min %10.4g  median %10.4g  max %10.4g %s\n", what, withoutNegativeZero(v.front()),
                    withoutNegativeZero(v[v.size() / 2]), withoutNegativeZero(v.back()), unit);
    };
    std::printf("%zu bodies (one row each: python3 scripts/run_summary.py OUT)\n", shown.size());
    spread("heave amplitude", "m", [](const BodySummary& b) { return 0.5 * (b.maxUp - b.minUp); });
    spread("mean submerged volume", "m3", [](const BodySummary& b) { return b.sumSubmerged / b.rows; });
    spread("final height (along up)", "m", [](const BodySummary& b) { return b.height; });
}

/// Writes each water event to events.csv as it happens: t,substep,body,event,water_body,submerged_fraction.
class EventCsvWriter : public btBuoyancyEventListener {
public:
    EventCsvWriter(std::FILE* file, const Scene& scene, const SceneWorld& world) : m_file(file) {
        for (std::size_t i = 0; i < world.actions.size(); ++i)
            if (world.actions[i]) m_names.emplace_back(world.actions[i].get(), scene.bodies[i].name);
        for (std::size_t i = 0; i < scene.waters.size(); ++i) m_waters.push_back("waters[" + std::to_string(i) + "]");
    }
    void onEnterWater(const btBuoyancyEvent& e) override { write(e, "enter_water"); }
    void onLeaveWater(const btBuoyancyEvent& e) override { write(e, "leave_water"); }
    void onFullySubmerged(const btBuoyancyEvent& e) override { write(e, "fully_submerged"); }
    void onSurfaced(const btBuoyancyEvent& e) override { write(e, "surfaced"); }

private:
    void write(const btBuoyancyEvent& e, const char* type) {
        const char* body = "?";
        for (const auto& [action, name] : m_names)
            if (action == e.action) body = name.c_str();
        const char* water = e.waterBody >= 0 && std::size_t(e.waterBody) < m_waters.size() ? m_waters[e.waterBody].c_str()
                                                                                        : "water";
        std::fprintf(m_file, "%s,%llu,%s,%s,%s,%s\n", shortestDecimal(e.time).c_str(),
                     static_cast<unsigned long long>(e.substep), body, type, water,
                     shortestDecimal(e.submergedFraction).c_str());
    }
    std::FILE* m_file;
    std::vector<std::pair<const btBuoyancyAction*, std::string>> m_names;
    std::vector<std::string> m_waters;
};

}  // namespace

int runScene(const RunOptions& options) {
    const Scene scene = loadSceneFile(options.scene);
    const double duration = options.duration ? *options.duration : scene.duration;
    if (!std::isfinite(duration) || duration < 0) throw UsageError("--duration: must be a number >= 0");

    if (!options.png.empty()) {  // checked before the (possibly long) build
        if (!options.pngSink)
            throw UsageError("--png: this build of buoyancy has no offscreen renderer (OpenGL, EGL or stb were not "
                             "found when it was configured; see scripts/install-deps.sh)");
        if (options.size.size() != 2 || options.size[0] < 16 || options.size[1] < 16 || options.size[0] > 8192 ||
            options.size[1] > 8192)
            throw UsageError("--size: expected two integers W H in [16, 8192]");
    }
    std::unique_ptr<SceneWorld> world = buildSceneWorld(scene, options.import_timeout);
    SceneWorld& w = *world;
    // Say which level of detail each floating body uses (method, texture; the error budget's pick).
    if (!options.quiet) printLevelsOfDetail(scene, w);
    std::unique_ptr<SceneFrameSink> png;
    if (!options.png.empty()) png = options.pngSink(options.png, options.size.at(0), options.size.at(1), scene);

    std::error_code ec;
    std::filesystem::create_directories(options.out, ec);
    const std::string csvPath = (std::filesystem::path(options.out) / "trajectory.csv").string();
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(csvPath.c_str(), "w"), &std::fclose);
    if (!f) throw UsageError("--out: cannot write " + csvPath);
    std::fputs("t,body,x,y,z,qx,qy,qz,qw,cx,cy,cz,vx,vy,vz,wx,wy,wz,submerged_volume,mass,water_volume,"
               "fbx,fby,fbz,fdx,fdy,fdz,cbx,cby,cbz\n",
               f.get());

    // The water events (hysteresis: the scene's "events"), one row each as they happen.
    const std::string eventsPath = (std::filesystem::path(options.out) / "events.csv").string();
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> ef(std::fopen(eventsPath.c_str(), "w"), &std::fclose);
    if (!ef) throw UsageError("--out: cannot write " + eventsPath);
    std::fputs("t,substep,body,event,water_body,submerged_fraction\n", ef.get());
    EventCsvWriter events(ef.get(), scene, w);
    w.buoyancy->addEventListener(&events);
    struct RemoveListener {
        btBuoyancyWorld& world;
        btBuoyancyEventListener* listener;
        ~RemoveListener() { world.removeEventListener(listener); }
    } removeListener{*w.buoyancy, &events};

    const int n = scene.substepsPerFrame;
    const double frameTime = scene.dt * n;
    const long long frames = static_cast<long long>(std::ceil(duration / frameTime - 1e-9));
    std::vector<BodySummary> summary(w.bodies.size());
    std::string line;
    writeRows(f.get(), 0.0, scene, w, summary, line);
    if (png) png->frame(scene, w, 0.0);
    ProgressReporter progress("run " + std::filesystem::path(options.scene).filename().string(), frames * frameTime,
                              " s simulated", ProgressReporter::modeForStderr(options.quiet));
    double tLast = 0.0;
    long long nextOutput = 1;  // index k of the next multiple k·output_interval to report
    for (long long frame = 1; frame <= frames; ++frame) {
        stepSceneFrame(scene, w);
        const double t = frame * frameTime;
        // First frame boundary at or after each multiple of the output interval (tolerance for rounding).
        if (t >= nextOutput * scene.outputInterval - 1e-9 * frameTime) {
            writeRows(f.get(), t, scene, w, summary, line);
            tLast = t;
            if (png) png->frame(scene, w, t);
            while (nextOutput * scene.outputInterval <= t + 1e-9 * frameTime) ++nextOutput;
        }
        progress.update(t);
    }
    progress.finish();
    if (std::fflush(f.get()) != 0) throw UsageError("--out: error writing " + csvPath);
    if (std::fflush(ef.get()) != 0) throw UsageError("--out: error writing " + eventsPath);
    if (!options.quiet) {
        printSummary(scene, summary, tLast);
        std::printf("trajectory: %s\n", csvPath.c_str());
    }
    return kExitOk;
}

int runSceneCommand(const std::string& scenePath, const std::string& outDir, std::optional<double> duration) {
    RunOptions options;
    options.scene = scenePath;
    options.out = outDir;
    options.duration = duration;
    options.quiet = true;  // the in-process runner of the tests and example scenes: no progress or summary
    try {
        return runScene(options);
    } catch (const UsageError& e) {
        std::cerr << "error: " << e.what() << '\n';
        return kExitBadInput;
    } catch (const InternalError& e) {
        std::cerr << "internal error: " << e.what() << '\n';
        return kExitInternal;
    } catch (const std::exception& e) {
        std::cerr << "internal error: " << e.what() << '\n';
        return kExitInternal;
    }
}

}  // namespace buoyancy::cli
