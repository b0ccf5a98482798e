#include "render/SceneRenderer.h"

#include "render/GlApi.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

namespace buoyancy::render {

namespace {

// One program for everything; uMode picks body (wet/dry), plain, ground (sea bed), water, arrow or deep-water plane.
const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 aPos;
uniform mat4 uModel;
uniform mat4 uViewProj;
uniform float uPointSize;
out vec3 vWorld;
out vec3 vLocal;
void main() {
    vec4 w = uModel * vec4(aPos, 1.0);
    vWorld = w.xyz;
    vLocal = aPos;
    gl_Position = uViewProj * w;
    gl_PointSize = uPointSize;
}
)";

const char* kFragmentShader = R"(#version 330 core
in vec3 vWorld;
in vec3 vLocal;
out vec4 oColour;
uniform vec3 uColour;
uniform vec3 uWetColour;
uniform float uAlpha;
uniform float uAlphaFacing;   // water: opacity looking straight down (uAlpha: at a grazing angle)
uniform int uMode;            // 0 body, 1 plain (unlit), 2 ground, 3 water, 4 arrow (lit, no wet test), 5 deep plane
uniform int uHasWater;
uniform int uWaterline;       // 1: a light line where a body cuts the surface
uniform int uTwoTone;         // 1: paint the body's lower half (mesh frame) white
uniform vec3 uPatternCentre;  // mesh frame
uniform sampler2D uHeights;   // water heights, texel (i, j) = sample (i, j) of the grid
uniform vec4 uWaterGrid;      // x0, z0, dx, dz
uniform vec2 uWaterSize;      // nx, nz
uniform float uWaterMean;
uniform float uCrest;         // 1 / the frame's largest wave height over the mean, 1/m (0: flat water, no crest shading)
uniform float uCrestAmount;   // crest shading at the largest crest, 0..1
uniform vec3 uDeepColour;
uniform float uFogDepth;      // m
uniform vec3 uLightDir;
uniform vec3 uEye;

float waterHeight(vec2 xz) {
    vec2 g = (xz - uWaterGrid.xy) / uWaterGrid.zw;
    vec2 uv = (g + 0.5) / uWaterSize;
    return (g.x >= 0.0 && g.y >= 0.0 && g.x <= uWaterSize.x - 1.0 && g.y <= uWaterSize.y - 1.0)
               ? texture(uHeights, uv).r : uWaterMean;
}

void main() {
    if (uMode == 1) { oColour = vec4(uColour, uAlpha); return; }
    vec3 n = normalize(cross(dFdx(vWorld), dFdy(vWorld)));
    vec3 toEye = normalize(uEye - vWorld);
    if (dot(n, toEye) < 0.0) n = -n;
    float diffuse = max(dot(n, uLightDir), 0.0);
    vec3 base = uColour;
    float depth = 0.0;  // below the water surface, m
    bool onWaterline = false;
    if ((uMode == 0 || uMode == 2) && uHasWater == 1) {
        // Wet when below the water height at this x, z (the rule of the samples, per pixel).
        float below = waterHeight(vWorld.xz) - vWorld.y;
        if (uMode == 0) {
            if (below > 0.0) base = uWetColour;
            if (uTwoTone == 1 && vLocal.y < uPatternCentre.y) base = mix(base, vec3(0.97), below > 0.0 ? 0.5 : 0.85);
            // The waterline: within about 1.5 pixels of the surface height.
            float perPixel = max(fwidth(below), 1e-6);
            onWaterline = uWaterline == 1 && abs(below) < 1.5 * perPixel;
        }
        depth = max(below, 0.0);
    }
    if (onWaterline) { oColour = vec4(0.97, 0.97, 0.93, 1.0); return; }
    vec3 colour = base * (0.38 + 0.62 * diffuse);
    if (uMode == 5) colour = uDeepColour;
    if ((uMode == 0 || uMode == 2) && depth > 0.0) colour = mix(colour, uDeepColour, 1.0 - exp(-depth / uFogDepth));
    float alpha = uAlpha;
    if (uMode == 3) {
        vec3 h = normalize(uLightDir + toEye);
        colour += vec3(0.55) * pow(max(dot(n, h), 0.0), 80.0);
        // Fresnel-like: clear looking down, opaque at a grazing angle.
        alpha = mix(uAlphaFacing, uAlpha, pow(1.0 - max(dot(n, toEye), 0.0), 5.0));
        // Crests light and troughs dark, both more opaque, so that ripples show over the clear near water.
        // Height over the largest wave, square-rooted: small ripples far from a splash still show.
        float relative = clamp((vWorld.y - uWaterMean) * uCrest, -1.0, 1.0);
        float crest = sign(relative) * sqrt(abs(relative)) * uCrestAmount;
        colour = crest > 0.0 ? mix(colour, vec3(0.72, 0.86, 0.97), 0.8 * crest) : colour * (1.0 + 0.6 * crest);
        alpha = max(alpha, min(abs(crest), 1.0) * 0.75);
    }
    oColour = vec4(colour, alpha);
}
)";

