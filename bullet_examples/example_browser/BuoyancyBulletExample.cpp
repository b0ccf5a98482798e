#include "BuoyancyBulletExample.h"
#include "BuoyancyExamples.h"

#include "example_scenes/ExampleEntries.h"
#include "example_scenes/SceneFileExample.h"
#include "render/SceneFrame.h"

#include "CommonInterfaces/CommonCameraInterface.h"
#include "OpenGLWindow/OpenGLInclude.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

using buoyancy::examples::ExampleOptions;
using buoyancy::examples::ExampleScene;
using buoyancy::examples::SceneFileExample;

namespace {

/// Floats per GLInstanceVertex (Bullet's OpenGLWindow/GLInstanceGraphicsShape.h): xyzw, normal, uv.
constexpr int kVertexFloats = 9;

/// The scene's water frame (identity without a buoyancy world).
const btWaterFrame& waterFrameOf(const buoyancy::cli::SceneWorld& world) {
    static const btWaterFrame identity;
    return world.buoyancy ? world.buoyancy->getWaterFrame() : identity;
}

/// A point of a RenderFrame (water coordinates, SceneFrame.h) in world coordinates.
btVector3 toWorld(const btWaterFrame& frame, const Eigen::Vector3f& q) {
    const Eigen::Vector3d p = frame.toWorldPoint(q.cast<double>());
    return btVector3(btScalar(p.x()), btScalar(p.y()), btScalar(p.z()));
}

void putVertex(std::vector<float>& out, const btVector3& p, const btVector3& n) {
    const float v[kVertexFloats] = {float(p.x()), float(p.y()), float(p.z()), 1.f, float(n.x()), float(n.y()),
                                    float(n.z()), 0.5f, 0.5f};
    out.insert(out.end(), v, v + kVertexFloats);
}

/// Flat-shaded vertices of `mesh` (three per triangle, the face normal), placed by `meshToBody`.
std::vector<float> flatVertices(const buoyancy::TriangleMesh& mesh, const btTransform& meshToBody) {
    std::vector<float> out;
    out.reserve(mesh.triangles.size() * 3 * kVertexFloats);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        btVector3 c[3];
        for (int k = 0; k < 3; ++k) {
            const Eigen::Vector3d& p = mesh.corner(t, k);
            c[k] = meshToBody(btVector3(btScalar(p.x()), btScalar(p.y()), btScalar(p.z())));
        }
        btVector3 n = (c[1] - c[0]).cross(c[2] - c[0]);
        n = n.length2() > btScalar(0) ? n.normalized() : btVector3(0, 1, 0);
        for (int k = 0; k < 3; ++k) putVertex(out, c[k], n);
    }
    return out;
}

/// Environment variable as a number (0 when unset).
long envNumber(const char* name) {
    const char* v = std::getenv(name);
    return v && *v ? std::strtol(v, nullptr, 10) : 0;
}

}  // namespace

BuoyancyBulletExample::BuoyancyBulletExample(CommonExampleOptions& options, ExampleScene::CreateFunc createScene)
    : CommonRigidBodyBase(options.m_guiHelper) {
    m_sceneOptions.guiHelper = nullptr;  // we draw with Bullet's GUI helper, not our renderer
    m_sceneOptions.option = options.m_option;
    try {
        ExampleScene* scene = createScene(m_sceneOptions);
        m_scene.reset(dynamic_cast<SceneFileExample*>(scene));
        if (!m_scene) delete scene;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "Buoyancy example: %s\n", e.what());
    }
}

BuoyancyBulletExample::~BuoyancyBulletExample() { exitPhysics(); }

