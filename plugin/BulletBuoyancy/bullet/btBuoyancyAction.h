#pragma once
/// @file btBuoyancyAction.h
/// The Bullet coupling: one btActionInterface per floating body (in the style of btRaycastVehicle).
/// Each substep, after Bullet has integrated the transforms, it evaluates the pressure force and torque
/// (design.md 2.3), drag and skin friction (2.6) and added mass (2.7) at the body's new pose and applies
/// them as impulses (F·dt, τ·dt), so any maxSubSteps gives the same motion (design.md 3).
///
/// Usage:  btBuoyancyWorld water(&dynamicsWorld, &surface);  btBuoyancyAction action(body, shape, &water);
///         dynamicsWorld->addAction(&action);   // ... remove it before deleting the body.
/// Removing the action from the world is safe at any time. Deleting the body while its action is still in
/// the world is a misuse (checked in debug builds: the body must be in the world the action runs in).

#include <BulletBuoyancy/bullet/btBuoyancyBody.h>
#include <BulletBuoyancy/bullet/btBuoyancyDeviceBackend.h>
#include <BulletBuoyancy/bullet/btBuoyancySettings.h>
#include <BulletBuoyancy/bullet/btBuoyancyShape.h>
#include <BulletBuoyancy/bullet/btBuoyancyWorld.h>
#include <BulletBuoyancy/bullet/btTemporalLevelOfDetail.h>  // the older bt names of the controller, for users
#include <BulletBuoyancy/bullet/btMarineHydrodynamics.h>
#include <BulletBuoyancy/integrals/DragClusters.h>
#include <BulletBuoyancy/integrals/Hydrostatics.h>
#include <BulletBuoyancy/integrals/WaterPatch.h>
#include <BulletBuoyancy/temporal/TemporalLevelOfDetail.h>
#include <BulletBuoyancy/water/btWaterSurface.h>

#include <BulletDynamics/Dynamics/btActionInterface.h>
#include <LinearMath/btTransform.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

class btRigidBody;
class btBuoyancyWorld;
class btCollisionWorld;
class btBuoyantBody;
class btBuoyancyDeformable;

/// What the last substep computed for one body (world frame). Forces are the ones applied (after the drag
/// stability limit); torques are about the body's centre of mass.
struct btBuoyancyResult {
    double submergedVolume = 0;                 ///< V_sub, m³
    btVector3 centreOfBuoyancy = btVector3(0, 0, 0); ///< m, world (meaningless when submergedVolume is 0)
    btVector3 buoyancyForce = btVector3(0, 0, 0);    ///< pressure force, N
    btVector3 buoyancyTorque = btVector3(0, 0, 0);   ///< pressure torque about the COM, N·m
    btVector3 dragForce = btVector3(0, 0, 0);        ///< pressure drag + skin friction, N
    btVector3 dragTorque = btVector3(0, 0, 0);       ///< about the COM, N·m
    double wettedArea = 0;                      ///< m²
    double waterlineArea = 0;                   ///< m²
    /// The heave added mass applied this substep (along the water's up), kg; across it the added mass is C_a ρ V_sub
    /// (btBuoyancySettings::addedMassCoefficient, design.md 2.7).
    double addedMass = 0;
    double time = 0;                            ///< water time of the evaluation, s
    /// The linear impulse applied at the centre of mass this substep (buoyancy, drag and added mass together; zero
    /// when nothing was applied), N·s.
    btVector3 linearImpulse = btVector3(0, 0, 0);
    /// The angular impulse applied this substep, N·m·s.
    btVector3 angularImpulse = btVector3(0, 0, 0);
    bool applied = false;                       ///< false when nothing was applied (dry, asleep, rejected)
    /// The hydrostatic fields were predicted from earlier exact evaluations, not evaluated at this substep
    /// (btBuoyancySettings::hydrostaticsInterval > 1; buoyancy::HydrostaticsHistory).
    bool predicted = false;
    /// Ok, or why no buoyancy was computed although the body may be in the water (btBuoyancyStatusMessage).
    btBuoyancyStatus status = btBuoyancyStatus::Ok;
};

/// Internal (btBuoyancyWorld's batch): evaluate `action`'s body for the current substep of its world (dt, s).
void btBuoyancyWorldEvaluate(btBuoyancyAction& action, const btCollisionWorld* collisionWorld, double dt);
/// Internal (btBuoyancyWorld's batch): ask the CPU to bring an action's state into the cache before it is evaluated
/// (the batch walks many bodies whose state is no longer cached): its own object (`referenced` false), or, a stage
/// later, what it points to (its rigid body, its body's mesh frame). Changes nothing.
void btBuoyancyWorldPrefetch(const btBuoyancyAction& action, bool referenced);
/// Internal (btBuoyancyWorld's batch): query the wave heights of the patch the action's next exact evaluation will
/// build, when its last evaluation asked for it (while Bullet steps, on another thread); true when they were queried.
/// Changes no result.
bool btBuoyancyWorldPrebuildPatch(btBuoyancyAction& action);