GLuint compile(GLenum type, const char* src) {
    GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        glDeleteShader(s);
        throw std::runtime_error(std::string("renderer: shader does not compile: ") + log);
    }
    return s;
}

/// A vertex array with positions (float3) and 32-bit indices.
struct GpuMesh {
    GLuint vao = 0, vbo = 0, ebo = 0;
    GLsizei indexCount = 0;
    void create() {
        glGenVertexArrays(1, &vao);
        glGenBuffers(1, &vbo);
        glGenBuffers(1, &ebo);
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glEnableVertexAttribArray(0);
        glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 3 * sizeof(float), nullptr);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
        glBindVertexArray(0);
    }
    void upload(const std::vector<float>& xyz, const std::vector<unsigned>& idx, GLenum usage) {
        glBindVertexArray(vao);
        glBindBuffer(GL_ARRAY_BUFFER, vbo);
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(xyz.size() * sizeof(float)), xyz.data(), usage);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(idx.size() * sizeof(unsigned)), idx.data(), GL_STATIC_DRAW);
        indexCount = GLsizei(idx.size());
        glBindVertexArray(0);
    }
    void destroy() {
        if (ebo) glDeleteBuffers(1, &ebo);
        if (vbo) glDeleteBuffers(1, &vbo);
        if (vao) glDeleteVertexArrays(1, &vao);
        vao = vbo = ebo = 0;
    }
};

/// Unit arrow along +y from 0 to 1: a shaft (radius 0.5) to 0.75 and a cone (radius 1.2) to the tip; x and z
/// are later scaled by the arrow's width.
void unitArrow(std::vector<float>& xyz, std::vector<unsigned>& idx) {
    const int n = 12;
    const float shaftR = 0.5f, headR = 1.2f, headStart = 0.75f;
    auto ring = [&](float r, float y) {
        const unsigned first = unsigned(xyz.size() / 3);
        for (int i = 0; i < n; ++i) {
            const float a = 2.f * 3.14159265f * float(i) / float(n);
            xyz.insert(xyz.end(), {r * std::cos(a), y, r * std::sin(a)});
        }
        return first;
    };
    const unsigned b0 = ring(shaftR, 0.f), b1 = ring(shaftR, headStart), h0 = ring(headR, headStart);
    const unsigned tip = unsigned(xyz.size() / 3);
    xyz.insert(xyz.end(), {0.f, 1.f, 0.f});
    const unsigned base = unsigned(xyz.size() / 3);
    xyz.insert(xyz.end(), {0.f, 0.f, 0.f});
    for (int i = 0; i < n; ++i) {
        const unsigned j = unsigned((i + 1) % n);
        idx.insert(idx.end(), {b0 + i, b1 + i, b1 + j, b0 + i, b1 + j, b0 + j});  // shaft
        idx.insert(idx.end(), {h0 + i, tip, h0 + j});                              // cone
        idx.insert(idx.end(), {b1 + i, h0 + i, h0 + j, b1 + i, h0 + j, b1 + j});  // head's underside
        idx.insert(idx.end(), {base, b0 + i, b0 + j});                             // shaft's end
    }
}

}  // namespace

