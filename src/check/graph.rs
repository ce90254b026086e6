//! The families of Steps 2 and 3: the A2U link and the A2A path of every step, the link bands
//! and lengths, the acoustic connectivity of the team and the line of sight of the planned
//! chain. Written from the paper (P3, P4, C5_2/C5_3, C1_13 and Algorithm 1, lines 18–22) and the
//! plan format; nothing here calls `crate::graph` or the planner.
//!
//! A node is the USV (at its planned (x, y) and z = 0) or an AUV. A link has *line of sight*
//! when every sample of 𝓛_r on the segment (`Seafloor::segment_clearance` at
//! `scenario.acoustic.resolution`) is at or above the floor within [`LOS_TOL`] and none is over
//! an obstacle cell, NODATA or land (`obstacles`); a link whose end is outside the grid has
//! none.
//!
//! A plan whose windows all have an empty `graph.a2u` (no Step 2 data: a planner that runs
//! Step 1 only) skips these families: each is a PASS row with 0 checks and the note
//! "no Step 2 graph in this plan". A plan in which some windows have a graph and others do not
//! fails the structure family, and the windows without one are skipped here.

use super::run::{at, diff, Checker, Family};
use super::*;
use crate::plan::{Link, Stage, Window};
use crate::seafloor::SegmentClearance;

/// The note of a skipped family.
const SKIP_NOTE: &str = "no Step 2 graph in this plan";

/// Position of a node at step k of a stage: the USV (`None`) at the surface, or AUV `n`.
pub(super) fn node(st: &Stage, who: Option<usize>, k: usize) -> Option<[f64; 3]> {
    match who {
        None => st.usv.position.get(k).map(|p| [p[0], p[1], 0.0]),
        Some(n) => st.auvs.get(n)?.position.get(k).copied(),
    }
}

fn node_name(who: Option<usize>) -> String {
    who.map_or("USV".into(), |n| format!("AUV {n}"))
}

pub(super) fn link_name(l: &Link) -> String {
    match l.b {
        None => format!("A2U link AUV {}–USV", l.a),
        Some(b) => format!("A2A link AUV {}–AUV {b}", l.a),
    }
}

/// The same link, either way round.
fn same_link(x: &Link, y: &Link) -> bool {
    (x.a == y.a && x.b == y.b)
        || matches!((x.b, y.b), (Some(xb), Some(yb)) if x.a == yb && xb == y.a)
}

/// What keeps the A2A edges `edges` from being a Hamiltonian path over AUVs 0..n (empty when
/// they are one): N − 1 distinct edges between distinct AUVs < N, every degree ≤ 2, no cycle,
/// connected.
pub(super) fn path_problems(edges: &[[usize; 2]], n: usize) -> Vec<String> {
    let mut problems = Vec::new();
    if edges.len() + 1 != n {
        problems.push(format!(
            "{} edges, a path through N = {n} AUVs has N − 1",
            edges.len()
        ));
    }
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut degree = vec![0usize; n];
    let mut seen: Vec<[usize; 2]> = Vec::new();
    for &[i, j] in edges {
        if i >= n || j >= n {
            problems.push(format!("edge [{i}, {j}] names an AUV ≥ N = {n}"));
            continue;
        }
        if i == j {
            problems.push(format!("edge [{i}, {j}] is a loop"));
            continue;
        }
        let e = [i.min(j), i.max(j)];
        if seen.contains(&e) {
            problems.push(format!("edge [{i}, {j}] is repeated"));
            continue;
        }
        seen.push(e);
        degree[i] += 1;
        degree[j] += 1;
        let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
        if ri == rj {
            problems.push(format!("edge [{i}, {j}] closes a cycle"));
        } else {
            parent[ri] = rj;
        }
    }
    for (i, d) in degree.iter().enumerate() {
        if *d > 2 {
            problems.push(format!("AUV {i} has degree {d} > 2"));
        }
    }
    if n > 0 {
        let r0 = root(&mut parent, 0);
        let cut: Vec<usize> = (1..n).filter(|&i| root(&mut parent, i) != r0).collect();
        if !cut.is_empty() {
            problems.push(format!(
                "not connected: AUVs {cut:?} unreachable from AUV 0"
            ));
        }
    }
    problems
}