/// What btBuoyancyAction::setBodyMassFromShape set, and how exactly Bullet's diagonal inertia represents the solid.
struct btBuoyancyMassResult {
    double mass = 0;                              ///< ρ V, kg
    btVector3 localInertia{0, 0, 0};              ///< the diagonal handed to setMassProps, kg·m² (body axes)
    btVector3 centroidOffset{0, 0, 0};            ///< the solid's centroid in the body's centre-of-mass frame, m
    /// Largest product of inertia over the smallest principal moment (0 when the body axes are principal): what the
    /// diagonal leaves out, dimensionless.
    double productOfInertiaRatio = 0;
};

/// Buoyancy of one rigid body in the water of a btBuoyancyWorld.
class btBuoyancyAction : public btActionInterface, public btBuoyancyDeviceBody {
public:
    /// Any rigid body whose collision/COM frame holds the mesh at `meshInCom` (identity when the mesh's
    /// origin is the COM and its axes the principal axes).
    /// @param body      the body (not owned; must outlive the action's presence in a world)
    /// @param shape     shared buoyancy data of the body's mesh
    /// @param world     the shared context (not owned, outlives the action); the action registers with it
    /// @param settings  drag/added-mass settings (validated; the method and texture come from `shape`)
    /// @throws std::invalid_argument naming a bad argument or setting
    btBuoyancyAction(btRigidBody* body, std::shared_ptr<const btBuoyancyShape> shape, btBuoyancyWorld* world,
                     const btBuoyancySettings& settings = btBuoyancySettings(),
                     const btTransform& meshInCom = btTransform::getIdentity());
    /// Your own rigid body as it is: the geometry is its collision shape (btBuoyancyShape::fromCollisionShape, in
    /// the body's centre-of-mass frame, where Bullet puts the shape), the mass and inertia are the body's own.
    /// @throws std::invalid_argument naming the collision shape's type when it is not supported, or a bad setting
    btBuoyancyAction(btRigidBody* body, btBuoyancyWorld* world, const btBuoyancySettings& settings = btBuoyancySettings());
    /// A body of another type (btBuoyancyBody.h: a body of your own integrator, a part of an articulated body) whose
    /// centre-of-mass frame holds the mesh at `meshInCom`; the action reads and writes it only through the interface.
    /// @param body      the body (not owned; must outlive the action)
    /// @throws std::invalid_argument as the constructor above
    btBuoyancyAction(btBuoyancyBody& body, std::shared_ptr<const btBuoyancyShape> shape, btBuoyancyWorld* world,
                     const btBuoyancySettings& settings = btBuoyancySettings(),
                     const btTransform& meshInCom = btTransform::getIdentity());
    /// A body made by btBuoyantBody: its mesh frame follows updateMassProperties automatically.
    btBuoyancyAction(btBuoyantBody& body, btBuoyancyWorld* world, const btBuoyancySettings& settings = btBuoyancySettings());
    ~btBuoyancyAction() override;
    btBuoyancyAction(const btBuoyancyAction&) = delete;
    btBuoyancyAction& operator=(const btBuoyancyAction&) = delete;

    /// Called by Bullet once per substep after integrateTransforms; applies impulses for `deltaTimeStep`. When its
    /// btBuoyancyWorld batches (the default, btBuoyancyWorld::setBatching), the first action of the world called in a
    /// substep evaluates every body of the world across threads, and each action applies its own result here.
    void updateAction(btCollisionWorld* collisionWorld, btScalar deltaTimeStep) override;
    /// Draws the buoyancy force at the centre of buoyancy and the drag force at the COM (1 m per m·g).
    void debugDraw(btIDebugDraw* debugDrawer) override;

    /// Set the body's mass and inertia from the buoyancy geometry at a uniform `density` (kg/m³, finite, > 0):
    /// mass ρ V; inertia the solid's exact tensor (a btSphereShape's 2/5 m R² in closed form, every other shape from
    /// its exact mesh integrals), taken about the body's centre-of-mass frame origin and expressed in its axes,
    /// whose diagonal is handed to btRigidBody::setMassProps (Bullet's own calculateLocalInertia takes most shapes
    /// for their bounding box: a sphere's inertia 2.5× too large, a capsule's or a cone's far off). The body is
    /// activated and its world inertia updated. Exact when the solid's centroid is the frame's origin and its axes
    /// are principal (boxes, spheres, capsules, cylinders, multi-spheres of symmetric layout, btBuoyantBody's bodies);
    /// otherwise the result says by how much it is not (a btConeShape's centroid lies a quarter of its height below
    /// Bullet's origin: shift the shape in a btCompoundShape to make it exact).
    /// @throws std::invalid_argument for a density that is not finite and positive (body unchanged)
    btBuoyancyMassResult setBodyMassFromShape(double density);

