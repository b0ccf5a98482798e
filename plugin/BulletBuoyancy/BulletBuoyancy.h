#pragma once
/// @file BulletBuoyancy.h
/// Everything a program needs to add buoyancy to a Bullet world, in one include:
///
///     #include <BulletBuoyancy/BulletBuoyancy.h>
///
/// The public headers are this one and the headers it includes (directly or through them); only those are
/// installed. The Bullet layer (bullet/) holds the classes a Bullet program uses: the world context
/// (btBuoyancyWorld), the per-body action (btBuoyancyAction), its settings and shape, the body builder, and
/// the optional actions (flooding through a water graph, time-varying mass, deformable bodies, the interactive
/// water's coupling). The water surfaces (water/), the mesh import and checks (mesh/) and the water graph
/// (graph/) are Bullet-free.

// The Bullet layer.
#include <BulletBuoyancy/bullet/btBuoyancyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancyBody.h>
#include <BulletBuoyancy/bullet/btBuoyancyDeformable.h>
#include <BulletBuoyancy/bullet/btBuoyancyEvents.h>
#include <BulletBuoyancy/bullet/btBuoyancyImmediate.h>
#include <BulletBuoyancy/bullet/btBuoyancyInvariants.h>
#include <BulletBuoyancy/bullet/btBuoyancyMultiBodyAction.h>
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/bullet/btBuoyancyState.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btBuoyantBodyBuilder.h>
#include <BulletBuoyancy/bullet/btMarineHydrodynamics.h>
#include <BulletBuoyancy/bullet/btCollisionShapeMesh.h>
#include <BulletBuoyancy/bullet/btConvexHullMesh.h>
#include <BulletBuoyancy/bullet/btFloodingAction.h>
#include <BulletBuoyancy/bullet/btInteractiveWaterCoupler.h>
#include <BulletBuoyancy/bullet/btTimeVaryingMassAction.h>
#include <BulletBuoyancy/bullet/btWaterFrame.h>

// Water surfaces.
#include <BulletBuoyancy/water/btFftOceanSurface.h>
#include <BulletBuoyancy/water/btGerstnerWaterSurface.h>
#include <BulletBuoyancy/water/btGridWaterSurface.h>
#include <BulletBuoyancy/water/btInteractiveWaterSurface.h>
#include <BulletBuoyancy/water/btRiverSurface.h>
#include <BulletBuoyancy/water/btWaterDeviceDescription.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

// Meshes: import, checks and repair, primitives.
#include <BulletBuoyancy/mesh/MeshImport.h>
#include <BulletBuoyancy/mesh/MeshRepair.h>
#include <BulletBuoyancy/mesh/PrimitiveMeshes.h>
#include <BulletBuoyancy/mesh/TriangleMesh.h>

// Water graphs: water inside permeable bodies.
#include <BulletBuoyancy/graph/AutoWaterGraph.h>
#include <BulletBuoyancy/graph/PermeabilityMap.h>
#include <BulletBuoyancy/graph/PermeabilityTexture.h>
#include <BulletBuoyancy/graph/WaterGraph.h>
#include <BulletBuoyancy/graph/WaterIngress.h>