struct SceneRenderer::Impl {
    GLuint program = 0;
    GLint uModel = -1, uViewProj = -1, uPointSize = -1, uColour = -1, uWetColour = -1, uAlpha = -1, uMode = -1,
          uHasWater = -1, uHeights = -1, uWaterGrid = -1, uWaterSize = -1, uWaterMean = -1, uLightDir = -1, uEye = -1,
          uAlphaFacing = -1, uWaterline = -1, uTwoTone = -1, uPatternCentre = -1, uCrest = -1, uDeepColour = -1,
          uFogDepth = -1, uCrestAmount = -1;
    GpuMesh arrow, water, ground, points;
    int waterNx = 0, waterNz = 0;
    GLuint heightTexture = 0;
    struct CachedMesh {
        GpuMesh gpu;
        std::size_t vertices = 0, triangles = 0;
        std::uint64_t version = 0;
    };
    std::unordered_map<const TriangleMesh*, CachedMesh> meshes;
    std::vector<float> scratch;
    std::vector<unsigned> scratchIdx;

    GpuMesh& bodyMesh(const TriangleMesh& m, std::uint64_t version) {
        auto it = meshes.find(&m);
        if (it != meshes.end() && it->second.vertices == m.vertices.size() &&
            it->second.triangles == m.triangles.size() && it->second.version == version)
            return it->second.gpu;
        if (it != meshes.end()) it->second.gpu.destroy();
        CachedMesh& c = meshes[&m];
        c.version = version;
        c.vertices = m.vertices.size();
        c.triangles = m.triangles.size();
        scratch.clear();
        scratchIdx.clear();
        for (const auto& v : m.vertices) scratch.insert(scratch.end(), {float(v.x()), float(v.y()), float(v.z())});
        for (const auto& t : m.triangles) scratchIdx.insert(scratchIdx.end(), {unsigned(t[0]), unsigned(t[1]), unsigned(t[2])});
        c.gpu.create();
        c.gpu.upload(scratch, scratchIdx, GL_STATIC_DRAW);
        return c.gpu;
    }

    void setModel(const Eigen::Matrix4f& m) { glUniformMatrix4fv(uModel, 1, GL_FALSE, m.data()); }
    void setColour(const Eigen::Vector3f& c, float alpha) {
        glUniform3f(uColour, c.x(), c.y(), c.z());
        glUniform1f(uAlpha, alpha);
    }

    void uploadWater(const RenderWater& w, float mean) {
        if (w.nx != waterNx || w.nz != waterNz) {  // new index buffer for a new grid size
            waterNx = w.nx;
            waterNz = w.nz;
            scratchIdx.clear();
            for (int j = 0; j + 1 < w.nz; ++j)
                for (int i = 0; i + 1 < w.nx; ++i) {
                    const unsigned a = unsigned(j * w.nx + i), b = a + 1, c = a + unsigned(w.nx), d = c + 1;
                    scratchIdx.insert(scratchIdx.end(), {a, c, b, b, c, d});
                }
            scratch.assign(std::size_t(w.nx) * w.nz * 3, 0.f);
            water.upload(scratch, scratchIdx, GL_DYNAMIC_DRAW);
        }
        scratch.resize(std::size_t(w.nx) * w.nz * 3);
        for (int j = 0; j < w.nz; ++j)
            for (int i = 0; i < w.nx; ++i) {
                float* p = &scratch[3 * (std::size_t(j) * w.nx + i)];
                const bool border = i == 0 || j == 0 || i == w.nx - 1 || j == w.nz - 1;
                p[0] = w.x0 + float(i) * w.dx;
                p[1] = border ? mean : w.heights[std::size_t(j) * w.nx + i];  // meets the far water without a gap
                p[2] = w.z0 + float(j) * w.dz;
            }
        glBindBuffer(GL_ARRAY_BUFFER, water.vbo);
        glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(scratch.size() * sizeof(float)), scratch.data());
        glBindTexture(GL_TEXTURE_2D, heightTexture);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, w.nx, w.nz, 0, GL_RED, GL_FLOAT, w.heights.data());
    }
};