    /// Result of the last substep.
    const btBuoyancyResult& getLastResult() const { return m_result; }
    /// The Bullet rigid body, or nullptr when the action floats another body type (getBody).
    btRigidBody* getRigidBody() const { return m_body->getRigidBody(); }
    /// The body as the action reads and writes it (btBuoyancyBody.h).
    btBuoyancyBody& getBody() const { return *m_body; }
    /// The shared buoyancy data.
    const std::shared_ptr<const btBuoyancyShape>& getShape() const { return m_shape; }
    /// Settings in use.
    const btBuoyancySettings& getSettings() const { return m_settings; }
    /// Replace the settings. @throws std::invalid_argument (settings unchanged), also when settings.addedMass is on while
    /// the marine hydrodynamics are enabled (setMarineHydrodynamics)
    void setSettings(const btBuoyancySettings& settings);
    /// Marine-robotics hydrodynamics (Fossen's model, design.md 2.10): a 6×6 added mass, linear and quadratic damping
    /// in a body-fixed frame and the added mass's Coriolis forces, solved with the body's own mass at the end of each
    /// substep (stable for any added mass). Off by default. They replace the scalar added mass of the settings, so
    /// btBuoyancySettings::addedMass must be false while they are enabled; the per-sample drag and damping of the
    /// settings still apply (set dragCoefficient, skinFriction, linearDamping to 0 when the datasheet's damping covers
    /// them; radiationDamping acts only near the surface). A velocity set on the body from outside between substeps
    /// counts as an impulse on the rigid mass and is shared with the added mass (before the first wet substep it is
    /// taken as it is). Rigid bodies only (btBuoyancyMultiBodyAction has no marine model).
    /// @throws std::invalid_argument naming the field (btMarineHydrodynamics::validate), or `enabled` when
    ///         settings.addedMass is on (nothing changed)
    void setMarineHydrodynamics(const btMarineHydrodynamics& hydrodynamics);
    /// The marine hydrodynamics in use (enabled false: none).
    const btMarineHydrodynamics& getMarineHydrodynamics() const { return m_marine; }
    /// The mesh frame in the body's COM frame (for bodies not made by btBuoyantBody).
    void setMeshInComFrame(const btTransform& meshInCom) { m_meshInCom = meshInCom; }
    /// The mesh frame in the body's COM frame currently used.
    btTransform getMeshInComFrame() const;
    /// The drag samples in use: the shape's fine drag samples merged into at most settings.dragClusters
    /// clusters (design.md 2.5; shared between the actions of one shape at one setting).
    const buoyancy::DragClusters& getDragClusters() const { return *m_drag; }
    /// Number of substeps whose impulses were rejected as non-finite (should stay 0).
    std::uint64_t getRejectedCount() const { return m_rejected; }

    ///@name Water events and state (btBuoyancyEvents.h, docs/integration.md "Events and queries")
    /// The body's submerged volume over its volume at the last substep, 0..1: 0 out of the water, 1 under it. It keeps
    /// its last value while the body sleeps in calm water or gets no buoyancy for want of gravity; with
    /// btBuoyancySettings::buoyancyEnabled false it is 0 (no submerged volume is computed).
    double getSubmergedFraction() const { return m_submergedFraction; }
    /// True from the substep the body entered the water until it leaves it (the hysteresis of
    /// btBuoyancyWorld::getEventSettings).
    bool isInWater() const { return m_waterState.inWater; }
    /// True from the substep the body became fully submerged until it surfaces.
    bool isFullySubmerged() const { return m_waterState.submerged; }
    /// The water body the body is in: an index in btBuoyancyWorld::getWaterBodies(), or −1 when it is not in the
    /// water (isInWater) or in the world's unbounded water.
    int getWaterBody() const { return m_waterState.inWater ? m_waterState.waterBody : -1; }
    ///@}

