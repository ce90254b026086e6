//! Obstacles beyond the AUV paths (whose samples `floor` tests): the USV's path and the planned
//! acoustic links may not cross an obstacle cell (NODATA or land) either, and a link over one
//! has no line of sight (used by the connectivity family of `graph`).
//!
//! A path or link is sampled by the checker's own 𝓛_r rule (`run::own_samples`, as the AUV
//! segments) and every sample is tested with `Seafloor::obstacle`; a sample off the grid counts
//! as an obstacle.

use super::graph::{link_name, node};
use super::run::{own_samples, seg, Checker, Family};

impl Checker<'_> {
    /// Why the segment p → q crosses an obstacle: the first such sample, where and what it is
    /// over. None when every sample is clear.
    pub(super) fn crossing(&self, p: [f64; 3], q: [f64; 3]) -> Option<String> {
        let r = self.resolution();
        let Some(samples) = own_samples(p, q, r) else {
            return Some(format!("the segment cannot be sampled at r = {r} m"));
        };
        for (i, s) in samples.enumerate() {
            let what = match self.floor.obstacle(s[0], s[1]) {
                Ok(None) => continue,
                Ok(Some(o)) => o.to_string(),
                Err(e) => e.to_string(),
            };
            return Some(format!(
                "sample {i} at ({:.2}, {:.2}, {:.2}) is {what}",
                s[0], s[1], s[2]
            ));
        }
        None
    }

    /// Records every sample of p → q in the obstacle family `f` (margin −1 over an obstacle or
    /// off the grid, 0 when clear); `who` names the segment.
    fn record_samples(&self, f: &mut Family, p: [f64; 3], q: [f64; 3], who: impl Fn() -> String) {
        let r = self.resolution();
        let Some(samples) = own_samples(p, q, r) else {
            f.record(f64::NEG_INFINITY, || {
                format!("{}: cannot sample this segment at r = {r} m", who())
            });
            return;
        };
        for (i, s) in samples.enumerate() {
            let what = match self.floor.obstacle(s[0], s[1]) {
                Ok(None) => None,
                Ok(Some(o)) => Some(o.to_string()),
                Err(e) => Some(e.to_string()),
            };
            f.record(if what.is_some() { -1.0 } else { 0.0 }, || {
                format!(
                    "{}: sample {i} at ({:.2}, {:.2}, {:.2}) is {}",
                    who(),
                    s[0],
                    s[1],
                    s[2],
                    what.as_deref().unwrap_or("clear")
                )
            });
        }
    }

    /// The USV's segments (every stage) and the planned links of k = 1..=K (final stage) in the
    /// obstacle family.
    pub(super) fn usv_and_link_obstacles(&self, f: &mut Family) {
        for (w, pre, st) in self.stages() {
            let p = &st.usv.position;
            for k in 1..=self.k.min(p.len().saturating_sub(1)) {
                let (a, b) = (p[k - 1], p[k]);
                self.record_samples(f, [a[0], a[1], 0.0], [b[0], b[1], 0.0], || {
                    seg(w, k, &format!("{pre}USV"))
                });
            }
        }
        for (w, win) in self.plan.windows.iter().enumerate() {
            let st = &win.final_;
            for (k, links) in win.links.links.iter().enumerate().skip(1) {
                if k > self.k {
                    break;
                }
                for x in links {
                    // a link naming no vehicle is the structure family's
                    let (Some(p), Some(q)) = (node(st, Some(x.a), k), node(st, x.b, k)) else {
                        continue;
                    };
                    self.record_samples(f, p, q, || {
                        format!("window {w}, k = {k}, {}", link_name(x))
                    });
                }
            }
        }
    }
}