void BuoyancyBulletExample::initPhysics() {
    if (!m_scene) return;
    try {
        m_scene->initPhysics();
    } catch (const std::exception& e) {
        std::fprintf(stderr, "Buoyancy example: %s\n", e.what());
        return;
    }
    buoyancy::cli::SceneWorld* world = m_scene->world();
    if (!world) return;
    m_dynamicsWorld = &world->world;  // owned by the scene: exitPhysics() must not delete it

    // Bullet's camera and grid know y-up and z-up: take the world axis nearest to the water frame's up.
    const Eigen::Vector3d up = waterFrameOf(*world).up();
    m_upAxis = std::abs(up.z()) > std::abs(up.y()) ? 2 : 1;
    m_guiHelper->setUpAxis(m_upAxis);
    m_guiHelper->createPhysicsDebugDrawer(m_dynamicsWorld);

    m_scene->frameOptions().waterResolution = 48;  // the water mesh: 48 x 48 vertices, re-uploaded every frame
    m_scene->renderScene();                        // builds the frame (no renderer of ours: guiHelper is null)
    createBodyGraphics();
    createWaterGraphics();
    resetCamera();
}

void BuoyancyBulletExample::createBodyGraphics() {
    buoyancy::cli::SceneWorld& world = *m_scene->world();
    const buoyancy::render::RenderFrame& frame = m_scene->frame();
    m_bodyShapes.assign(world.bodies.size(), -1);
    m_bodyMeshVersions.assign(world.bodies.size(), 0);
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
        const btBuoyantBody& body = *world.bodies[i];
        btRigidBody* rb = body.getRigidBody();
        const buoyancy::TriangleMesh& mesh =
            i < frame.bodies.size() && frame.bodies[i].mesh ? *frame.bodies[i].mesh : body.getShape()->getMesh();
        // Vertices in the rigid body's frame: syncPhysicsToGraphics then places them by the body's transform.
        const btTransform meshToBody = rb->getWorldTransform().inverse() * body.getMeshWorldTransform();
        const std::vector<float> v = flatVertices(mesh, meshToBody);
        std::vector<int> indices(v.size() / kVertexFloats);
        for (std::size_t k = 0; k < indices.size(); ++k) indices[k] = int(k);
        const int shape = m_guiHelper->registerGraphicsShape(v.data(), int(indices.size()), indices.data(),
                                                             int(indices.size()), B3_GL_TRIANGLES, -1);
        const Eigen::Vector3f c = buoyancy::render::bodyColour(i);
        const float colour[4] = {c.x(), c.y(), c.z(), 1.f};
        const btTransform& t = rb->getWorldTransform();
        const btVector3 o = t.getOrigin();
        const btQuaternion q = t.getRotation();
        const float pos[4] = {float(o.x()), float(o.y()), float(o.z()), 1.f};
        const float orn[4] = {float(q.x()), float(q.y()), float(q.z()), float(q.w())};
        const float scaling[4] = {1.f, 1.f, 1.f, 1.f};
        rb->setUserIndex(m_guiHelper->registerGraphicsInstance(shape, pos, orn, colour, scaling));
        m_bodyShapes[i] = shape;
        if (i < frame.bodies.size()) m_bodyMeshVersions[i] = frame.bodies[i].meshVersion;
    }
    if (world.ground) {  // Bullet's own plane graphics (a checkered floor)
        m_guiHelper->createCollisionShapeGraphicsObject(world.ground->getCollisionShape());
        m_guiHelper->createCollisionObjectGraphicsObject(world.ground.get(), btVector3(0.8f, 0.75f, 0.6f));
    }
}