    ///@name Save and restore (btBuoyancyState.h, docs/integration.md "Save and restore")
    /// The body's buoyancy state as a versioned blob of bytes: everything this action carries from one substep to the
    /// next — the temporal level of detail (TemporalLevelOfDetail: its records, interval, check and cool-down
    /// counters), the water queries' warm starts, the drag's kept water heights and velocities, the linear damping's
    /// share, the sleep decision's last centre of mass and the body's own sleeping thresholds, the water events'
    /// states (in the water, fully submerged, which water body), the water body chosen, the rejected-substep count and
    /// the last result. Not saved: the settings, the shape, a deformable's samples (build the action the same way), and
    /// the Bullet body's own state (its transforms, velocities, activation state, deactivation time and sleeping
    /// thresholds: save and restore those yourself, docs/integration.md). Call between stepSimulation calls. Size:
    /// 14 kB for a box in a Gerstner sea with the default settings: 32 bytes per drag cluster for the drag's kept water
    /// (220 clusters) and 32 bytes per point of the water queries' warm starts (samples or mesh vertices, water-patch
    /// nodes, drag clusters; none in flat water).
    std::vector<unsigned char> saveState() const;
    /// Restore what saveState wrote into this action: an action built the same way (same shape, settings and world),
    /// the same one or another (a replay, a rollback, another process of the same build and precision). The blob is
    /// read and checked whole before anything changes. Restore the world (btBuoyancyWorld::restoreState) too, and the
    /// Bullet body's own state; call between stepSimulation calls.
    /// @param data, size  the blob (size in bytes)
    /// @throws std::invalid_argument naming the problem, the action unchanged: not a state blob (wrong magic), another
    ///         format version, a blob of the other precision (float/double btScalar), another kind of blob (a world's,
    ///         a flooding action's ...), truncated, corrupted (checksum), a blob of a body with another mesh, sample, drag
    ///         cluster or velocity probe count, or a water-query warm start naming a water body the world does not have
    /// @throws std::logic_error when called from an event callback (during a step)
    void restoreState(const unsigned char* data, std::size_t size);
    /// restoreState of a whole vector. @throws std::invalid_argument, std::logic_error (see above)
    void restoreState(const std::vector<unsigned char>& blob) { restoreState(blob.data(), blob.size()); }
    ///@}

    ///@name Deformable bodies and device backends
    /// Deformable body (paper Fig. 17): use `deformable`'s samples, re-baked from animated vertices
    /// (btBuoyancyDeformable::setVertices), instead of the shape's; nullptr: the shape's again.
    /// @throws std::invalid_argument when its sample count differs from the shape's
    void setDeformable(std::shared_ptr<btBuoyancyDeformable> deformable);
    /// The deformable samples in use, or nullptr.
    const std::shared_ptr<btBuoyancyDeformable>& getDeformable() const { return m_deformable; }
    /// The hydrostatic samples in use: the deformable's, or the shape's.
    const buoyancy::SurfaceSamples& getSamplesInUse() const;
    /// The velocities drag is evaluated at, given this substep's hydrostatics `h` (see updateAction): the body's
    /// velocity plus this substep's hydrostatic kick (with added mass) plus the gravity kick of the next one.
    /// `h`, v and w are in the world's water frame (btBuoyancyWorld::getWaterFrame; the world's axes for +y up).
    /// Public so a batching backend evaluates every body's drag at exactly the velocity the action would.
    /// @param dt  substep, s   @param[out] v  m/s   @param[out] w  rad/s
    void dragEvaluationVelocity(const buoyancy::HydrostaticsResult& h, double dt, Eigen::Vector3d& v,
                                Eigen::Vector3d& w) const override;
    /// The linear damping coefficient b of this substep's drag, m/s (design.md 2.6, "Radiation damping"):
    /// settings.linearDamping plus the radiation damping β g / ω_n faded by the depth of the body's top under the
    /// water (btBuoyancySettings::radiationDamping). Public so a batching backend uses the action's own value.
    /// @param h     this substep's hydrostatics (waterline area and submerged volume), water frame
    /// @param pose  the mesh's pose in the water frame (btBuoyancyWorld::getWaterFrame)
    double linearDampingNow(const buoyancy::HydrostaticsResult& h, const Eigen::Isometry3d& pose) const override;
    /// This substep's record of the body for a batching backend (btBuoyancyDeviceBody::deviceRecord): false unless the
    /// action would compute it with a sampled method (not exact-mesh, buoyancy on, awake or in changing water, in
    /// reach of the water and not entirely under flat water, where the closed form is used).
    bool deviceRecord(const btWaterSurface& water, double time, btBuoyancyDeviceRecord& out) const override;
    ///@}

private:
    friend class btBuoyancyImmediate;  // steps a body that is in no Bullet world (m_outsideWorld)
    friend void btBuoyancyWorldEvaluate(btBuoyancyAction& action, const btCollisionWorld* collisionWorld, double dt);
    friend void btBuoyancyWorldPrefetch(const btBuoyancyAction& action, bool referenced);
    friend bool btBuoyancyWorldPrebuildPatch(btBuoyancyAction& action);
    /// Everything of a substep that reads the body and writes only this action's state: the water, hydrostatics,
    /// drag, the temporal level of detail and the decisions; what it would write into the body is kept for
    /// applyPending. Safe to run for different bodies at once. dt: substep, s (> 0, finite).
    /// A list of phases, in this order; the gates (returning false) end the substep with their own effects:
    /// startEvaluation, readWorld, readBodyPose, chooseWater, bodyReachesWater (gates), then predictHydrostatics,
    /// buildWaterPatch, evaluateHydrostatics (a gate too), addedMassAndWaterForce, evaluateDrag,
    /// recordTemporalLevelOfDetail, implicitDragScale, computeImpulses, recordResult, decideImpulseAndSleep.
    void evaluate(const btCollisionWorld* collisionWorld, double dt);
    /// Write what evaluate decided into the body (activation, sleeping thresholds, impulses), at the action's turn.
    void applyPending();

