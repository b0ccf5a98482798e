#include "render/SceneFrame.h"


#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace buoyancy::render {

namespace {

Eigen::Matrix4f toMatrix(const btTransform& t) {
    Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
    const btMatrix3x3& b = t.getBasis();
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) m(r, c) = float(b[r][c]);
        m(r, 3) = float(t.getOrigin()[r]);
    }
    return m;
}

Eigen::Vector3f toVec(const btVector3& v) { return Eigen::Vector3f(float(v.x()), float(v.y()), float(v.z())); }

/// The scene's water frame (the identity without a buoyancy context). A frame is drawn in its coordinates: the
/// renderer's y is the frame's up, so the camera orbits about up and the water is a height field in y, whatever
/// the scene's gravity (a +y-up scene: the world's coordinates exactly).
const btWaterFrame& waterFrameOf(const cli::SceneWorld& world) {
    static const btWaterFrame identity;
    return world.buoyancy ? world.buoyancy->getWaterFrame() : identity;
}

/// World → water coordinates as a Bullet transform.
btTransform worldToWater(const btWaterFrame& f) { return f.isIdentity() ? btTransform::getIdentity() : f.getTransform().inverse(); }

Eigen::Vector3f waterVector(const btWaterFrame& f, const btVector3& v) {
    return f.toWaterVector(Eigen::Vector3d(double(v.x()), double(v.y()), double(v.z()))).cast<float>();
}

Eigen::Vector3f waterPoint(const btWaterFrame& f, const btVector3& p) {
    return f.toWaterPoint(Eigen::Vector3d(double(p.x()), double(p.y()), double(p.z()))).cast<float>();
}

/// Width / height of the pictures the automatic framing is made for (`buoyancy run --png`'s 16:9 sizes).
constexpr double kPictureAspect = 16.0 / 9.0;

/// The smallest eye–target distance at which every point, seen by `cam` (its target, yaw, pitch and vertical field
/// of view), lies within kFillFraction of the picture's half-width and half-height from its centre, for a picture
/// of width / height `aspect`; at least a tenth of the points' spread, so the eye stays outside them.
double framingDistance(const RenderCamera& cam, const std::vector<Eigen::Vector3d>& points, double aspect) {
    constexpr double kFillFraction = 0.6;
    RenderCamera unit = cam;
    unit.distance = 1.f;
    const Eigen::Vector3d back = (unit.eye() - unit.target).cast<double>();  // unit vector, target → eye
    const Eigen::Vector3d right = Eigen::Vector3d::UnitY().cross(back).normalized();
    const Eigen::Vector3d up = back.cross(right);
    const double tanY = kFillFraction * std::tan(0.5 * double(cam.fovDeg) * M_PI / 180.0), tanX = tanY * aspect;
    const Eigen::Vector3d target = cam.target.cast<double>();
    double d = 0, spread = 0;
    for (const Eigen::Vector3d& p : points) {
        const Eigen::Vector3d q = p - target;
        spread = std::max(spread, q.norm());
        // A point at depth (d − q·back) in front of the eye needs |q·right| ≤ tanX·depth and |q·up| ≤ tanY·depth.
        d = std::max(d, q.dot(back) + std::max(std::abs(q.dot(right)) / tanX, std::abs(q.dot(up)) / tanY));
    }
    return std::max({d, 0.1 * spread, 0.05});
}

}  // namespace

Eigen::Vector3f bodyColour(std::size_t index) {
    static const float palette[][3] = {{0.90f, 0.55f, 0.20f}, {0.95f, 0.85f, 0.30f}, {0.80f, 0.30f, 0.30f},
                                       {0.60f, 0.45f, 0.80f}, {0.35f, 0.75f, 0.45f}, {0.90f, 0.60f, 0.70f},
                                       {0.55f, 0.40f, 0.25f}, {0.85f, 0.85f, 0.85f}};
    const float* c = palette[index % (sizeof palette / sizeof palette[0])];
    return Eigen::Vector3f(c[0], c[1], c[2]);
}