/// What keeps `links` from being [A2U link of `a2u`] followed by the A2A edges `edges` (any order,
/// either way round); empty when it is.
fn links_problems(links: &[Link], a2u: Option<usize>, edges: &[[usize; 2]]) -> Vec<String> {
    let mut problems = Vec::new();
    match (links.first(), a2u) {
        (Some(l), Some(a)) if l.b.is_none() && l.a == a => {}
        (first, a) => problems.push(format!(
            "the first link is {}, graph.a2u gives the A2U link AUV {}–USV",
            first.map_or("missing".into(), link_name),
            a.map_or("?".into(), |a| a.to_string())
        )),
    }
    let rest = links.get(1..).unwrap_or_default();
    let as_link = |e: &[usize; 2]| Link {
        a: e[0],
        b: Some(e[1]),
    };
    for e in edges {
        let count = rest.iter().filter(|l| same_link(l, &as_link(e))).count();
        if count != 1 {
            problems.push(format!(
                "A2A edge [{}, {}] appears {count} times among the links",
                e[0], e[1]
            ));
        }
    }
    for l in rest {
        if !edges.iter().any(|e| same_link(l, &as_link(e))) {
            problems.push(format!("{} is not an edge of graph.a2a", link_name(l)));
        }
    }
    problems
}

