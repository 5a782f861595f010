//! A wrench (force and torque about a point) and what a six-axis sensor's user computes from
//! one: the centre of pressure of a press on a plane below the sensor, and the wrench in another
//! frame.

use fairgrasp_kinematics::Pose;

/// A force \[N\] and a torque \[N·m\] about a point, both in one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Wrench {
    pub force: [f64; 3],
    pub torque: [f64; 3],
}

impl Wrench {
    /// The same wrench in the frame `frame` is expressed in (force and torque rotated by the
    /// inverse of `frame`'s rotation; the point the torque is taken about is unchanged). E.g.
    /// with `frame` = the sensor's pose in `base_link`, a `base_link` wrench becomes the
    /// sensor's own reading.
    pub fn in_frame(&self, frame: &Pose) -> Wrench {
        let inverse = frame.inverse();
        Wrench {
            force: inverse.transform_vector(self.force),
            torque: inverse.transform_vector(self.torque),
        }
    }

    /// Where a press acts on a plane `depth` \[m\] below the point the torque is taken about
    /// (along −z of the wrench's frame, which must have z up): the contact point `(x, y)` \[m\]
    /// relative to that point, for one contact (or the centre of pressure of several) on that
    /// plane. With `r = (x, y, −depth)` and `M = r × F`: `x = −(M_y + depth·F_x) / F_z`,
    /// `y = (M_x − depth·F_y) / F_z`. `None` while the vertical force is below `min_force` \[N\]
    /// (the point is then noise).
    pub fn centre_of_pressure(&self, depth: f64, min_force: f64) -> Option<[f64; 2]> {
        let [fx, fy, fz] = self.force;
        let [mx, my, _] = self.torque;
        (fz.abs() >= min_force && fz.is_finite())
            .then(|| [-(my + depth * fx) / fz, (mx - depth * fy) / fz])
    }
}
