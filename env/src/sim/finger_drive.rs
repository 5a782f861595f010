//! The gripper's finger drive: the position motor both the simulator and the free-space step use.
//!
//! Each finger slides on a prismatic joint of the palm, `travel` \[m\] from fully open (0) to
//! closed (`finger_travel`), driven by a force-limited spring-damper motor toward a target
//! travel. rapier solves the motor implicitly inside its joint solver; [`FingerState::advance`]
//! integrates the same motor for a finger that touches nothing (implicit Euler, so it is stable
//! at the physics time step), which is all a free-space step needs.

/// Motor stiffness \[N/m\] of each finger.
pub const FINGER_STIFFNESS: f64 = 1.0e4;
/// Motor damping \[N·s/m\] of each finger.
pub const FINGER_DAMPING: f64 = 1.0e2;

/// One finger's closing travel \[m\] and travel rate \[m/s\], relative to the palm.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FingerState {
    pub travel: f64,
    pub rate: f64,
}

/// What moves a free finger during one physics step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FingerDrive {
    /// Target travel \[m\].
    pub target: f64,
    /// Motor force limit \[N\].
    pub max_force: f64,
    /// Finger mass \[kg\].
    pub mass: f64,
    /// Gravity's component along the closing axis \[m/s²\].
    pub gravity_along_axis: f64,
    /// Travel limit \[m\] (the joint's range is `[0, limit]`).
    pub limit: f64,
}

impl FingerState {
    /// The state after one time step `dt` \[s\] of a finger touching nothing: the motor force
    /// `k·(target − travel) − c·rate`, taken at the end of the step and clamped to the force
    /// limit, plus gravity along the axis; the travel stops at the joint limits.
    pub fn advance(self, drive: &FingerDrive, dt: f64) -> FingerState {
        let (k, c, m) = (FINGER_STIFFNESS, FINGER_DAMPING, drive.mass);
        let spring = k * (drive.target - self.travel);
        // Implicit: m (v' − v)/dt = k (x* − x − v' dt) − c v' + m g.
        let implicit =
            (m * self.rate / dt + spring + m * drive.gravity_along_axis) / (m / dt + k * dt + c);
        let motor = spring - (k * dt + c) * implicit;
        let rate = if motor.abs() <= drive.max_force {
            implicit
        } else {
            self.rate + dt * (drive.max_force.copysign(motor) / m + drive.gravity_along_axis)
        };
        let travel = self.travel + dt * rate;
        if travel < 0.0 || travel > drive.limit {
            FingerState {
                travel: travel.clamp(0.0, drive.limit),
                rate: 0.0,
            }
        } else {
            FingerState { travel, rate }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 1.0 / 240.0;

    fn drive(target: f64) -> FingerDrive {
        FingerDrive {
            target,
            max_force: 5.0,
            mass: 0.05,
            gravity_along_axis: 0.0,
            limit: 0.0425,
        }
    }

    #[test]
    fn a_closing_finger_accelerates_at_the_force_limit_then_settles_on_the_target() {
        let mut s = FingerState::default();
        let d = drive(0.03);
        s = s.advance(&d, DT);
        // Far from the target the motor saturates: v = F/m · dt.
        assert!((s.rate - 5.0 / 0.05 * DT).abs() < 1e-9, "{s:?}");
        for _ in 0..240 {
            s = s.advance(&d, DT);
        }
        assert!((s.travel - 0.03).abs() < 1e-5, "{s:?}");
        assert!(s.rate.abs() < 1e-4, "{s:?}");
    }

    #[test]
    fn the_travel_stops_at_the_joint_limits() {
        let mut s = FingerState {
            travel: 0.04,
            rate: 0.5,
        };
        for _ in 0..10 {
            s = s.advance(&drive(0.0425), DT);
            assert!((0.0..=0.0425).contains(&s.travel), "{s:?}");
        }
        let mut s = FingerState::default();
        s = s.advance(&drive(0.0), DT);
        assert_eq!(s, FingerState::default());
    }

    #[test]
    fn gravity_along_the_axis_offsets_the_hold_by_m_g_over_k() {
        let mut s = FingerState {
            travel: 0.02,
            rate: 0.0,
        };
        let mut d = drive(0.02);
        d.gravity_along_axis = -9.81;
        for _ in 0..480 {
            s = s.advance(&d, DT);
        }
        let sag = 0.05 * 9.81 / FINGER_STIFFNESS;
        assert!((s.travel - (0.02 - sag)).abs() < 1e-7, "{s:?}");
    }
}