    ///@name The phases of evaluate (btBuoyancyAction.cpp), each called once per substep, in the order listed
    /// A gate returns false when the substep ends there (its effects written, nothing applied); true: go on.
    /// Everything they hand on is in the world's water frame (btBuoyancyWorld::getWaterFrame).
    ///@{
    /// What the gates learn about the body and its water this substep (defined in btBuoyancyAction.cpp).
    struct SubstepContext;
    /// What the phases of a body the water reaches hand on: hydrostatics, added mass, drag and impulses (defined in
    /// btBuoyancyAction.cpp; built only once the body is wet).
    struct SubstepForces;
    /// Ask for the next substep's patch heights (btBuoyancyWorldPrebuildPatch), when that substep will build one.
    void requestPatchPrebuild(const SubstepContext& c);
    /// Who would use a wave patch over the body in `water` this substep (design.md 2.5): its nodes per side
    /// (btBuoyancyWaterPatchNodes), and whether the hydrostatics and the drag each stand for more points than its
    /// nodes (`dragOn`: any drag is set). nodes 0: no patch (a straddling body, patches off, or a surface that prefers
    /// exact queries). The one rule of buildWaterPatch and requestPatchPrebuild.
    struct PatchUse {
        std::size_t nodes = 0;      ///< nodes per side
        bool hydrostatics = false;  ///< nodes² < the hydrostatics' points (mesh vertices or samples)
        bool drag = false;          ///< nodes² < the drag clusters
    };
    PatchUse patchUse(const SubstepContext& c, const btWaterSurface* water, bool dragOn) const;
    /// Any drag, skin friction or damping is set (settings).
    bool dragIsOn() const {
        return m_settings.dragCoefficient > 0 || m_settings.skinFriction > 0 || m_settings.linearDamping > 0 ||
               m_settings.radiationDamping > 0;
    }
    /// Marks the substep evaluated and clears what the last one left pending (m_evaluatedSubstep, the pending flags,
    /// m_result.applied and .status); debug builds check that the body is in `collisionWorld`.
    void startEvaluation(const btCollisionWorld* collisionWorld);
    /// Gate. Reads the world's water (c.water, c.bounded) and whether changing water may reach the body (c.waves).
    /// False, doing nothing, for a body out of its world, a static one or a world without water; false with the
    /// gravity status in m_result (history forgotten, the body's sleeping thresholds pending) when gravity is not
    /// along the water's down axis; false with m_needsPrime set and m_lod cleared for a sleeping body in calm water.
    bool readWorld(SubstepContext& c);
    /// Gate. Reads the water's time (s), gravity (m/s²) and frame, and the body's pose, centre of mass and bounding
    /// sphere in that frame (c.pose, c.com, c.bc in m, c.br in m); a new frame clears the records and warm starts.
    /// False, counting a rejected substep and clearing m_lod, for a pose or centre of mass that is not finite.
    bool readBodyPose(SubstepContext& c);
    /// Gate. The water the body is in (design.md 2.9): the unbounded water or the water body chosen
    /// (chooseWaterBody), written to c.water, c.straddling, c.rho (kg/m³), m_activeWater, m_activeDensity,
    /// m_straddling. With water bodies, false (m_needsPrime set, m_lod cleared) for a sleeping body that only calm
    /// water reaches; c.waves then counts only the waters reached.
    bool chooseWater(SubstepContext& c);
    /// Of chooseWater, with water bodies: the water body nearest, whether the body straddles several (then
    /// m_regionsReached and the widest height bounds c.lo, c.hi, m), and resets the records and warm starts when
    /// the water body changed (m_activeWaterBody). Out of line: the single-water path's code stays as it was laid out.
    void chooseWaterBody(SubstepContext& c);
    /// Gate. The water's height bounds over the footprint (c.lo, c.hi, m). False for a dry body (no water, or the
    /// bounding sphere above c.hi): the dry result, the body's own sleeping thresholds pending, m_lod and the last
    /// centre of mass forgotten, submerged fraction 0. True: the body is woken (pending) when the water changes.
    bool bodyReachesWater(SubstepContext& c);
    /// Temporal level of detail (settings.hydrostaticsInterval): begins m_lod's substep (f.lodStep), and either
    /// marks an exact evaluation substep (f.evaluationSubstep) or predicts the hydrostatics and drag (f.predicted,
    /// f.prediction, f.h); otherwise f.h is empty, for evaluateHydrostatics.
    void predictHydrostatics(const SubstepContext& c, SubstepForces& f);
    /// Reads whether the water is flat (f.flat, f.flatH in m) and whether any drag is on (f.dragOn); builds the wave
    /// patch over the footprint when it saves queries (f.patch for the hydrostatics, f.dragPatch for the drag,
    /// the calling thread's scratch) and tells m_lod the water's slope bound (unless predicted).
    void buildWaterPatch(const SubstepContext& c, SubstepForces& f);
    /// Gate. Unless predicted (or buoyancy is off): f.h by the method registry, a closed form in flat water, the
    /// regions of a straddling body or the device backend (f.onDevice); torque about c.com. False, counting a
    /// rejected substep and clearing m_lod, when the evaluation threw.
    bool evaluateHydrostatics(const SubstepContext& c, SubstepForces& f);
    /// Added mass (design.md 2.7): f.m, f.ma, f.meff (kg), the body's gravity f.gravityAcc (m/s²), and the force of
    /// the water's acceleration under changing water (f.waterForce, f.replacedPressure in N, f.waterForceOn).
    void addedMassAndWaterForce(const SubstepContext& c, SubstepForces& f);
    /// Drag (design.md 2.6): the evaluation velocities f.v (m/s), f.w (rad/s), m_linearDamping, and f.dragF (N),
    /// f.dragT (N·m), f.uMean (m/s), f.linearPower (W): extrapolated while the motion follows the prediction,
    /// otherwise computed (device backend or computeDrag); m_lastMeanWaterVelocity unless predicted.
    void evaluateDrag(const SubstepContext& c, SubstepForces& f);
    /// At an exact evaluation substep of the temporal level of detail: records f.h, the drag and the velocities
    /// into m_lod.
    void recordTemporalLevelOfDetail(const SubstepContext& c, const SubstepForces& f);
    /// Implicit drag (design.md 2.6): scales f.dragF and f.dragT so the velocity after the impulse is the one the
    /// drag was evaluated at; updates m_linearShare from a computed drag.
    void implicitDragScale(const SubstepContext& c, SubstepForces& f);
    /// The impulses of the substep, f.linearImpulse (N·s) and f.angularImpulse (N·m·s), water frame: hydrostatics
    /// (twice when priming), added mass and its growth (reads m_result.addedMass, the last substep's), the water's
    /// acceleration and the drag.
    void computeImpulses(const SubstepContext& c, SubstepForces& f);
    /// Writes m_result (world frame; not yet .applied nor the impulses, which applyPending writes) and
    /// m_submergedFraction.
    void recordResult(const SubstepContext& c, const SubstepForces& f);
    /// The impulses in the world frame (through the marine model when enabled); rejects one that is not finite
    /// (counted, m_lod cleared); otherwise decides rest (m_lastCom) and leaves the sleeping thresholds and the
    /// impulses pending for applyPending.
    void decideImpulseAndSleep(const SubstepContext& c, const SubstepForces& f);
    ///@}
    /// The drag sum at velocities (v, w) with linear damping m_linearDamping; linearPower: the linear damping's part
    /// of its power, W (≤ 0).
    void computeDrag(const Eigen::Isometry3d& pose, const buoyancy::WaterPatch* patch, const Eigen::Vector3d& com,
                     const Eigen::Vector3d& v, const Eigen::Vector3d& w, double density, double time,
                     Eigen::Vector3d& force, Eigen::Vector3d& torque, Eigen::Vector3d& meanWaterVelocity,
                     double& linearPower, bool reuseWater = false);
    /// The added mass of this substep's submerged part (design.md 2.7), kg, per axis of the water frame: across the
    /// water's up (x, z) C_a ρ V_sub; along it (y, heave) at least the waterplane's c_wp ρ A_waterline^(3/2)
    /// (btBuoyancySettings::addedMassWaterplaneCoefficient). Zeros without btBuoyancySettings::addedMass.
    /// @param rho  the water's density, kg/m³
    Eigen::Vector3d addedMassOf(const buoyancy::HydrostaticsResult& h, double rho) const;
    /// linearDampingNow given the depth of the top of the body's bounding sphere under the water (m, ≥ 0).
    double linearDampingAt(const buoyancy::HydrostaticsResult& h, double topDepth) const;
    /// (Re)select the shared drag clusters for the current settings and size the drag workspace.
    void selectDragClusters();
    /// Whole body below the lowest water point of flat water: the closed form from the dry mass properties.
    buoyancy::HydrostaticsResult submergedClosedForm(const Eigen::Isometry3d& pose, double rho, double g,
                                                     const Eigen::Vector3d& com) const;