SceneRenderer::SceneRenderer() : m_impl(std::make_unique<Impl>()) {
    Impl& r = *m_impl;
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    r.program = glCreateProgram();
    glAttachShader(r.program, vs);
    glAttachShader(r.program, fs);
    glLinkProgram(r.program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(r.program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048];
        glGetProgramInfoLog(r.program, sizeof log, nullptr, log);
        glDeleteProgram(r.program);
        throw std::runtime_error(std::string("renderer: shader program does not link: ") + log);
    }
    auto loc = [&](const char* n) { return glGetUniformLocation(r.program, n); };
    r.uModel = loc("uModel");
    r.uViewProj = loc("uViewProj");
    r.uPointSize = loc("uPointSize");
    r.uColour = loc("uColour");
    r.uWetColour = loc("uWetColour");
    r.uAlpha = loc("uAlpha");
    r.uMode = loc("uMode");
    r.uHasWater = loc("uHasWater");
    r.uHeights = loc("uHeights");
    r.uWaterGrid = loc("uWaterGrid");
    r.uWaterSize = loc("uWaterSize");
    r.uWaterMean = loc("uWaterMean");
    r.uLightDir = loc("uLightDir");
    r.uEye = loc("uEye");
    r.uAlphaFacing = loc("uAlphaFacing");
    r.uWaterline = loc("uWaterline");
    r.uTwoTone = loc("uTwoTone");
    r.uPatternCentre = loc("uPatternCentre");
    r.uCrest = loc("uCrest");
    r.uCrestAmount = loc("uCrestAmount");
    r.uDeepColour = loc("uDeepColour");
    r.uFogDepth = loc("uFogDepth");

    std::vector<float> xyz;
    std::vector<unsigned> idx;
    unitArrow(xyz, idx);
    r.arrow.create();
    r.arrow.upload(xyz, idx, GL_STATIC_DRAW);
    r.water.create();
    r.ground.create();
    xyz = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    idx = {0, 2, 1, 0, 3, 2};
    r.ground.upload(xyz, idx, GL_STATIC_DRAW);
    r.points.create();
    glGenTextures(1, &r.heightTexture);
    glBindTexture(GL_TEXTURE_2D, r.heightTexture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

SceneRenderer::~SceneRenderer() {
    Impl& r = *m_impl;
    clearMeshCache();
    r.arrow.destroy();
    r.water.destroy();
    r.ground.destroy();
    r.points.destroy();
    if (r.heightTexture) glDeleteTextures(1, &r.heightTexture);
    if (r.program) glDeleteProgram(r.program);
}

void SceneRenderer::clearMeshCache() {
    for (auto& kv : m_impl->meshes) kv.second.gpu.destroy();
    m_impl->meshes.clear();
}

std::size_t SceneRenderer::meshCacheSize() const { return m_impl->meshes.size(); }

void SceneRenderer::draw(const RenderFrame& frame, int width, int height) {
    Impl& r = *m_impl;
    glViewport(0, 0, width, height);
    glClearColor(frame.background.x(), frame.background.y(), frame.background.z(), 1.f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glUseProgram(r.program);

    const RenderCamera& cam = frame.camera;
    const Eigen::Matrix4f viewProj = cam.projection(float(width) / float(std::max(height, 1))) * cam.view();
    glUniformMatrix4fv(r.uViewProj, 1, GL_FALSE, viewProj.data());
    const Eigen::Vector3f eye = cam.eye();
    glUniform3f(r.uEye, eye.x(), eye.y(), eye.z());
    const Eigen::Vector3f light = Eigen::Vector3f(0.35f, 0.85f, 0.4f).normalized();
    glUniform3f(r.uLightDir, light.x(), light.y(), light.z());
    glUniform1f(r.uPointSize, 3.f);

    const RenderWater& w = frame.water;
    const bool hasWater = w.visible && w.nx >= 2 && w.nz >= 2 && w.heights.size() == std::size_t(w.nx) * w.nz;
    glActiveTexture(GL_TEXTURE0);
    glUniform1i(r.uHeights, 0);
    glUniform1i(r.uHasWater, hasWater ? 1 : 0);
    float waterMean = 0;
    const float fogDepth = w.fogDepth > 0 ? w.fogDepth : std::max(0.35f * cam.distance, 1e-3f);
    glUniform1f(r.uFogDepth, fogDepth);
    glUniform3f(r.uDeepColour, w.deepColour.x(), w.deepColour.y(), w.deepColour.z());
    glUniform1i(r.uWaterline, w.waterline ? 1 : 0);
    glUniform1i(r.uTwoTone, 0);
    glUniform1f(r.uAlphaFacing, w.alphaFacing);
    glUniform1f(r.uCrest, 0.f);
    if (hasWater) {
        double sum = 0;
        for (float h : w.heights) sum += h;
        waterMean = float(sum / double(w.heights.size()));
        float largestWave = 0;
        for (float h : w.heights) largestWave = std::max(largestWave, std::abs(h - waterMean));
        r.uploadWater(w, waterMean);
        glUniform4f(r.uWaterGrid, w.x0, w.z0, w.dx, w.dz);
        glUniform2f(r.uWaterSize, float(w.nx), float(w.nz));
        glUniform1f(r.uWaterMean, waterMean);
        // Crest shading scaled to the largest wave of the frame; none on (nearly) flat water.
        const float flat = 1e-3f * std::max(cam.distance, 1.f);
        glUniform1f(r.uCrest, largestWave > flat ? 1.f / largestWave : 0.f);
        glUniform1f(r.uCrestAmount, w.crestShading);
    }

    // Ground: a large sandy quad on the plane, centred below the camera target, fading to deep water with depth.
    if (frame.ground.visible) {
        const Eigen::Vector3f n = frame.ground.normal.normalized();
        const Eigen::Vector3f c = cam.target - (n.dot(cam.target) - frame.ground.offset) * n;
        const Eigen::Vector3f t = (std::abs(n.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitZ())
                                      .cross(n).normalized();
        const Eigen::Vector3f b = n.cross(t);
        const float half = 40.f + 6.f * cam.distance;
        Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
        m.block<3, 1>(0, 0) = b * half;  // quad's x
        m.block<3, 1>(0, 1) = n;         // quad's y (flat)
        m.block<3, 1>(0, 2) = t * half;  // quad's z
        m.block<3, 1>(0, 3) = c;
        r.setModel(m);
        glUniform1i(r.uMode, 2);
        r.setColour(Eigen::Vector3f(0.76f, 0.70f, 0.55f), 1.f);
        glBindVertexArray(r.ground.vao);
        glDrawElements(GL_TRIANGLES, r.ground.indexCount, GL_UNSIGNED_INT, nullptr);
    }

    // Open water has a bottom: a deep-water plane well below the surface, so the translucent surface shows blue,
    // not the sky, where nothing lies beneath it.
    if (hasWater) {
        Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
        const float half = 60.f + 40.f * cam.distance;
        m(0, 0) = m(2, 2) = half;
        m.block<3, 1>(0, 3) = Eigen::Vector3f(cam.target.x(), waterMean - 6.f * fogDepth, cam.target.z());
        r.setModel(m);
        glUniform1i(r.uMode, 5);
        r.setColour(w.deepColour, 1.f);
        glBindVertexArray(r.ground.vao);
        glDrawElements(GL_TRIANGLES, r.ground.indexCount, GL_UNSIGNED_INT, nullptr);
    }

    // Bodies, wet/dry per pixel.
    glUniform1i(r.uMode, 0);
    for (const RenderBody& body : frame.bodies) {
        if (!body.mesh || body.mesh->triangles.empty()) continue;
        GpuMesh& g = r.bodyMesh(*body.mesh, body.meshVersion);
        r.setModel(body.meshToWorld);
        r.setColour(body.colour, 1.f);
        glUniform3f(r.uWetColour, body.wetColour.x(), body.wetColour.y(), body.wetColour.z());
        glUniform1i(r.uTwoTone, body.twoTonePattern ? 1 : 0);
        glUniform3f(r.uPatternCentre, body.patternCentre.x(), body.patternCentre.y(), body.patternCentre.z());
        glBindVertexArray(g.vao);
        glDrawElements(GL_TRIANGLES, g.indexCount, GL_UNSIGNED_INT, nullptr);
    }
    glUniform1i(r.uTwoTone, 0);

    // Sample points (wet blue, dry white), unlit.
    if (!frame.samples.positions.empty()) {
        glUniform1i(r.uMode, 1);
        r.setModel(Eigen::Matrix4f::Identity());
        for (int pass = 0; pass < 2; ++pass) {
            r.scratch.clear();
            r.scratchIdx.clear();
            for (std::size_t i = 0; i < frame.samples.positions.size(); ++i) {
                const bool wet = i < frame.samples.wet.size() && frame.samples.wet[i];
                if (wet != (pass == 1)) continue;
                const Eigen::Vector3f& p = frame.samples.positions[i];
                r.scratchIdx.push_back(unsigned(r.scratch.size() / 3));
                r.scratch.insert(r.scratch.end(), {p.x(), p.y(), p.z()});
            }
            if (r.scratchIdx.empty()) continue;
            r.points.upload(r.scratch, r.scratchIdx, GL_STREAM_DRAW);
            r.setColour(pass ? Eigen::Vector3f(0.1f, 0.3f, 1.f) : Eigen::Vector3f(1.f, 1.f, 1.f), 1.f);
            glBindVertexArray(r.points.vao);
            glDrawElements(GL_POINTS, r.points.indexCount, GL_UNSIGNED_INT, nullptr);
        }
    }

    // Water: translucent, after the opaque geometry.
    if (hasWater) {
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        glUniform1i(r.uMode, 3);
        r.setModel(Eigen::Matrix4f::Identity());
        r.setColour(w.colour, w.alpha);
        glBindVertexArray(r.water.vao);
        glDrawElements(GL_TRIANGLES, r.water.indexCount, GL_UNSIGNED_INT, nullptr);
        // Far water: four flat quads at the mean height framing the grid out to the horizon.
        const float y = waterMean;
        const float ax = w.x0, bx = w.x0 + w.dx * float(w.nx - 1), az = w.z0, bz = w.z0 + w.dz * float(w.nz - 1);
        const float far = 60.f + 30.f * cam.distance;
        const float X0 = ax - far, X1 = bx + far, Z0 = az - far, Z1 = bz + far;
        r.scratch = {X0, y, Z0, X1, y, Z0, X1, y, az, X0, y, az,   // z < grid
                     X0, y, bz, X1, y, bz, X1, y, Z1, X0, y, Z1,   // z > grid
                     X0, y, az, ax, y, az, ax, y, bz, X0, y, bz,   // x < grid
                     bx, y, az, X1, y, az, X1, y, bz, bx, y, bz};  // x > grid
        r.scratchIdx.clear();
        for (unsigned q = 0; q < 4; ++q)
            r.scratchIdx.insert(r.scratchIdx.end(), {4 * q, 4 * q + 1, 4 * q + 2, 4 * q, 4 * q + 2, 4 * q + 3});
        r.points.upload(r.scratch, r.scratchIdx, GL_STREAM_DRAW);
        glBindVertexArray(r.points.vao);
        glDrawElements(GL_TRIANGLES, r.points.indexCount, GL_UNSIGNED_INT, nullptr);
        glDisable(GL_BLEND);
    }

    // Arrows last, over a cleared depth buffer: on top of bodies and water, yet each arrow shaded correctly.
    if (!frame.arrows.empty()) {
        glClear(GL_DEPTH_BUFFER_BIT);
        glUniform1i(r.uMode, 4);
        glBindVertexArray(r.arrow.vao);
        for (const RenderArrow& a : frame.arrows) {
            const float len = a.vector.norm();
            if (!(len > 1e-6f) || !std::isfinite(len)) continue;
            const Eigen::Vector3f y = a.vector / len;
            const Eigen::Vector3f x = (std::abs(y.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitZ())
                                          .cross(y).normalized();
            const Eigen::Vector3f z = x.cross(y);
            const float width = std::max(0.02f, std::min(0.06f * len, 0.05f * cam.distance * 0.15f));
            Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
            m.block<3, 1>(0, 0) = x * width;
            m.block<3, 1>(0, 1) = y * len;
            m.block<3, 1>(0, 2) = z * width;
            m.block<3, 1>(0, 3) = a.origin;
            r.setModel(m);
            r.setColour(a.colour, 1.f);
            glDrawElements(GL_TRIANGLES, r.arrow.indexCount, GL_UNSIGNED_INT, nullptr);
        }
    }
    glBindVertexArray(0);
    glUseProgram(0);
}

}  // namespace buoyancy::render
