//! The vehicle's envelope, re-evaluated from the plan file (the planner's twins are
//! `team::depth`, `team::climb`, `team::cruise`), with the limits the plan is held to:
//!
//! * **depth rating**: every waypoint keeps z ≥ −`auv.max_depth` (the path between waypoints is
//!   their straight segment, so the waypoints suffice); margin max_depth + z, metres.
//! * **flight-path angle**: every velocity through the water (the plan's V) keeps
//!   |V_z| ≤ tan(`auv.max_flight_path_angle`)·‖V_h‖, and from step 1 on climbs at most
//!   V_z ≤ `auv.climb_per_speed`·(‖V_h‖ − `auv.level_speed`) while the cruise floor is on;
//!   margin the least difference, m/s.
//! * **cruise floor** (with `auv.min_speed` > 0): every velocity from step 1 on keeps
//!   ‖V_h‖ ≥ min_speed, and so does every point between two of them: under the zero-order hold
//!   V_h runs along the straight line between consecutive velocities, so the least speed on a
//!   segment is the distance from the origin to that line segment. The first segment of a
//!   window whose start is slower than the floor (the mission's start at rest) is the ramp up
//!   to cruise and is not checked between its ends. Margin: speed − min_speed, m/s.

use super::run::{at, seg, Checker, Family};
use super::{FamilyResult, LENGTH_TOL, SPEED_TOL};

/// The least norm of the points of the segment from `a` to `b` (2-D).
pub fn least_on_segment(a: [f64; 2], b: [f64; 2]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1]];
    let dd = d[0] * d[0] + d[1] * d[1];
    let t = if dd > 0.0 {
        (-(a[0] * d[0] + a[1] * d[1]) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a[0] + t * d[0]).hypot(a[1] + t * d[1])
}

impl Checker<'_> {
    pub(super) fn envelope(&self) -> Vec<FamilyResult> {
        let mut fd = Family::new("depth rating", "m", LENGTH_TOL);
        let mut fg = Family::new("flight-path angle", "m/s", SPEED_TOL);
        let mut fc = Family::new("cruise floor", "m/s", SPEED_TOL);
        let auv = &self.limits.auv;
        // from NO_ANGLE_LIMIT on, no angle limit (a vehicle that moves vertically at rest)
        let limited = auv.max_flight_path_angle < crate::scenario::NO_ANGLE_LIMIT;
        let slope = auv.max_flight_path_angle.tan();
        let floor = auv.min_speed;
        for (w, pre, _, n, a) in self.auv_paths() {
            let who = format!("{pre}AUV {n}");
            for (k, p) in a.position.iter().enumerate().take(self.k.saturating_add(1)) {
                fd.record(auv.max_depth + p[2], || {
                    at(w, k, &format!("{who}: z = {:.3} m", p[2]))
                });
            }
            let v = &a.velocity;
            for (k, v) in v.iter().enumerate().take(self.k.saturating_add(1)) {
                let h = v[0].hypot(v[1]);
                let climb = if k >= 1 && floor > 0.0 {
                    // a speed below the floor is the cruise family's, not this one's
                    auv.climb_per_speed * (h.max(floor) - auv.level_speed.min(floor)) - v[2]
                } else {
                    f64::INFINITY // the window's start: at rest, or the last window's end
                };
                let angle_margin = if limited {
                    slope * h - v[2].abs()
                } else {
                    f64::INFINITY
                };
                let margin = angle_margin.min(climb);
                if margin == f64::INFINITY {
                    continue; // neither the angle nor the climb line applies here
                }
                fg.record(margin, || {
                    let angle = v[2].atan2(h).to_degrees();
                    at(
                        w,
                        k,
                        &format!("{who}: flight-path angle {angle:.2}° at {h:.3} m/s"),
                    )
                });
            }
            if floor <= 0.0 {
                continue;
            }
            for k in 1..=self.k.min(v.len().saturating_sub(1)) {
                let (va, vb) = ([v[k - 1][0], v[k - 1][1]], [v[k][0], v[k][1]]);
                let speed = vb[0].hypot(vb[1]);
                fc.record(speed - floor, || {
                    at(w, k, &format!("{who}: horizontal speed {speed:.4} m/s"))
                });
                if k == 1 && va[0].hypot(va[1]) < floor {
                    continue; // the ramp from a slower start
                }
                let least = least_on_segment(va, vb);
                fc.record(least - floor, || {
                    seg(
                        w,
                        k,
                        &format!("{who}: {least:.4} m/s between the waypoints"),
                    )
                });
            }
        }
        vec![fd.finish(), fg.finish(), fc.finish()]
    }
}
