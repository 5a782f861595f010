//! Where the arm stands: its base in the world, and the table frame that scenarios, grasps and
//! clearances are computed in.
//!
//! The world is the truth: z up, gravity along −z, the table top a horizontal plane at
//! `scene.table_height`. The arm's `base_link` may sit anywhere, above or below the table top,
//! with any yaw and a tilt (a wedge mount). Nothing here subtracts positions: every change of
//! frame goes through [`Pose`].
//!
//! The **table frame** has its origin on the table top, directly below (or above) the base
//! origin; its z axis points up along the world's z (against gravity), and its x axis is the
//! base's heading (base x projected onto the table). For a level base it is `base_link` shifted
//! along z to the table top, so positions drawn in it are the base-frame x, y of earlier versions.

use fairgrasp_kinematics::Pose;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// The arm's mount and the table frame, each expressed where it is needed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mount {
    /// `base_link` in `world` (`T_world_base`).
    pub base_in_world: Pose,
    /// The table frame in `world` (`T_world_table`).
    pub table_in_world: Pose,
    /// The table frame in `base_link` (`T_base_table`): what a policy that observes in
    /// `base_link` needs to know about "down" and "the table top".
    pub table_in_base: Pose,
}

impl Mount {
    /// The mount of a base at `base_in_world` over a table top at world height
    /// `table_height` \[m\].
    pub fn new(base_in_world: Pose, table_height: f64) -> Mount {
        let origin = base_in_world.xyz();
        let x = base_in_world.transform_vector([1.0, 0.0, 0.0]);
        // The heading is base x projected onto the table; for tilts below 90° it is well defined.
        let heading = x[1].atan2(x[0]);
        let table_in_world = Pose {
            iso: Isometry3::from_parts(
                Translation3::new(origin[0], origin[1], table_height),
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), heading),
            ),
        };
        Mount {
            base_in_world,
            table_in_base: base_in_world.inverse().compose(&table_in_world),
            table_in_world,
        }
    }

    /// Angle between the base's z axis and the world's z axis \[rad\]: 0 for a level base.
    pub fn tilt(&self) -> f64 {
        crate::config::validate::base_tilt(&self.base_in_world)
    }

    /// Height of the base origin above the table top \[m\] (negative: below it).
    pub fn base_height_above_table(&self) -> f64 {
        self.base_in_world.xyz()[2] - self.table_in_world.xyz()[2]
    }

    /// A pose given in the table frame, expressed in `base_link`.
    pub fn table_to_base(&self, pose_in_table: &Pose) -> Pose {
        self.table_in_base.compose(pose_in_table)
    }

    /// A pose given in `base_link`, expressed in the table frame.
    pub fn base_to_table(&self, pose_in_base: &Pose) -> Pose {
        self.table_in_base.inverse().compose(pose_in_base)
    }

    /// Height of a point given in `base_link` above the table top \[m\].
    pub fn height_above_table(&self, p_base: [f64; 3]) -> f64 {
        self.table_in_base.inverse().transform_point(p_base)[2]
    }

    /// The pose, in `base_link`, of a cube of edge `cube_size` \[m\] resting on the table top at
    /// `xy` \[m\] in the table frame, turned by `yaw` \[rad\] about the world vertical (relative to
    /// the base's heading).
    pub fn resting_object_in_base(&self, xy: [f64; 2], yaw: f64, cube_size: f64) -> Pose {
        let on_table = Pose::from_xyz_rpy([xy[0], xy[1], cube_size / 2.0], [0.0, 0.0, yaw]);
        self.table_to_base(&on_table)
    }

    /// Yaw of a pose given in `base_link` about the world vertical, relative to the base's
    /// heading \[rad\]: where its x axis points, projected onto the table top.
    pub fn yaw_on_table(&self, pose_in_base: &Pose) -> f64 {
        let x = self
            .base_to_table(pose_in_base)
            .transform_vector([1.0, 0.0, 0.0]);
        x[1].atan2(x[0])
    }
}