void BuoyancyBulletExample::createWaterGraphics() {
    m_waterShape = -1;
    const buoyancy::render::RenderWater& w = m_scene->frame().water;
    if (!w.visible || w.nx < 2 || w.nz < 2) return;
    m_waterVertices.assign(std::size_t(w.nx) * w.nz * kVertexFloats, 0.f);
    std::vector<int> indices;
    indices.reserve(std::size_t(w.nx - 1) * (w.nz - 1) * 12);
    for (int j = 0; j + 1 < w.nz; ++j)
        for (int i = 0; i + 1 < w.nx; ++i) {
            const int a = j * w.nx + i, b = a + 1, c = a + w.nx, d = c + 1;
            const int quad[12] = {a, c, b, b, c, d, a, b, c, b, d, c};  // both windings: seen from above and below
            indices.insert(indices.end(), quad, quad + 12);
        }
    updateWaterGraphics();
    m_waterShape = m_guiHelper->registerGraphicsShape(m_waterVertices.data(), w.nx * w.nz, indices.data(),
                                                      int(indices.size()), B3_GL_TRIANGLES, -1);
    const Eigen::Vector3f& c = w.colour;
    const float colour[4] = {c.x(), c.y(), c.z(), 0.6f};  // alpha < 1: Bullet draws it in its transparent pass
    const float pos[4] = {0, 0, 0, 1}, orn[4] = {0, 0, 0, 1}, scaling[4] = {1, 1, 1, 1};
    m_guiHelper->registerGraphicsInstance(m_waterShape, pos, orn, colour, scaling);
}

void BuoyancyBulletExample::updateWaterGraphics() {
    const buoyancy::render::RenderWater& w = m_scene->frame().water;
    if (m_waterVertices.size() != std::size_t(w.nx) * w.nz * kVertexFloats) return;
    const btWaterFrame& frame = waterFrameOf(*m_scene->world());
    auto height = [&](int i, int j) {
        return w.heights[std::size_t(std::clamp(j, 0, w.nz - 1)) * w.nx + std::size_t(std::clamp(i, 0, w.nx - 1))];
    };
    for (int j = 0; j < w.nz; ++j)
        for (int i = 0; i < w.nx; ++i) {
            const Eigen::Vector3f q(w.x0 + i * w.dx, height(i, j), w.z0 + j * w.dz);
            // Normal from central differences of the height field, in water coordinates, then to world.
            const Eigen::Vector3f nq = Eigen::Vector3f(-(height(i + 1, j) - height(i - 1, j)) / (2 * w.dx), 1.f,
                                                       -(height(i, j + 1) - height(i, j - 1)) / (2 * w.dz))
                                           .normalized();
            const Eigen::Vector3d n = frame.toWorldVector(nq.cast<double>());
            const btVector3 p = toWorld(frame, q);
            float* v = &m_waterVertices[(std::size_t(j) * w.nx + i) * kVertexFloats];
            v[0] = float(p.x());
            v[1] = float(p.y());
            v[2] = float(p.z());
            v[3] = 1.f;
            v[4] = float(n.x());
            v[5] = float(n.y());
            v[6] = float(n.z());
            v[7] = float(i) / float(w.nx - 1);
            v[8] = float(j) / float(w.nz - 1);
        }
}

void BuoyancyBulletExample::updateDeformedBodies() {
    buoyancy::cli::SceneWorld& world = *m_scene->world();
    const buoyancy::render::RenderFrame& frame = m_scene->frame();
    for (std::size_t i = 0; i < frame.bodies.size() && i < m_bodyShapes.size(); ++i) {
        const buoyancy::render::RenderBody& b = frame.bodies[i];
        if (m_bodyShapes[i] < 0 || !b.mesh || b.meshVersion == m_bodyMeshVersions[i]) continue;
        const btBuoyantBody& body = *world.bodies[i];
        const btTransform meshToBody = body.getRigidBody()->getWorldTransform().inverse() * body.getMeshWorldTransform();
        std::vector<float> v = flatVertices(*b.mesh, meshToBody);
        m_guiHelper->updateShape(m_bodyShapes[i], v.data(), int(v.size() / kVertexFloats));
        m_bodyMeshVersions[i] = b.meshVersion;
    }
}

void BuoyancyBulletExample::exitPhysics() {
    removePickingConstraint();
    if (m_dynamicsWorld) m_dynamicsWorld->setDebugDrawer(nullptr);
    m_dynamicsWorld = nullptr;  // the scene owns the world: not CommonRigidBodyBase::exitPhysics()
    m_waterShape = -1;
    m_bodyShapes.clear();
    m_bodyMeshVersions.clear();
    if (m_scene) m_scene->exitPhysics();
}