    /// Build on `body`, or on `rigid` (wrapped in m_rigidBody) when body is null.
    btBuoyancyAction(btRigidBody* rigid, btBuoyancyBody* body, std::shared_ptr<const btBuoyancyShape> shape,
                     btBuoyancyWorld* world, const btBuoyancySettings& settings, const btTransform& meshInCom);

    btBuoyancyRigidBody m_rigidBody;  ///< the btRigidBody constructors' body (wraps nullptr otherwise)
    btBuoyancyBody* m_body;           ///< the body read and written (&m_rigidBody, or the caller's)
    std::shared_ptr<const btBuoyancyShape> m_shape;
    btBuoyancyWorld* m_world;
    const btBuoyantBody* m_owner = nullptr;
    btBuoyancySettings m_settings;
    btTransform m_meshInCom;
    std::uint64_t m_frameVersion = 0;  ///< the world's water-frame version the records were made in
    bool m_outsideWorld = false;  ///< immediate mode: the body need not be in a Bullet world
    btBuoyancyResult m_result;
    std::uint64_t m_lastSubstep = 0;
    /// @name What evaluate decided for the body, written by applyPending (at the action's turn in Bullet's order)
    ///@{
    std::uint64_t m_evaluatedSubstep = 0; ///< the substep evaluate last ran for (0: never)
    bool m_pendingActivate = false;       ///< wake the body
    bool m_pendingSleep = false;          ///< set its sleeping thresholds to m_pendingLinearSleep, m_pendingAngularSleep
    btScalar m_pendingLinearSleep = 0, m_pendingAngularSleep = 0; ///< m/s, rad/s
    bool m_pendingImpulse = false;        ///< apply m_pendingJ (N·s) and m_pendingL (N·m·s)
    btVector3 m_pendingJ = btVector3(0, 0, 0), m_pendingL = btVector3(0, 0, 0);
    ///@}
    std::uint64_t m_rejected = 0;
    /// @name Water events: the submerged fraction set by evaluate, the states advanced by applyPending
    ///@{
    double m_submergedFraction = 0;     ///< getSubmergedFraction
    btBuoyancyWaterState m_waterState;  ///< in water, fully submerged, which water body
    ///@}
    /// @name The water of the current substep: the world's unbounded water, or the water body chosen (design.md 2.9)
    ///@{
    const btWaterSurface* m_activeWater = nullptr; ///< nullptr: no water reaches the body
    double m_activeDensity = 1000.0;               ///< its ρ_w, kg/m³
    int m_activeWaterBody = -1;                    ///< index in btBuoyancyWorld::getWaterBodies(), −1: none
    /// The regions a straddling body reaches this substep (capacity kept: no allocation once grown).
    std::vector<buoyancy::WaterRegion> m_regionsReached;
    /// The body straddles water bodies this substep: pressure from regionHydrostatics, drag per region.
    bool m_straddling = false;
    /// True when the sphere (`centre`, world, m; `radius`, m) is within water body `index`'s region's sides and
    /// reaches no other water body's region.
    bool reachesOnlyWaterBody(std::size_t index, const Eigen::Vector3d& centre, double radius) const;
    /// Append the convex pieces of `body`'s region but their tops and bottoms to m_regionsReached, as half-spaces of
    /// the world's water frame, with its water and density.
    void appendRegionsOf(const btWaterBody& body);
    ///@}
    std::shared_ptr<btBuoyancyDeformable> m_deformable;  ///< re-baked samples of a deformable body
    /// True until the first hydrostatic kick after creation or sleep: Bullet has already applied gravity for
    /// a substep whose buoyancy kick (at the starting pose) was never given; see updateAction.
    bool m_needsPrime = true;
    /// @name Temporal level of detail (settings.hydrostaticsInterval)
    ///@{
    /// The controller: records, interval, checks (temporal/TemporalLevelOfDetail.h).
    buoyancy::TemporalLevelOfDetail m_lod;
    Eigen::Vector3d m_lastMeanWaterVelocity = Eigen::Vector3d::Zero(); ///< of the last computed drag, m/s
    double m_linearDamping = 0;     ///< this substep's linear damping coefficient b (linearDampingNow), m/s
    /// Share of the last computed drag's power that was linear damping (0..1): how the implicit drag solve splits an
    /// extrapolated drag (temporal level of detail) into its linear and quadratic parts.
    double m_linearShare = 0;
    ///@}
    // Workspace sized once (no allocation per substep).
    buoyancy::SampleWorkspace m_ws;
    /// Warm-start memory of the water queries on m_ws's points (hydrostatic samples).
    btWaterQueryCache m_waterCache;
    /// Drag level of detail (design.md 2.5): clusters of the shape's drag samples, and per cluster the water height
    /// (m) and velocity (m/s) of the last drag evaluation that queried them, which the predicted substeps reuse (the
    /// rest of a drag evaluation's arrays is the evaluating thread's scratch).
    std::shared_ptr<const buoyancy::DragClusters> m_drag;
    std::vector<double> m_dh, m_ux, m_uy, m_uz;
    btWaterQueryCache m_dragCache;   ///< warm start of the height and velocity queries at the cluster points
    btWaterQueryCache m_probeCache;  ///< warm start of the velocity queries at the probes
    /// Fewer wave queries (design.md 2.5): the warm start of the per-body grid of water heights (the grid itself is the
    /// evaluating thread's scratch).
    btWaterQueryCache m_patchCache;
    /// The next exact evaluation's patch heights, queried ahead (btBuoyancyWorldPrebuildPatch): used when the patch
    /// then built has the same lattice, time and water, so the results are those of querying them then.
    struct PatchPrebuild {
        bool wanted = false;                     ///< asked for by the last evaluation
        bool ready = false;                      ///< heights queried
        const btWaterSurface* water = nullptr;   ///< the surface the patch is for
        const btWaterSurface* copy = nullptr;    ///< its copy that is queried (btWaterSurface::cloneForQueriesAhead)
        std::uint64_t revision = 0;              ///< the surface's revision when asked for
        double time = 0;                         ///< the water's time, s
        int nodes = 0;                           ///< nodes per side
        buoyancy::WaterPatch::Lattice lattice;   ///< where the nodes are
        std::vector<double> f;                   ///< node heights, m (row by row, WaterPatch::nodePositions)
        btWaterQueryCache cache;                 ///< m_patchCache after the query
    } m_prebuild;
    /// @name Sleeping: Bullet tests the stored velocity, which at rest on the water is +g·dt, not 0 (the kick for
    /// the next substep comes after integration: symplectic Euler, design.md 3), against thresholds that a bobbing
    /// body passes at the top of every bob. In the water the action decides instead, on the body's energy above
    /// its hydrostatic equilibrium, and opens or closes Bullet's thresholds accordingly; out of the water the
    /// body's own thresholds apply again.
    ///@{
    /// Afloat, a body rests when its energy above the hydrostatic equilibrium is below that of a heave moving its
    /// submerged volume by this fraction of it (so it sleeps within 0.1 % of its Archimedes draft, design.md 3).
    static constexpr double kRestVolumeFraction = 1e-3;
    /// Not afloat (under water, on the bottom, in the air), it rests below the kinetic energy of this fraction of
    /// √(g L), L the radius of its bounding sphere (1.6 cm/s for L = 0.25 m).
    static constexpr double kRestSpeedFraction = 1e-2;
    /// The energy below which a body is at rest, J (see kRestVolumeFraction, kRestSpeedFraction).
    double restEnergy(const buoyancy::HydrostaticsResult& h, double mass, const Eigen::Vector3d& gravityAcc) const;
    /// Kinetic energy (from the centre of mass's real motion over the substep and the angular velocity) plus the
    /// energy held by the still unbalanced hydrostatic force and torque, J (design.md 3).
    double energyAboveEquilibrium(const buoyancy::HydrostaticsResult& h, const Eigen::Vector3d& com, double dt,
                                  double mass, const Eigen::Vector3d& gravityAcc) const;
    double m_baseLinearSleep = 0;   ///< the body's linear sleeping threshold when the action was made, m/s
    double m_baseAngularSleep = 0;  ///< the body's angular sleeping threshold when the action was made, rad/s
    Eigen::Vector3d m_lastCom = Eigen::Vector3d::Zero(); ///< COM after the previous wet substep, m
    bool m_hasLastCom = false;      ///< m_lastCom is valid (the previous substep was wet and applied)
    ///@}
    /// @name Marine hydrodynamics (design.md 2.10)
    ///@{
    btMarineHydrodynamics m_marine;
    /// Turn this substep's impulses (J, L: world, N·s, N·m·s, the action's buoyancy and drag for the rigid mass) into
    /// the ones that give the marine model's end-of-step velocity; false when it is not finite (nothing applied).
    bool marineImpulse(const buoyancy::HydrostaticsResult& h, double dt, btVector3& J, btVector3& L);
    std::uint64_t m_marineSubstep = 0;  ///< the substep whose end state is below (0: none)
    buoyancy::Vector6d m_marineVelocity = buoyancy::Vector6d::Zero(); ///< end-of-step velocity [v; ω], world
    Eigen::Matrix3d m_marineRotation = Eigen::Matrix3d::Identity();   ///< body → world at that substep's end
    Eigen::Vector3d m_marineCurrent = Eigen::Vector3d::Zero();        ///< the water velocity used then, m/s, world
    ///@}
};