Eigen::Vector3f wetColourOf(const Eigen::Vector3f& dry) {
    // Darker and more saturated, the same hue: soaked paint, never the water's blue.
    const float grey = dry.mean();
    return (0.6f * (dry + 0.35f * (dry - Eigen::Vector3f::Constant(grey)))).cwiseMax(0.f).cwiseMin(1.f);
}

RenderCamera frameSceneCamera(const cli::Scene& scene, const cli::SceneWorld& world) {
    RenderCamera cam;
    const btWaterFrame& frame = waterFrameOf(world);
    const btTransform toWater = worldToWater(frame);
    // The bodies' vertices in water coordinates (at most about kMaxPoints of them: a fleet is sampled).
    constexpr std::size_t kMaxPoints = 20000;
    std::size_t total = 0;
    for (const auto& body : world.bodies) total += body->getShape()->getMesh().vertices.size();
    const std::size_t stride = std::max<std::size_t>(1, total / kMaxPoints);
    std::vector<Eigen::Vector3d> points;
    points.reserve(std::min(total, 2 * kMaxPoints));
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
    for (const auto& body : world.bodies) {
        const btTransform t = toWater * body->getMeshWorldTransform();
        const auto& vertices = body->getShape()->getMesh().vertices;
        for (std::size_t k = 0; k < vertices.size(); k += stride) {
            const btVector3 w = t(btVector3(btScalar(vertices[k].x()), btScalar(vertices[k].y()), btScalar(vertices[k].z())));
            const Eigen::Vector3d p(double(w.x()), double(w.y()), double(w.z()));
            points.push_back(p);
            lo = lo.cwiseMin(p);
            hi = hi.cwiseMax(p);
        }
    }
    if (points.empty()) {
        lo = hi = Eigen::Vector3d(0, scene.waterHeight, 0);
        points.push_back(lo);
    }
    const Eigen::Vector3d centre = 0.5 * (lo + hi);
    cam.target = centre.cast<float>();
    // Keep the waterline in view when the bodies are near it.
    const double radius = 0.5 * (hi - lo).norm();
    const double waterY = scene.waterHeight;
    if (std::abs(centre.y() - waterY) < radius + 0.5) cam.target.y() = float(0.5 * (centre.y() + waterY));
    cam.fovDeg = 40.f;
    // The scene's "camera" block overrides what it gives; a given yaw or pitch is used for the fit.
    if (scene.camera.yaw) cam.yawDeg = float(*scene.camera.yaw);
    if (scene.camera.pitch) cam.pitchDeg = float(*scene.camera.pitch);
    if (scene.camera.target) cam.target = frame.toWaterPoint(*scene.camera.target).cast<float>();
    cam.distance = float(framingDistance(cam, points, kPictureAspect));
    if (scene.camera.distance) cam.distance = float(*scene.camera.distance);
    return cam;
}