impl Checker<'_> {
    /// Line of sight of the segment p → q (see the module docs).
    pub(super) fn los(&self, p: [f64; 3], q: [f64; 3]) -> Result<SegmentClearance, String> {
        self.floor
            .segment_clearance(p, q, self.resolution())
            .map_err(|e| e.to_string())
    }

    /// Structure of window `w`'s graph and link report: lengths K + 1, indices < N, bands
    /// parallel to the links.
    pub(super) fn graph_structure(&mut self, w: usize, win: &Window) {
        let (g, l) = (&win.graph, &win.links);
        let n = self.s.team.auvs;
        let k1 = self.k.saturating_add(1);
        if g.a2u.is_empty() {
            let other = self
                .plan
                .windows
                .iter()
                .position(|v| !v.graph.a2u.is_empty());
            self.require(other.is_none(), || {
                format!(
                    "window {w} has no Step 2 graph (graph.a2u is empty), window {} has one",
                    other.unwrap_or_default()
                )
            });
            let bare = g.a2a.is_empty() && l.links.is_empty() && l.out_of_band.is_empty();
            self.require(bare, || {
                format!("window {w}: A2A edges or links recorded but graph.a2u is empty")
            });
            return;
        }
        let (a2u, a2a) = (g.a2u.len(), g.a2a.len());
        self.require(a2u == k1, || {
            format!("window {w}: graph.a2u has {a2u} entries, expected K + 1 = {k1}")
        });
        self.require(a2a == k1, || {
            format!("window {w}: graph.a2a has {a2a} entries, expected K + 1 = {k1}")
        });
        let bad = g
            .a2u
            .iter()
            .chain(g.a2a.iter().flatten().flatten())
            .find(|&&i| i >= n);
        self.require(bad.is_none(), || {
            format!(
                "window {w}: the graph names AUV {} ≥ N = {n}",
                bad.unwrap_or(&0)
            )
        });
        if l.links.is_empty() {
            return; // reported by the link families
        }
        let links = l.links.len();
        self.require(links == k1, || {
            format!("window {w}: links.links has {links} entries, expected K + 1 = {k1}")
        });
        let bad = |x: &Link| x.a >= n || x.b.is_some_and(|b| b >= n);
        let bad_link = l
            .links
            .iter()
            .flatten()
            .chain(l.out_of_band.iter().map(|o| &o.link))
            .find(|x| bad(x))
            .copied();
        self.require(bad_link.is_none(), || {
            format!(
                "window {w}: {} names an AUV ≥ N = {n}",
                bad_link.as_ref().map_or(String::new(), link_name)
            )
        });
        let parallel = l.bands.len() == l.links.len()
            && l.bands
                .iter()
                .zip(&l.links)
                .all(|(b, x)| b.len() == x.len());
        self.require(parallel, || {
            format!("window {w}: links.bands is not parallel to links.links")
        });
        let big_k = self.k;
        let late = l.out_of_band.iter().find(|o| o.k > big_k).map(|o| o.k);
        self.require(late.is_none(), || {
            format!(
                "window {w}: out_of_band names step {} > K = {big_k}",
                late.unwrap_or_default()
            )
        });
    }

    /// The six families of Steps 2 and 3, in table order.
    pub(super) fn graph_families(&self) -> Vec<FamilyResult> {
        let mut fh = Family::new("A2A Hamiltonian path", "problems", 0.0);
        let mut fa = Family::new("A2U link", "m", A2U_TIE_TOL);
        let mut fb = Family::new("link bands within [0, ρ·d_s]", "m", BAND_LIMIT_TOL);
        let mut fl = Family::new("links in band", "m", BAND_TOL);
        let mut fc = Family::new(
            "acoustic connectivity (range + line of sight)",
            "AUVs cut off",
            0.0,
        );
        let mut fs = Family::new("planned chain line of sight", "m", LOS_TOL);
        let n = self.s.team.auvs;
        let mut any = false;
        for (w, win) in self.plan.windows.iter().enumerate() {
            if win.graph.a2u.is_empty() {
                continue;
            }
            any = true;
            // N is trusted (it sizes the checks) only when both stages have N AUVs; otherwise
            // the structure family has failed and these checks would say nothing new
            if win.final_.auvs.len() != n || win.step1.auvs.len() != n {
                for f in [&mut fh, &mut fa, &mut fb, &mut fl, &mut fc, &mut fs] {
                    f.record(f64::NEG_INFINITY, || {
                        format!("window {w}: the stages do not have team.auvs = {n} AUVs")
                    });
                }
                continue;
            }
            self.hamiltonian(&mut fh, w, win);
            self.a2u(&mut fa, w, win);
            self.bands(&mut fb, w, win);
            self.in_band(&mut fl, w, win);
            self.connectivity(&mut fc, w, win);
            self.chain_los(&mut fs, w, win);
        }
        if fc.passing() && fc.checked > 0 {
            fc.where_ = format!("every AUV reaches the USV at all {} steps", fc.checked);
        }
        let mut out = vec![fh, fa, fb, fl, fc, fs];
        if !any {
            for f in &mut out {
                f.where_ = SKIP_NOTE.into();
            }
        }
        out.into_iter().map(Family::finish).collect()
    }

    /// Steps of window `win` at which its positions can be read: k = 0..=K, cut to the final
    /// stage's USV path (the structure family reports a short one).
    fn steps(&self, win: &Window) -> usize {
        self.k.saturating_add(1).min(win.final_.usv.position.len())
    }

    // ------------------------------------------------------------------------------------
    // P4: the A2A edges form a Hamiltonian path; the links are the A2U link and those edges
    // ------------------------------------------------------------------------------------
    fn hamiltonian(&self, f: &mut Family, w: usize, win: &Window) {
        let (g, links) = (&win.graph, &win.links.links);
        let n = self.s.team.auvs;
        for k in 0..self.steps(win) {
            let Some(edges) = g.a2a.get(k) else {
                f.record(f64::NEG_INFINITY, || at(w, k, "no A2A edges recorded"));
                continue;
            };
            let problems = path_problems(edges, n);
            f.record(-(problems.len() as f64), || {
                let what = if problems.is_empty() {
                    "a Hamiltonian path".to_string()
                } else {
                    problems.join("; ")
                };
                at(w, k, &format!("A2A edges {edges:?}: {what}"))
            });
            if links.is_empty() {
                continue; // the link families report the missing link report
            }
            let Some(planned) = links.get(k) else {
                f.record(f64::NEG_INFINITY, || at(w, k, "no links recorded"));
                continue;
            };
            let problems = links_problems(planned, g.a2u.get(k).copied(), edges);
            f.record(-(problems.len() as f64), || {
                let what = if problems.is_empty() {
                    "links = A2U link + A2A edges".to_string()
                } else {
                    problems.join("; ")
                };
                at(w, k, &what)
            });
        }
    }

    // ------------------------------------------------------------------------------------
    // P3: the A2U link is the AUV nearest the USV, in Step 1's positions
    // ------------------------------------------------------------------------------------
    fn a2u(&self, f: &mut Family, w: usize, win: &Window) {
        let st = &win.step1;
        let n = self.s.team.auvs;
        for (k, &a) in win
            .graph
            .a2u
            .iter()
            .enumerate()
            .take(self.k.saturating_add(1))
        {
            let Some(usv) = node(st, None, k) else {
                continue; // structure
            };
            let dist: Option<Vec<f64>> = (0..n)
                .map(|i| node(st, Some(i), k).map(|p| diff(p, usv)))
                .collect();
            let Some(dist) = dist else { continue };
            let Some(&da) = dist.get(a) else {
                f.record(f64::NEG_INFINITY, || {
                    at(w, k, &format!("graph.a2u = {a} is not an AUV (N = {n})"))
                });
                continue;
            };
            let (nearest, dmin) =
                dist.iter()
                    .copied()
                    .enumerate()
                    .fold((a, da), |b, (i, d)| if d < b.1 { (i, d) } else { b });
            f.record(dmin - da, || {
                let tail = if nearest == a {
                    "the nearest".to_string()
                } else {
                    format!("AUV {nearest} is nearer at {dmin:.6} m")
                };
                at(
                    w,
                    k,
                    &format!("A2U link AUV {a} at {da:.6} m from the USV (Step 1); {tail}"),
                )
            });
        }
    }

    // ------------------------------------------------------------------------------------
    // C5_2/C5_3 bands: 0 ≤ lo ≤ hi ≤ ρ·d_s, ρ the margin the plan claims (link_margin)
    // ------------------------------------------------------------------------------------
    fn bands(&self, f: &mut Family, w: usize, win: &Window) {
        let rho = self.s.acoustic.link_margin;
        let top = rho * self.limits.acoustic.sonar_range;
        let l = &win.links;
        for (k, (bands, links)) in l.bands.iter().zip(&l.links).enumerate() {
            for (b, link) in bands.iter().zip(links) {
                let margin = b.lo.min(b.hi - b.lo).min(top - b.hi);
                // f64::min drops a NaN: test it separately
                let margin = if b.lo.is_nan() || b.hi.is_nan() || !(rho > 0.0 && rho <= 1.0) {
                    f64::NAN
                } else {
                    margin
                };
                f.record(margin, || {
                    at(
                        w,
                        k,
                        &format!(
                            "{}: band [{}, {}], ρ·d_s = {top} (link_margin ρ = {rho})",
                            link_name(link),
                            b.lo,
                            b.hi
                        ),
                    )
                });
            }
        }
    }

    // ------------------------------------------------------------------------------------
    // C5_2/C5_3: every planned link's final length is in its band, or reported out of it
    // ------------------------------------------------------------------------------------
    fn in_band(&self, f: &mut Family, w: usize, win: &Window) {
        let (st, l) = (&win.final_, &win.links);
        if l.links.is_empty() {
            f.record(f64::NEG_INFINITY, || {
                format!("window {w}: no link report (links.links is empty) for its Step 2 graph")
            });
            return;
        }
        let length = |k: usize, x: &Link| Some(diff(node(st, Some(x.a), k)?, node(st, x.b, k)?));
        for k in 1..self.steps(win).min(l.links.len()) {
            for (i, x) in l.links[k].iter().enumerate() {
                let name = link_name(x);
                let Some(len) = length(k, x) else {
                    f.record(f64::NEG_INFINITY, || {
                        at(w, k, &format!("{name}: no such vehicle"))
                    });
                    continue;
                };
                let Some(b) = l.bands.get(k).and_then(|b| b.get(i)) else {
                    f.record(f64::NEG_INFINITY, || {
                        at(w, k, &format!("{name}: no band recorded"))
                    });
                    continue;
                };
                let margin = (len - b.lo).min(b.hi - len);
                let margin = if b.lo.is_nan() || b.hi.is_nan() {
                    f64::NAN
                } else {
                    margin
                };
                let reported = l
                    .out_of_band
                    .iter()
                    .any(|o| o.k == k && same_link(&o.link, x));
                let text = |how: &str| {
                    at(
                        w,
                        k,
                        &format!(
                            "{name}: length {len:.6} m, band [{:.6}, {:.6}]{how}",
                            b.lo, b.hi
                        ),
                    )
                };
                if margin >= -BAND_TOL || !reported {
                    let how = if margin >= -BAND_TOL {
                        ""
                    } else {
                        ", not listed in out_of_band"
                    };
                    f.record(margin, || text(how));
                } else {
                    // outside its band and reported so: accepted (the entry is checked below)
                    f.record(0.0, || text(", listed in out_of_band"));
                }
            }
        }
        // every out_of_band entry names a planned link of k = 1..=K with its true length and
        // its recorded band
        for o in &l.out_of_band {
            let k = o.k;
            let name = link_name(&o.link);
            let found = l.links.get(k).and_then(|links| {
                let i = links.iter().position(|x| same_link(x, &o.link))?;
                Some((l.bands.get(k)?.get(i).copied(), length(k, &o.link)))
            });
            let problem = match found {
                _ if k == 0 => Some("k = 0 is the fixed start, not planned".to_string()),
                None => Some("not a planned link at this step".to_string()),
                Some((None, _)) | Some((_, None)) => Some("no band or no such vehicle".into()),
                Some((Some(b), Some(len))) => {
                    let len_ok = (o.length - len).abs() <= OUT_OF_BAND_REL_TOL * len.max(1.0);
                    let band_ok = (o.band.lo - b.lo).abs() <= BAND_LIMIT_TOL
                        && (o.band.hi - b.hi).abs() <= BAND_LIMIT_TOL;
                    (!(len_ok && band_ok)).then(|| {
                        format!(
                            "recorded length {} m and band [{}, {}], the plan gives {len} m \
                             and band [{}, {}]",
                            o.length, o.band.lo, o.band.hi, b.lo, b.hi
                        )
                    })
                }
            };
            if let Some(p) = problem {
                f.record(f64::NEG_INFINITY, || {
                    at(w, k, &format!("out_of_band entry {name}: {p}"))
                });
            }
        }
    }

    // ------------------------------------------------------------------------------------
    // every AUV reaches the USV through links in range and in line of sight
    // ------------------------------------------------------------------------------------
    fn connectivity(&self, f: &mut Family, w: usize, win: &Window) {
        let st = &win.final_;
        let n = self.s.team.auvs;
        let d_s = self.limits.acoustic.sonar_range;
        // node 0 is the USV, node i + 1 is AUV i
        let who = |i: usize| i.checked_sub(1);
        for k in 0..self.steps(win) {
            let pos: Option<Vec<[f64; 3]>> = (0..=n).map(|i| node(st, who(i), k)).collect();
            let Some(pos) = pos else { continue };
            // (distance, clearance or why there is none) of every pair i < j in range
            let mut link = vec![vec![None; n + 1]; n + 1];
            for i in 0..=n {
                for j in i + 1..=n {
                    let d = diff(pos[i], pos[j]);
                    // in range: the clearance and the first obstacle crossed, if any
                    let los = if d <= d_s + LENGTH_TOL {
                        Some((self.los(pos[i], pos[j]), self.crossing(pos[i], pos[j])))
                    } else {
                        None
                    };
                    let ok = matches!(&los, Some((Ok(c), None)) if c.min_clearance >= -LOS_TOL);
                    link[i][j] = Some((d, los.clone(), ok));
                    link[j][i] = Some((d, los, ok));
                }
            }
            let mut reached = vec![false; n + 1];
            reached[0] = true;
            let mut queue = vec![0];
            while let Some(i) = queue.pop() {
                for j in 0..=n {
                    if !reached[j] && matches!(link[i][j], Some((_, _, true))) {
                        reached[j] = true;
                        queue.push(j);
                    }
                }
            }
            let cut: Vec<usize> = (1..=n).filter(|&i| !reached[i]).collect();
            f.record(-(cut.len() as f64), || {
                if cut.is_empty() {
                    return at(w, k, "every AUV reaches the USV");
                }
                // the pair (cut node, reached node) that comes closest
                let names: Vec<String> = cut.iter().map(|&i| node_name(who(i))).collect();
                let closest = cut
                    .iter()
                    .flat_map(|&i| (0..=n).filter(|&j| reached[j]).map(move |j| (i, j)))
                    .filter_map(|(i, j)| {
                        let (d, los, _) = link[i][j].clone()?;
                        Some((i, j, d, los))
                    })
                    .min_by(|a, b| a.2.total_cmp(&b.2));
                let Some((i, j, d, los)) = closest else {
                    return at(w, k, &format!("cut off from the USV: {}", names.join(", ")));
                };
                let why = match los {
                    None => format!("{d:.3} m > d_s = {d_s} m"),
                    Some((_, Some(crossing))) => format!(
                        "in range ({d:.3} m) but no line of sight: it crosses an obstacle \
                         cell, {crossing}"
                    ),
                    Some((Ok(c), None)) => format!(
                        "in range ({d:.3} m) but no line of sight: clearance {:.3} m at \
                         ({:.2}, {:.2}, {:.2})",
                        c.min_clearance, c.at[0], c.at[1], c.at[2]
                    ),
                    Some((Err(e), None)) => {
                        format!("in range ({d:.3} m), line of sight not evaluated: {e}")
                    }
                };
                at(
                    w,
                    k,
                    &format!(
                        "cut off from the USV: {}; nearest connected node to {} is the {}: {why}",
                        names.join(", "),
                        node_name(who(i)),
                        node_name(who(j))
                    ),
                )
            });
        }
    }

    // ------------------------------------------------------------------------------------
    // C1_13 on the plan: every planned link of k = 1..=K has line of sight
    // ------------------------------------------------------------------------------------
    fn chain_los(&self, f: &mut Family, w: usize, win: &Window) {
        let (st, l) = (&win.final_, &win.links);
        if l.links.is_empty() {
            f.record(f64::NEG_INFINITY, || {
                format!("window {w}: no link report (links.links is empty) for its Step 2 graph")
            });
            return;
        }
        for k in 1..self.steps(win).min(l.links.len()) {
            for x in &l.links[k] {
                let name = link_name(x);
                let (Some(p), Some(q)) = (node(st, Some(x.a), k), node(st, x.b, k)) else {
                    f.record(f64::NEG_INFINITY, || {
                        at(w, k, &format!("{name}: no such vehicle"))
                    });
                    continue;
                };
                match self.los(p, q) {
                    Ok(c) => f.record(c.min_clearance, || {
                        at(
                            w,
                            k,
                            &format!(
                                "{name}: clearance {:.4} m at ({:.2}, {:.2}, {:.2})",
                                c.min_clearance, c.at[0], c.at[1], c.at[2]
                            ),
                        )
                    }),
                    Err(e) => f.record(f64::NEG_INFINITY, || at(w, k, &format!("{name}: {e}"))),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_and_non_paths() {
        assert!(path_problems(&[[0, 1], [1, 2], [2, 3]], 4).is_empty());
        assert!(path_problems(&[[2, 0], [0, 3], [1, 3]], 4).is_empty());
        assert!(path_problems(&[], 1).is_empty());
        // a cycle (and so a missing AUV)
        let p = path_problems(&[[0, 1], [1, 2], [0, 2]], 4);
        assert!(p.iter().any(|s| s.contains("cycle")), "{p:?}");
        assert!(p.iter().any(|s| s.contains("[3]")), "{p:?}");
        // a star
        let p = path_problems(&[[0, 1], [0, 2], [0, 3]], 4);
        assert_eq!(p, ["AUV 0 has degree 3 > 2"]);
        // too few, repeated, loops, out of range: never a panic
        assert!(!path_problems(&[[0, 1]], 3).is_empty());
        assert!(!path_problems(&[[0, 1], [1, 0]], 3).is_empty());
        assert!(!path_problems(&[[1, 1], [0, 1]], 3).is_empty());
        assert!(!path_problems(&[[0, 7], [0, 1]], 3).is_empty());
        assert!(!path_problems(&[[0, 1]], 0).is_empty());
    }

    #[test]
    fn links_match_the_graph() {
        let usv = |a| Link { a, b: None };
        let aa = |a, b| Link { a, b: Some(b) };
        let edges = [[0, 1], [1, 2]];
        assert!(links_problems(&[usv(1), aa(1, 0), aa(1, 2)], Some(1), &edges).is_empty());
        assert!(!links_problems(&[usv(0), aa(0, 1), aa(1, 2)], Some(1), &edges).is_empty());
        assert!(!links_problems(&[usv(1), aa(0, 1)], Some(1), &edges).is_empty());
        assert!(!links_problems(&[usv(1), aa(0, 1), aa(0, 2)], Some(1), &edges).is_empty());
        assert!(
            !links_problems(&[usv(1), aa(0, 1), aa(1, 2), aa(1, 2)], Some(1), &edges).is_empty()
        );
        assert!(!links_problems(&[], Some(1), &edges).is_empty());
    }
}
