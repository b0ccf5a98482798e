#pragma once
/// @file RenderFrame.h
/// What the renderer draws, as plain data (no OpenGL, no Bullet): bodies (a mesh and its world transform),
/// force arrows, the water surface as a height grid, the ground plane, optional surface-sample points and the
/// camera. Built from a running scene by SceneFrame.h; drawn by SceneRenderer.h.

#include <BulletBuoyancy/mesh/TriangleMesh.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace buoyancy::render {

/// An orbit camera looking at `target`, y up.
struct RenderCamera {
    Eigen::Vector3f target = Eigen::Vector3f::Zero(); ///< point looked at, world, m
    float distance = 10.f;  ///< eye–target distance, m
    float yawDeg = 35.f;    ///< rotation of the eye about +y (the water frame's up: SceneFrame.h), degrees (0: eye on +z)
    float pitchDeg = 22.f;  ///< elevation of the eye above the target's horizontal plane, degrees
    float fovDeg = 45.f;    ///< vertical field of view, degrees

    /// Eye position, world, m.
    Eigen::Vector3f eye() const;
    /// World → eye matrix.
    Eigen::Matrix4f view() const;
    /// Eye → clip matrix for a viewport of aspect width/height (near/far from the distance).
    Eigen::Matrix4f projection(float aspect) const;
};

/// One body: its mesh (mesh frame, m) placed by `meshToWorld`.
struct RenderBody {
    const TriangleMesh* mesh = nullptr;                    ///< must outlive the draw call
    std::uint64_t meshVersion = 0;  ///< bump when the mesh's vertices change (deformable bodies): re-uploaded
    Eigen::Matrix4f meshToWorld = Eigen::Matrix4f::Identity();
    Eigen::Vector3f colour = Eigen::Vector3f(0.85f, 0.55f, 0.25f); ///< dry colour, linear RGB 0..1
    Eigen::Vector3f wetColour = Eigen::Vector3f(0.5f, 0.3f, 0.11f); ///< colour of the surface below the water
    /// Paint the half of the body below its mesh frame's x–z plane through `patternCentre` white, so that a round
    /// body's tilt shows: upright, its colour is on top; rolled over, the white half is.
    bool twoTonePattern = false;
    Eigen::Vector3f patternCentre = Eigen::Vector3f::Zero(); ///< mesh frame, m
};

/// A force arrow from `origin` along `vector` (both world, m; the length is already scaled).
struct RenderArrow {
    Eigen::Vector3f origin = Eigen::Vector3f::Zero();
    Eigen::Vector3f vector = Eigen::Vector3f::Zero();
    Eigen::Vector3f colour = Eigen::Vector3f::Ones();
};

/// The water surface as heights on a regular x–z grid (also used per pixel for the wet/dry colouring).
struct RenderWater {
    bool visible = true;
    int nx = 0, nz = 0;             ///< samples along x and z (≥ 2 each when visible)
    float x0 = 0, z0 = 0;           ///< world x, z of sample (0, 0), m
    float dx = 1, dz = 1;           ///< spacing, m
    std::vector<float> heights;     ///< nx·nz heights (world y), index j·nx + i, m
    Eigen::Vector3f colour = Eigen::Vector3f(0.12f, 0.36f, 0.62f);
    /// Colour that what lies below the surface fades to with depth (and the bottom of open water), linear RGB 0..1.
    Eigen::Vector3f deepColour = Eigen::Vector3f(0.05f, 0.21f, 0.34f);
    float alpha = 0.9f;             ///< opacity seen at a grazing angle (far water)
    float alphaFacing = 0.15f;      ///< opacity looking straight down (near water: bodies below it stay visible)
    /// Depth below the mean surface over which submerged things fade 63 % towards `deepColour`, m; 0: 0.35 × the
    /// camera distance.
    float fogDepth = 0;
    /// Crest shading at the frame's largest wave (0: none, 1: fully light and opaque): crests lighter and troughs
    /// darker, both more opaque, by the square root of their height over the largest wave's, so that small ripples
    /// (the rings of a splash) show.
    float crestShading = 0.6f;
    bool waterline = true;          ///< draw the waterline on the bodies (a light line where they cut the surface)
};

/// The static ground plane {p : normal · p = offset}.
struct RenderGround {
    bool visible = false;
    Eigen::Vector3f normal = Eigen::Vector3f::UnitY(); ///< unit
    float offset = 0;                                  ///< m
};

/// Surface samples drawn as points, wet (below the water height) or dry.
struct RenderPoints {
    std::vector<Eigen::Vector3f> positions; ///< world, m
    std::vector<std::uint8_t> wet;          ///< 1 = below the water surface at the sample's x, z
};

/// Everything one picture shows.
struct RenderFrame {
    RenderCamera camera;
    std::vector<RenderBody> bodies;
    std::vector<RenderArrow> arrows;
    RenderWater water;
    RenderGround ground;
    RenderPoints samples;
    Eigen::Vector3f background = Eigen::Vector3f(0.78f, 0.85f, 0.92f); ///< sky colour
};

}  // namespace buoyancy::render