void buildSceneFrame(const cli::Scene& scene, const cli::SceneWorld& world, const SceneFrameOptions& options,
                     RenderFrame& out) {
    const double t = world.time();
    out.bodies.clear();
    out.arrows.clear();
    out.samples.positions.clear();
    out.samples.wet.clear();

    // Water grid: the interactive grid's own extent, or a square around the camera target.
    RenderWater& w = out.water;
    // A fluid lighter than 100 kg/m³ is air (the balloon): its "surface" is not drawn, nothing is wet.
    w.visible = world.water != nullptr && scene.waterDensity >= 100.0;
    if (w.visible) {
        const int n = std::max(2, options.waterResolution);
        double cx = out.camera.target.x(), cz = out.camera.target.z();
        double hx = options.waterExtent > 0 ? options.waterExtent : std::max(8.0, 2.0 * double(out.camera.distance));
        double hz = hx;
        if (scene.water.type == "interactive") {
            cx = scene.water.centre.x();
            cz = scene.water.centre.y();
            hx = 0.5 * scene.water.size.x();
            hz = 0.5 * scene.water.size.y();
        }
        w.nx = w.nz = n;
        w.x0 = float(cx - hx);
        w.z0 = float(cz - hz);
        w.dx = float(2 * hx / (n - 1));
        w.dz = float(2 * hz / (n - 1));
        std::vector<double> xs(std::size_t(n) * n), zs(xs.size()), hs(xs.size());
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                xs[std::size_t(j) * n + i] = double(w.x0) + i * double(w.dx);
                zs[std::size_t(j) * n + i] = double(w.z0) + j * double(w.dz);
            }
        world.water->heights(xs.data(), zs.data(), xs.size(), t, hs.data());
        w.heights.resize(hs.size());
        for (std::size_t k = 0; k < hs.size(); ++k) w.heights[k] = std::isfinite(hs[k]) ? float(hs[k]) : 0.f;
    }

    // Everything below in water coordinates (waterFrameOf): n·p = d becomes (Rᵀn)·q = d − n·o.
    const btWaterFrame& frame = waterFrameOf(world);
    const btTransform toWater = worldToWater(frame);
    out.ground.visible = world.ground != nullptr;
    out.ground.normal = frame.toWaterVector(world.groundNormal).cast<float>();
    out.ground.offset = float(world.groundOffset - world.groundNormal.dot(frame.origin()));

    const bool arrows = options.arrows && int(world.bodies.size()) <= options.maxArrowBodies;
    const double g = scene.gravity.norm();
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
        const btBuoyantBody& body = *world.bodies[i];
        const btTransform meshWorld = toWater * body.getMeshWorldTransform();  // mesh → water coordinates
        RenderBody rb;
        rb.mesh = &body.getShape()->getMesh();
        rb.meshToWorld = toMatrix(meshWorld);
        rb.colour = bodyColour(i);
        rb.wetColour = wetColourOf(rb.colour);
        if (i < scene.bodies.size() && scene.bodies[i].shape.type == "sphere") {  // a ball's rotation shows
            rb.twoTonePattern = true;
            rb.patternCentre = body.getShape()->getBoundsCentre().cast<float>();
        }
        out.bodies.push_back(rb);

        const btBuoyancyAction* action = i < world.actions.size() ? world.actions[i].get() : nullptr;
        if (arrows && action) {
            const double weight = body.getMass() * g;
            if (weight > 0) {
                const double perNewton = options.arrowScale * body.getShape()->getBoundsRadius() / weight;
                const Eigen::Vector3f com = waterPoint(frame, body.getRigidBody()->getCenterOfMassPosition());
                const btBuoyancyResult& r = action->getLastResult();
                out.arrows.push_back({com, Eigen::Vector3f(0.f, float(-weight * perNewton), 0.f),
                                      Eigen::Vector3f(0.9f, 0.1f, 0.1f)});
                if (r.submergedVolume > 0)
                    out.arrows.push_back({waterPoint(frame, r.centreOfBuoyancy),
                                          waterVector(frame, r.buoyancyForce) * float(perNewton),
                                          Eigen::Vector3f(0.1f, 0.8f, 0.2f)});
                if (double(r.dragForce.length()) > 0.01 * weight)
                    out.arrows.push_back({com, waterVector(frame, r.dragForce) * float(perNewton),
                                          Eigen::Vector3f(0.15f, 0.3f, 0.95f)});
            }
        }

        if (options.samples && world.water) {
            const buoyancy::SurfaceSamples& s = body.getShape()->getDragSamples();
            std::vector<double> xs(s.size()), zs(s.size()), hs(s.size());
            const std::size_t first = out.samples.positions.size();
            for (std::size_t k = 0; k < s.size(); ++k) {
                const btVector3 p = meshWorld(btVector3(btScalar(s.px[k]), btScalar(s.py[k]), btScalar(s.pz[k])));
                out.samples.positions.push_back(toVec(p));
                xs[k] = double(p.x());
                zs[k] = double(p.z());
            }
            world.water->heights(xs.data(), zs.data(), xs.size(), t, hs.data());
            for (std::size_t k = 0; k < s.size(); ++k)  // wet: the sample lies below the water height
                out.samples.wet.push_back(out.samples.positions[first + k].y() < hs[k] ? 1 : 0);
        }
    }
}

}  // namespace buoyancy::render
