// The pictures and the browser follow the up axis: a frame of a Z-up or oblique scene (render/SceneFrame.cpp) is
// drawn in the water frame's coordinates, so it equals the frame of the same scene built Y-up (the oracle), body
// poses, water heights, force arrows, ground plane and camera alike. Headless (no OpenGL context).
#include "render/SceneFrame.h"
#include "scene/SceneFile.h"
#include "scene/SceneWorld.h"

#include <catch2/catch.hpp>

#include <Eigen/Geometry>
#include <sstream>
#include <string>

using namespace buoyancy;

namespace {

std::string vec(const Eigen::Vector3d& v) {
    std::ostringstream s;
    s.precision(17);
    s << "[" << v.x() << ", " << v.y() << ", " << v.z() << "]";
    return s.str();
}

/// A box heeled 10° in Gerstner waves over a ground plane, a camera target given, all mapped by the rotation Q.
cli::Scene mappedScene(const Eigen::Matrix3d& Q, bool frame) {
    const Eigen::AngleAxisd r(Q * Eigen::AngleAxisd(10 * M_PI / 180, Eigen::Vector3d::UnitX()).toRotationMatrix());
    std::ostringstream s;
    s.precision(17);
    s << R"({"gravity": )" << vec(Q * Eigen::Vector3d(0, -9.81, 0))
      << R"(, "water": {"type": "gerstner", "waves": [{"amplitude": 0.2, "wavelength": 8, "direction": [0.6, 0.8]}])";
    if (frame) s << R"(, "frame": {"up": )" << vec(Q.col(1)) << R"(, "x": )" << vec(Q.col(0)) << "}";
    s << R"(}, "ground": {"height": -3}, "camera": {"target": )" << vec(Q * Eigen::Vector3d(0.5, 0, 0.25))
      << R"(, "distance": 6}, "bodies": [{"shape": {"type": "box", "size": [1, 0.5, 0.8]}, "density": 500,)"
      << R"( "position": )" << vec(Q * Eigen::Vector3d(0.3, 0.1, -0.2)) << R"(, "rotation": {"axis": )" << vec(r.axis())
      << R"(, "degrees": )" << r.angle() * 180 / M_PI << "}}]}";
    return cli::parseScene(s.str(), "s.json", ".");
}

/// Largest difference between two frames' contents (m, or the unit of the compared field).
double difference(const render::RenderFrame& a, const render::RenderFrame& b) {
    double d = double((a.camera.target - b.camera.target).norm());
    REQUIRE(a.bodies.size() == b.bodies.size());
    for (std::size_t i = 0; i < a.bodies.size(); ++i) d = std::max(d, double((a.bodies[i].meshToWorld - b.bodies[i].meshToWorld).cwiseAbs().maxCoeff()));
    REQUIRE(a.arrows.size() == b.arrows.size());
    for (std::size_t i = 0; i < a.arrows.size(); ++i) {
        d = std::max(d, double((a.arrows[i].origin - b.arrows[i].origin).norm()));
        d = std::max(d, double((a.arrows[i].vector - b.arrows[i].vector).norm()));
    }
    REQUIRE(a.water.heights.size() == b.water.heights.size());
    for (std::size_t k = 0; k < a.water.heights.size(); ++k) d = std::max(d, double(std::abs(a.water.heights[k] - b.water.heights[k])));
    d = std::max(d, double(std::abs(a.water.x0 - b.water.x0) + std::abs(a.water.z0 - b.water.z0)));
    d = std::max(d, double((a.ground.normal - b.ground.normal).norm() + std::abs(a.ground.offset - b.ground.offset)));
    return d;
}

render::RenderFrame frameAfter(const cli::Scene& scene, double seconds) {
    auto world = cli::buildSceneWorld(scene, 10.0);
    render::SceneFrameOptions options;
    options.waterResolution = 24;
    render::RenderFrame f;
    f.camera = render::frameSceneCamera(scene, *world);
    while (world->time() < seconds - 1e-9) cli::stepSceneFrame(scene, *world);
    render::buildSceneFrame(scene, *world, options, f);
    return f;
}

}  // namespace

TEST_CASE("scene frames of a Z-up and an oblique scene equal the Y-up scene's frame (renderer follows up)", "[examples]") {
    const render::RenderFrame yUp = frameAfter(mappedScene(Eigen::Matrix3d::Identity(), false), 0.5);
    REQUIRE(yUp.bodies.size() == 1);
    CHECK(yUp.ground.normal.isApprox(Eigen::Vector3f::UnitY()));
    Eigen::Matrix3d zUp;
    zUp << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // gravity −z: the default frame (x, up z, −y)
    const Eigen::Matrix3d oblique = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, -2, 2).normalized()).toRotationMatrix();
    // Float frames (RenderFrame holds floats) and 0.5 s of physics that differ by rounding only: 1e-4.
    CHECK(difference(yUp, frameAfter(mappedScene(zUp, false), 0.5)) < 1e-4);
    CHECK(difference(yUp, frameAfter(mappedScene(oblique, true), 0.5)) < 1e-4);
}
