//! The physics state a soft reset restores: every rapier set, cloned once after the build.

use rapier3d::prelude::*;

/// The cloneable part of the physics state, restored by a soft reset.
#[derive(Clone)]
pub struct Snapshot {
    islands: IslandManager,
    broad_phase: BroadPhaseBvh,
    narrow_phase: NarrowPhase,
    bodies: RigidBodySet,
    colliders: ColliderSet,
    impulse_joints: ImpulseJointSet,
    multibody_joints: MultibodyJointSet,
    ccd_solver: CCDSolver,
}

impl Snapshot {
    pub fn take(w: &PhysicsWorld) -> Self {
        Snapshot {
            islands: w.islands.clone(),
            broad_phase: w.broad_phase.clone(),
            narrow_phase: w.narrow_phase.clone(),
            bodies: w.bodies.clone(),
            colliders: w.colliders.clone(),
            impulse_joints: w.impulse_joints.clone(),
            multibody_joints: w.multibody_joints.clone(),
            ccd_solver: w.ccd_solver.clone(),
        }
    }

    pub fn restore(&self, w: &mut PhysicsWorld) {
        w.islands = self.islands.clone();
        w.broad_phase = self.broad_phase.clone();
        w.narrow_phase = self.narrow_phase.clone();
        w.bodies = self.bodies.clone();
        w.colliders = self.colliders.clone();
        w.impulse_joints = self.impulse_joints.clone();
        w.multibody_joints = self.multibody_joints.clone();
        w.ccd_solver = self.ccd_solver.clone();
    }
}