void BuoyancyBulletExample::stepSimulation(float deltaTime) {
    if (!m_dynamicsWorld) return;
    frameLoopHook();
    m_scene->stepSimulation(deltaTime);
}

void BuoyancyBulletExample::renderScene() {
    if (!m_dynamicsWorld) return;
    m_scene->renderScene();  // the frame: water heights, deformed meshes, arrows
    updateDeformedBodies();
    if (m_waterShape >= 0) {
        updateWaterGraphics();
        m_guiHelper->updateShape(m_waterShape, m_waterVertices.data(), int(m_waterVertices.size() / kVertexFloats));
    }
    CommonRigidBodyBase::renderScene();  // syncPhysicsToGraphics + render
    drawArrows();
    ++m_frames;
}

void BuoyancyBulletExample::drawArrows() {
    btIDebugDraw* draw = m_dynamicsWorld->getDebugDrawer();
    if (!draw) return;
    const btWaterFrame& frame = waterFrameOf(*m_scene->world());
    for (const buoyancy::render::RenderArrow& a : m_scene->frame().arrows) {
        const btVector3 from = toWorld(frame, a.origin), to = toWorld(frame, a.origin + a.vector);
        const btVector3 colour(a.colour.x(), a.colour.y(), a.colour.z());
        draw->drawLine(from, to, colour);
        const btVector3 d = to - from;
        const btScalar len = d.length();
        if (len < btScalar(1e-6)) continue;
        // Arrow head: two strokes back from the tip, in a plane holding the arrow.
        const btVector3 u = d / len;
        btVector3 side = u.cross(btVector3(0, 0, 1));
        if (side.length2() < btScalar(1e-6)) side = u.cross(btVector3(1, 0, 0));
        side.normalize();
        const btScalar h = std::min(btScalar(0.25) * len, btScalar(0.3));
        draw->drawLine(to, to - h * u + 0.5f * h * side, colour);
        draw->drawLine(to, to - h * u - 0.5f * h * side, colour);
    }
    draw->flushLines();
}

void BuoyancyBulletExample::physicsDebugDraw(int debugFlags) {
    CommonRigidBodyBase::physicsDebugDraw(debugFlags);
    drawArrows();
}

void BuoyancyBulletExample::resetCamera() {
    if (!m_scene || !m_scene->world()) return;
    m_scene->resetCamera();
    const buoyancy::render::RenderCamera& cam = m_scene->frame().camera;
    const btWaterFrame& frame = waterFrameOf(*m_scene->world());
    const btVector3 target = toWorld(frame, cam.target);
    btVector3 u = toWorld(frame, cam.eye()) - target;
    u = u.length2() > btScalar(0) ? u.normalized() : btVector3(0, 1, 1).normalized();
    // Bullet's SimpleCamera: with y up the eye sits at yaw/pitch Ry(yaw)·Rx(-pitch)·(0, 0, -d), with z up at
    // Rz(yaw)·Rx(pitch)·(0, -d, 0) (examples/OpenGLWindow/SimpleCamera.cpp); invert both for the eye direction u.
    const double deg = 180.0 / M_PI;
    float yaw, pitch;
    if (m_upAxis == 2) {
        pitch = float(-std::asin(std::clamp(double(u.z()), -1.0, 1.0)) * deg);
        yaw = float(std::atan2(double(u.x()), double(-u.y())) * deg);
    } else {
        pitch = float(-std::asin(std::clamp(double(u.y()), -1.0, 1.0)) * deg);
        yaw = float(std::atan2(double(-u.x()), double(-u.z())) * deg);
    }
    m_guiHelper->resetCamera(cam.distance, yaw, pitch, float(target.x()), float(target.y()), float(target.z()));
}

