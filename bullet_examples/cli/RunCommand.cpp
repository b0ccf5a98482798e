#include "cli/RunCommand.h"

#include "cli/CliErrors.h"
#include "cli/SceneFile.h"
#include "cli/SceneWorld.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <vector>

namespace buoyancy::cli {

void addRunCommand(CLI::App& app, RunOptions& options) {
    CLI::App* run = app.add_subcommand("run", "Run a scene file headless and write DIR/trajectory.csv");
    run->add_option("scene", options.scene, "Scene JSON file (docs/scene-format.md)")->required();
    run->add_option("--out", options.out, "Output folder (created when missing)")->required();
    run->add_option("--duration", options.duration, "Override the scene's duration, s")->check(CLI::NonNegativeNumber);
    run->add_option("--import-timeout", options.import_timeout, "Time limit of each mesh import, s")
        ->check(CLI::PositiveNumber);
    run->add_option("--png", options.png, "Also render a PNG per output interval into this folder (offscreen)");
    run->add_option("--size", options.size, "Picture size W H in pixels (with --png; default 960 540)")
        ->expected(2);
}

namespace {

void writeRows(std::FILE* f, double t, const Scene& scene, SceneWorld& w) {
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
        std::fprintf(f, "%.17g,%s", t, scene.bodies[i].name.c_str());
        for (double x : values) std::fprintf(f, ",%.17g", x);
        std::fputc('\n', f);
    }
}

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
    // Issue 9: say which level of detail each floating body uses (method, texture; the error budget's pick).
    for (std::size_t i = 0; i < w.actions.size() && i < scene.bodies.size(); ++i)
        if (w.actions[i]) {
            const auto& shape = w.actions[i]->getShape();
            std::cerr << "body " << scene.bodies[i].name << ": level of detail "
                      << btBuoyancyPickLevelOfDetail(scene.bodies[i].buoyancy, shape->getMesh().triangleCount()).description
                      << ", drag on " << w.actions[i]->getDragClusters().size() << " clusters\n";
        }
    std::unique_ptr<SceneFrameSink> png;
    if (!options.png.empty()) png = options.pngSink(options, scene);

    std::error_code ec;
    std::filesystem::create_directories(options.out, ec);
    const std::string csvPath = (std::filesystem::path(options.out) / "trajectory.csv").string();
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(csvPath.c_str(), "w"), &std::fclose);
    if (!f) throw UsageError("--out: cannot write " + csvPath);
    std::fputs("t,body,x,y,z,qx,qy,qz,qw,cx,cy,cz,vx,vy,vz,wx,wy,wz,submerged_volume,mass,water_volume,"
               "fbx,fby,fbz,fdx,fdy,fdz,cbx,cby,cbz\n",
               f.get());

    const int n = scene.substepsPerFrame;
    const double frameTime = scene.dt * n;
    const long long frames = static_cast<long long>(std::ceil(duration / frameTime - 1e-9));
    writeRows(f.get(), 0.0, scene, w);
    if (png) png->frame(scene, w, 0.0);
    long long nextOutput = 1;  // index k of the next multiple k·output_interval to report
    for (long long frame = 1; frame <= frames; ++frame) {
        stepSceneFrame(scene, w);
        const double t = frame * frameTime;
        // First frame boundary at or after each multiple of the output interval (tolerance for rounding).
        if (t >= nextOutput * scene.outputInterval - 1e-9 * frameTime) {
            writeRows(f.get(), t, scene, w);
            if (png) png->frame(scene, w, t);
            while (nextOutput * scene.outputInterval <= t + 1e-9 * frameTime) ++nextOutput;
        }
    }
    if (std::fflush(f.get()) != 0) throw UsageError("--out: error writing " + csvPath);
    return kExitOk;
}

int runSceneCommand(const std::string& scenePath, const std::string& outDir, std::optional<double> duration) {
    RunOptions options;
    options.scene = scenePath;
    options.out = outDir;
    options.duration = duration;
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
