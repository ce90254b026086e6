//! The seafloor families: the floor is the one the plan was made on (identity), and every
//! vehicle stays over the grid, clear of the floor (C2_2 at waypoints and along segments) and
//! of obstacles.

use super::run::{at, own_samples, seg, Checker, Family};
use super::{FamilyResult, FLOOR_TOL};

impl Checker<'_> {
    // ------------------------------------------------------------------------------------
    // 9. seafloor identity
    // ------------------------------------------------------------------------------------
    pub(super) fn identity(&self) -> FamilyResult {
        let mut f = Family::new("seafloor identity", "mismatches", 0.0);
        let r = &self.plan.seafloor;
        let found = self.floor.fingerprint();
        let same = found == r.fingerprint;
        f.record(if same { 0.0 } else { -1.0 }, || {
            if same {
                format!("fingerprint {found} matches")
            } else {
                format!(
                    "this is not the floor the plan was made on: fingerprint {} (plan) vs {found} \
                     (floor)",
                    r.fingerprint
                )
            }
        });
        let (z_min, z_max) = self.floor.z_range();
        let l = &r.lattice;
        for (name, plan, floor) in [
            ("nx", l.nx as f64, self.floor.nx() as f64),
            ("ny", l.ny as f64, self.floor.ny() as f64),
            ("x0", l.x0, self.floor.x0()),
            ("y0", l.y0, self.floor.y0()),
            ("dx", l.dx, self.floor.dx()),
            ("dy", l.dy, self.floor.dy()),
            ("z_min", r.z_min, z_min),
            ("z_max", r.z_max, z_max),
        ] {
            f.record(if plan == floor { 0.0 } else { -1.0 }, || {
                format!("seafloor record {name} = {plan}, the floor has {floor}")
            });
        }
        f.finish()
    }

    // ------------------------------------------------------------------------------------
    // 6. floor (C2_2 at waypoints and along segments, grid, obstacles)
    // ------------------------------------------------------------------------------------
    pub(super) fn floor(&self) -> Vec<FamilyResult> {
        let mut fg = Family::new("inside the seafloor grid", "m", 0.0);
        let mut fw = Family::new("C2_2 floor clearance (waypoints)", "m", FLOOR_TOL);
        let mut fs = Family::new("C2_2 floor clearance (segments)", "m", FLOOR_TOL);
        let mut fo = Family::new("no obstacle (NODATA/land)", "samples", 0.0);
        let eps = self.limits.auv.floor_clearance;
        let r = self.resolution();
        let e = self.floor.extent();
        for (w, pre, _, n, a) in self.auv_paths() {
            let who = format!("{pre}AUV {n}");
            for (k, p) in a.position.iter().enumerate().take(self.k.saturating_add(1)) {
                fg.record(inside(&e, p[0], p[1]), || {
                    at(w, k, &format!("{who} at ({}, {})", p[0], p[1]))
                });
                match self.floor.elevation(p[0], p[1]) {
                    Ok(z) => fw.record(p[2] - z - eps, || {
                        at(w, k, &format!("{who}: z = {}, floor {z}", p[2]))
                    }),
                    Err(err) => fw.record(f64::NEG_INFINITY, || at(w, k, &format!("{who}: {err}"))),
                }
            }
            for k in 1..=self.k.min(a.position.len()) {
                let (Some(pa), Some(pb)) = (a.position.get(k - 1), a.position.get(k)) else {
                    continue;
                };
                let (pa, pb) = (*pa, *pb);
                // the seafloor's own 𝓛_r query
                match self.floor.segment_clearance(pa, pb, r) {
                    Ok(c) => fs.record(c.min_clearance - eps, || {
                        seg(
                            w,
                            k,
                            &format!(
                                "{who}: clearance {:.4} m at ({:.2}, {:.2}, {:.2})",
                                c.min_clearance, c.at[0], c.at[1], c.at[2]
                            ),
                        )
                    }),
                    Err(err) => {
                        fs.record(f64::NEG_INFINITY, || seg(w, k, &format!("{who}: {err}")))
                    }
                }
                // and our own sampling of the same rule, which also tests every sample for
                // obstacles: n = max(1, ⌈horizontal length / r⌉) intervals, endpoints included
                let Some(samples) = own_samples(pa, pb, r) else {
                    fo.record(f64::NEG_INFINITY, || {
                        seg(
                            w,
                            k,
                            &format!("{who}: cannot sample this segment at r = {r} m"),
                        )
                    });
                    continue;
                };
                for (i, q) in samples.enumerate() {
                    if !self.floor.contains(q[0], q[1]) {
                        continue; // reported by the grid family at the endpoints
                    }
                    match self.floor.elevation(q[0], q[1]) {
                        Ok(z) => fs.record(q[2] - z - eps, || {
                            seg(
                                w,
                                k,
                                &format!(
                                    "{who}: sample {i} at ({:.2}, {:.2}, {:.2}), floor {z:.3}",
                                    q[0], q[1], q[2]
                                ),
                            )
                        }),
                        Err(err) => {
                            fs.record(f64::NEG_INFINITY, || seg(w, k, &format!("{who}: {err}")))
                        }
                    }
                    let obstacle = self.floor.is_obstacle(q[0], q[1]).unwrap_or(true);
                    fo.record(if obstacle { -1.0 } else { 0.0 }, || {
                        let what = if obstacle {
                            "over NODATA or land"
                        } else {
                            "clear"
                        };
                        seg(
                            w,
                            k,
                            &format!("{who}: sample {i} at ({:.2}, {:.2}) is {what}", q[0], q[1]),
                        )
                    });
                }
            }
        }
        // the USV's waypoints are over the grid too, and its path and the planned links clear
        // of obstacles
        for (w, pre, st) in self.stages() {
            for (k, p) in st
                .usv
                .position
                .iter()
                .enumerate()
                .take(self.k.saturating_add(1))
            {
                fg.record(inside(&e, p[0], p[1]), || {
                    at(w, k, &format!("{pre}USV at ({}, {})", p[0], p[1]))
                });
            }
        }
        self.usv_and_link_obstacles(&mut fo);
        vec![fg.finish(), fw.finish(), fs.finish(), fo.finish()]
    }
}

/// Signed distance of (x, y) inside the extent `e` (negative outside; NaN for a non-finite
/// point: f64::min would hide a NaN).
fn inside(e: &crate::seafloor::Extent, x: f64, y: f64) -> f64 {
    if x.is_finite() && y.is_finite() {
        (x - e.x_min)
            .min(e.x_max - x)
            .min(y - e.y_min)
            .min(e.y_max - y)
    } else {
        f64::NAN
    }
}