/// Unattended runs (the CTest test, the documentation's picture): BUOYANCY_EXAMPLE_FRAMES=N quits the browser after
/// N frames of this example; BUOYANCY_EXAMPLE_PNG=FILE also writes the window of the last frame to FILE (Bullet's own
/// frame dump, as its F1 key does).
void BuoyancyBulletExample::frameLoopHook() {
    static const long frames = envNumber("BUOYANCY_EXAMPLE_FRAMES");
    static const std::string png = std::getenv("BUOYANCY_EXAMPLE_PNG") ? std::getenv("BUOYANCY_EXAMPLE_PNG") : "";
    if (frames <= 0) return;
    CommonGraphicsApp* app = m_guiHelper->getAppInterface();
    if (m_frames == frames - 1 && !png.empty() && app) {
        app->dumpNextFrameToPng(png.c_str());  // renders this frame into a texture, written at the buffer swap
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    if (m_frames >= frames) {
        const buoyancy::cli::SceneWorld& world = *m_scene->world();
        double sumY = 0;
        bool finite = true;
        for (const auto& b : world.bodies) {
            const btVector3 p = b->getRigidBody()->getCenterOfMassPosition();
            finite = finite && std::isfinite(double(p.x())) && std::isfinite(double(p.y())) && std::isfinite(double(p.z()));
            sumY += double(p.dot(btVector3(btScalar(waterFrameOf(world).up().x()), btScalar(waterFrameOf(world).up().y()),
                                           btScalar(waterFrameOf(world).up().z()))));
        }
        std::printf("Buoyancy example: %ld frames, %.3f s simulated, %zu bodies, mean height %.4f m, %s\n", m_frames,
                    m_scene->time(), world.bodies.size(), world.bodies.empty() ? 0.0 : sumY / double(world.bodies.size()),
                    finite ? "all finite" : "NOT FINITE");
        std::fflush(stdout);
        if (app && app->m_window) app->m_window->setRequestExit();
    }
}

// ---- Create functions: one per scene of our table ------------------------------------------------------------------

const char* BuoyancyExampleDescription(const char* name) {
    const buoyancy::examples::ExampleEntry* e = buoyancy::examples::findExampleEntry(name);
    return e && e->description ? e->description : "";
}

namespace {
template <ExampleScene::CreateFunc F>
CommonExampleInterface* makeBuoyancyExample(CommonExampleOptions& options) {
    return new BuoyancyBulletExample(options, F);
}
}  // namespace

namespace ex = buoyancy::examples;
CommonExampleInterface* BuoyancyBuoyInWavesCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::BuoyInWavesCreateFunc>(o); }
CommonExampleInterface* BuoyancyBoatHoledBowCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::BoatHoledBowCreateFunc>(o); }
CommonExampleInterface* BuoyancyBoatHoledSternCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::BoatHoledSternCreateFunc>(o); }
CommonExampleInterface* BuoyancyBallStabilityCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::BallStabilityCreateFunc>(o); }
CommonExampleInterface* BuoyancyVariableDensityBallCreateFunc(CommonExampleOptions& o) {
    return makeBuoyancyExample<ex::VariableDensityBallCreateFunc>(o);
}
CommonExampleInterface* BuoyancyPlushToyCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::PlushToyCreateFunc>(o); }
CommonExampleInterface* BuoyancyBalloonCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::BalloonCreateFunc>(o); }
CommonExampleInterface* BuoyancyFftFleetCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::FftFleetCreateFunc>(o); }
CommonExampleInterface* BuoyancyBeachBoatCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::BeachBoatCreateFunc>(o); }
CommonExampleInterface* BuoyancyCrateSplashCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::CrateSplashCreateFunc>(o); }
CommonExampleInterface* BuoyancyGerstnerDemoCreateFunc(CommonExampleOptions& o) { return makeBuoyancyExample<ex::GerstnerDemoCreateFunc>(o); }
