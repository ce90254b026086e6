//! Independent verification of a plan (`shoal check plan.json`).
//!
//! Every constraint of the plan is re-evaluated from the plan file and the seafloor alone. The
//! checker shares no code with the optimiser's constraint builders (`step1`, `team`, `graph`,
//! `linearise`, `scp`, `conic`, `vehicle`): it has its own AUV model ([`model`], RK4 on the
//! continuous dynamics or eq. (8) literally), its own geometry, its own objective, its own graph
//! tests. It uses only the plan data types ([`crate::plan`]), the scenario parameters recorded
//! in the plan, and the floor's elevation and segment queries ([`crate::seafloor`]).
//!
//! # Which stage is checked
//!
//! A window records two stages: `step1` (P2) and `final` (Step 3, P5 with its line-of-sight
//! rounds), the plan the team executes. **`final` is the plan**: every family below runs on it,
//! and window w + 1's stages must start where window w's `final` stage ends. Step 1's stage is
//! checked too, by the same families (structure, dynamics, speeds, C1_4, C1_5/C1_6, floor and
//! obstacles, heading rate, recorded fields, window chain, objective), because Step 2 builds its
//! graph on Step 1's positions; it costs one more pass over the same arrays. Messages name the
//! stage: "AUV 2" is the final stage's, "step1 AUV 2" Step 1's. The objective of `final` is
//! checked term by term (energy, depth, height, usv) but not its total, which also weighs P5's
//! own terms; Step 1's total is checked.
//!
//! # Families and margins
//!
//! Constraints are grouped in families (see [`CheckReport::table`]). Every individual check gives
//! a *margin*: how far inside the constraint the plan is, in the constraint's unit (positive =
//! satisfied with room, negative = violated by that much). Equalities (dynamics, chaining,
//! recorded values) have margin −|error|. A family passes when its worst margin is
//! ≥ −tolerance. A check that cannot be evaluated (non-finite number, point outside the grid)
//! counts as margin −∞, so it fails its family. Array entries that are missing (a truncated
//! plan) or indices that name no vehicle are a "structure" failure and skipped by the other
//! families.
//!
//! # Obstacles
//!
//! NODATA and land cells are obstacles (see [`crate::seafloor`]) that no path or link may cross.
//! The family **no obstacle (NODATA/land)** samples by the rule of 𝓛_r (every sample, endpoints
//! included) the segments of every AUV and of the USV (z = 0) in both stages, and every planned
//! link of k = 1..=K in the final stage, and tests each sample with `Seafloor::obstacle`; a
//! sample over an obstacle cell or off the grid has margin −1, tolerance 0. The family **inside
//! the seafloor grid** holds the AUVs' and the USV's waypoints.
//!
//! # AUV separation
//!
//! The family **AUV separation** (module `separation`) holds every pair of AUVs at least
//! `auv.min_separation` apart at every waypoint and along every segment between waypoints (the
//! least distance of two points moving on straight lines over the same interval, in closed
//! form), in both stages, k = 0..=K.
//!
//! # Steps 2 and 3 (the graph families)
//!
//! At every step k = 0..=K of every window (module `graph`):
//!
//! * **A2A Hamiltonian path**: `graph.a2a[k]` is N − 1 distinct edges between distinct AUVs
//!   < N, every AUV of degree ≤ 2, connected (hence no cycle); and `links.links[k]` is the A2U
//!   link of `graph.a2u[k]` followed by exactly those edges. Counted in problems, tolerance 0.
//! * **A2U link**: `graph.a2u[k]` is an AUV nearest the USV (at z = 0) in Step 1's positions
//!   (P3); margin = nearest distance − its distance, tolerance [`A2U_TIE_TOL`].
//! * **link bands within [0, ρ·d_s]**: every recorded band has 0 ≤ lo ≤ hi ≤ ρ·d_s, ρ the
//!   plan's `acoustic.link_margin` (the margin the plan claims its links keep inside d_s),
//!   tolerance [`BAND_LIMIT_TOL`].
//! * **links in band**: for k = 1..=K (k = 0 is the fixed start) every planned link's length in
//!   the final positions is in its band within [`BAND_TOL`], or the (k, link) is listed in
//!   `out_of_band`; every `out_of_band` entry names a planned link with its length (within
//!   [`OUT_OF_BAND_REL_TOL`] relative to max(length, 1 m)) and band.
//! * **acoustic connectivity (range + line of sight)**: over the USV and the AUVs (final
//!   positions), an edge joins two nodes within d_s + [`LENGTH_TOL`] whose segment has line of
//!   sight (every sample of 𝓛_r at or above the floor within [`LOS_TOL`], and none over an
//!   obstacle cell: NODATA or land cannot be seen through); every AUV must reach
//!   the USV. Margin = −(AUVs cut off), tolerance 0: the hard requirement, at 100 % of steps.
//! * **planned chain line of sight**: for k = 1..=K every link of `links.links[k]` has line of
//!   sight; margin = the segment's clearance, tolerance [`LOS_TOL`].
//!
//! A plan without Step 2 data (every `graph.a2u` empty, as written by a planner that runs only
//! Step 1) skips these six: each shows PASS with 0 checks and "no Step 2 graph in this plan".
//! A window with a graph but an empty link report fails "links in band" and "planned chain line
//! of sight".
//!
//! # Tolerances
//!
//! | family | tolerance | why |
//! |---|---|---|
//! | structure, seafloor identity, obstacles | 0 | exact facts |
//! | C1_1 AUV dynamics, position | [`DYNAMICS_POSITION_TOL`] = 1e-6 m | see constant |
//! | C1_1 AUV dynamics, velocity | [`DYNAMICS_VELOCITY_TOL`] = 1e-8 m/s | δ·1e-8 m/s = 1e-6 m at δ = 100 s |
//! | eq. (9) USV dynamics | [`DYNAMICS_POSITION_TOL`] | |
//! | model record | [`MODEL_REL_TOL`] = 1e-9 relative | |
//! | speeds (USV, C1_7) | [`SPEED_TOL`] = 1e-6 m/s | convex (cone) constraints |
//! | C1_4 underwater, C1_5/C1_6 ranges | [`LENGTH_TOL`] = 1e-6 m | convex constraints |
//! | C2_2 floor clearance, grid | [`FLOOR_TOL`] = 1e-3 m, 0 m for the grid | nonconvex (SCP) |
//! | C1_14 heading rate | [`HEADING_TURN_TOL`]/δ (1e-3 rad of turn per step) | nonconvex (SCP) |
//! | depth rating | [`LENGTH_TOL`] | linear rows |
//! | flight-path angle, cruise floor | [`SPEED_TOL`] | nonconvex (SCP), restricted by the model |
//! | recorded surge speed / heading | [`DERIVED_TOL`] = 1e-9 (m/s, rad) | pure arithmetic |
//! | window chain | [`CHAIN_TOL`] = 1e-9 (m, m/s) | a copy |
//! | objective | [`OBJECTIVE_REL_TOL`] = 1e-6 relative | |
//! | recorded metrics (energy, heights, heading rate; connected and chain fractions; `metrics`) | 1e-6 relative (fractions: 1e-6) | recomputed sums, recounted steps |
//! | recorded explored area (`metrics`) | `AREA_TOL` = 5 % relative | measured across the planner's strips |
//! | A2A Hamiltonian path | 0 problems | combinatorial facts |
//! | A2U link | [`A2U_TIE_TOL`] = 1e-9 m | ties between equally near AUVs |
//! | link bands within [0, ρ·d_s] | [`BAND_LIMIT_TOL`] = 1e-9 m | recorded numbers |
//! | AUV separation | [`SEPARATION_TOL`] = 1e-3 m | nonconvex (SCP) |
//! | links in band | [`BAND_TOL`] = 1e-3 m | nonconvex (SCP), as the planner's 1 mm report threshold |
//! | acoustic connectivity | 0 AUVs cut off; range [`LENGTH_TOL`], line of sight [`LOS_TOL`] | the hard requirement |
//! | planned chain line of sight | [`LOS_TOL`] = 1e-6 m | |

mod envelope;
mod floor;
mod graph;
mod metrics;
pub mod model;
mod objective;
mod obstacles;
mod run;
mod separation;
mod vehicles;

use crate::plan::{ObjectiveTerms, Plan};
use crate::scenario::Scenario;
use crate::seafloor::{load, LoadOptions, Region, Seafloor, SeafloorError};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// C1_1 / eq. (9): largest `‖P[k+1] − model(P[k], V[k], U[k])‖` accepted, metres. The planner's
/// plans (solver iterates of linear equality constraints) are consistent to ≈ 1e-12 m on
/// kilometre-scale coordinates, and the checker's RK4 propagator is good to ≈ 1e-12 relative
/// (see [`model`]). 1 µm is far below any physical meaning, so a larger error is a genuinely
/// inconsistent plan (tampered inputs, wrong model, wrong δ) or a subproblem solved only to
/// reduced accuracy.
pub const DYNAMICS_POSITION_TOL: f64 = 1e-6;
/// C1_1: largest `‖V[k+1] − model(V[k], U[k])‖` accepted, m/s; over a step of δ = 100 s it moves
/// the next position by at most 1e-6 m, i.e. it matches [`DYNAMICS_POSITION_TOL`].
pub const DYNAMICS_VELOCITY_TOL: f64 = 1e-8;
/// Recorded damping rates, time step, speed limit and discrete coefficients against the
/// checker's own, relative. They are computed by closed formulas (here: by RK4 with ≈ 1e-12
/// relative error), so anything above 1e-9 is a different model.
pub const MODEL_REL_TOL: f64 = 1e-9;
/// Speed limits (‖U_USV‖ ≤ usv.max_speed, C1_7 ‖V_n‖ ≤ auv.max_speed), m/s. These are second-
/// order cone constraints that the convex solver meets to ≈ 1e-8 of the variable scale
/// (≈ 1 m/s); 1e-6 m/s leaves two orders of margin and is physically nothing.
pub const SPEED_TOL: f64 = 1e-6;
/// Lengths of convex constraints (C1_4 depth below the surface, C1_5 / C1_6 ranges), metres.
/// Same reasoning as [`SPEED_TOL`] on coordinates of ≈ 100 m: 1e-6 m.
pub const LENGTH_TOL: f64 = 1e-6;
/// C2_2 floor clearance, metres. The clearance is nonconvex (bilinear floor); the plan is the
/// output of an iterative sequential-convex solve, which stops when the true violation is
/// below its feasibility tolerance (scp.feasibility_tol, default 1e-3). One millimetre against
/// a clearance of metres is negligible; a plan made with a looser scp.feasibility_tol can fail.
pub const FLOOR_TOL: f64 = 1e-3;
/// C1_14 heading rate: largest turn between consecutive samples beyond ψ̇_max·δ accepted,
/// radians per step (reported as a rate: tolerance HEADING_TURN_TOL/δ rad/s, 1e-5 rad/s at
/// δ = 100 s). Nonconvex like the floor, hence the same 1e-3 as the SCP's default feasibility
/// tolerance (which the planner applies to this turn angle); 1 mrad is 0.06°.
pub const HEADING_TURN_TOL: f64 = 1e-3;
/// Recorded surge speed (m/s) and heading (rad) against atan2/hypot of the recorded velocity:
/// the same floating-point formula, so only rounding (≈ 1e-16) separates honest values.
pub const DERIVED_TOL: f64 = 1e-9;
/// Window chaining (start of window w+1 = end of window w, window 0 = plan.initial), m and m/s:
/// the planner copies the state, so honest plans match exactly.
pub const CHAIN_TOL: f64 = 1e-9;
/// Objective terms recomputed against the stored ones, relative to the term's magnitude (the
/// weighted total: relative to the sum of the weighted terms' magnitudes). Summation order
/// alone changes them by ≈ 1e-14.
pub const OBJECTIVE_REL_TOL: f64 = 1e-6;

/// A2U link: the recorded AUV may be farther from the USV than the nearest one by this much,
/// metres (P3 picks the nearest; two AUVs equally near within rounding are both right).
pub const A2U_TIE_TOL: f64 = 1e-9;
/// Link bands: 0 ≤ lo ≤ hi ≤ d_s within this, metres. The bands are recorded numbers computed
/// from d_s and d_t (hi possibly lowered), so only rounding separates an honest band.
pub const BAND_LIMIT_TOL: f64 = 1e-9;
/// A planned link's final length outside its band by more than this (metres) must be listed in
/// `out_of_band`. The band constraints C5_2/C5_3 are nonconvex and solved by SCP to
/// scp.feasibility_tol (1e-3 by default), and the planner reports a link out of band when it is
/// outside by more than 1 mm: the same number.
pub const BAND_TOL: f64 = 1e-3;
/// An `out_of_band` entry's recorded length against the length recomputed from the final
/// positions, relative to max(length, 1 m): both are the same Euclidean norm.
pub const OUT_OF_BAND_REL_TOL: f64 = 1e-6;
/// Line of sight: a sample of 𝓛_r may be below the floor by at most this, metres (rounding in
/// the bilinear floor; a link touching the floor has line of sight).
pub const LOS_TOL: f64 = 1e-6;
/// AUV separation: two AUVs may come closer than `auv.min_separation` by at most this, metres.
/// The separation is nonconvex, solved by SCP to scp.feasibility_tol (1e-3 by default), as the
/// floor clearance is: the same number.
pub const SEPARATION_TOL: f64 = 1e-3;

/// Indent of the line(s) under a family's row that say where its worst margin is.
pub const WHERE_INDENT: &str = "    at ";

/// `text` cut at spaces into lines of at most `width` characters (a longer word stays whole);
/// none for an empty text. Continuation lines are indented by two spaces.
fn wrap_words(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in text.split(' ') {
        let limit = if lines.is_empty() { width } else { width - 2 };
        if !current.is_empty() && current.chars().count() + 1 + word.chars().count() > limit {
            lines.push(std::mem::take(&mut current));
        }
        if !current.is_empty() {
            current.push(' ');
        } else if !lines.is_empty() {
            current.push_str("  ");
        }
        current.push_str(word);
    }
    if !current.trim().is_empty() {
        lines.push(current);
    }
    lines
}

/// The result of one constraint family.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilyResult {
    /// E.g. "C1_7 AUV speed".
    pub name: &'static str,
    /// Smallest margin over every check of the family, in `unit` (+∞ when nothing was checked,
    /// −∞ when a check could not be evaluated).
    pub worst_margin: f64,
    /// Unit of the margins and the tolerance, e.g. "m", "m/s", "rad/s", "relative", "problems".
    pub unit: &'static str,
    /// The family passes when worst_margin ≥ −tolerance.
    pub tolerance: f64,
    /// Where the worst margin occurs: window, step, vehicle (and what was wrong).
    pub where_: String,
    /// Number of individual checks.
    pub checked: usize,
}

impl FamilyResult {
    /// True when `worst_margin` ≥ −`tolerance`.
    pub fn passed(&self) -> bool {
        self.worst_margin >= -self.tolerance
    }
}

/// The objective terms of one window: as stored in the plan and as recomputed.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectiveCheck {
    /// The window's index in the plan, 0-based.
    pub window: usize,
    /// "final" or "step1".
    pub stage: &'static str,
    /// The terms as recorded in the plan.
    pub stored: ObjectiveTerms,
    /// The final stage's total is not recomputed (NaN).
    pub recomputed: ObjectiveTerms,
}

/// Everything the checker found.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckReport {
    /// One result per constraint family, in the order of [`CheckReport::table`].
    pub families: Vec<FamilyResult>,
    /// Every structural problem found (the "structure" family shows the first).
    pub problems: Vec<String>,
    /// Per window: stored and recomputed objective terms.
    pub objectives: Vec<ObjectiveCheck>,
    /// The fingerprint of the floor recorded in the plan.
    pub plan_fingerprint: String,
    /// The fingerprint of the floor the plan was checked against (`Seafloor::fingerprint`).
    pub floor_fingerprint: String,
    /// Whose limits the plan was held to, and where they differ from the plan's own.
    pub limits: LimitsUsed,
}

impl CheckReport {
    /// True when every family passes.
    pub fn passed(&self) -> bool {
        self.families.iter().all(FamilyResult::passed)
    }

    /// The families that fail.
    pub fn failures(&self) -> Vec<&FamilyResult> {
        self.families.iter().filter(|f| !f.passed()).collect()
    }

    /// The family named `name`, if any.
    pub fn family(&self, name: &str) -> Option<&FamilyResult> {
        self.families.iter().find(|f| f.name == name)
    }

    /// An aligned text table: family, checks, worst margin, unit, tolerance, where, PASS/FAIL;
    /// then the objective terms, stored beside recomputed, and a verdict line.
    pub fn table(&self) -> String {
        let head = [
            "family",
            "checks",
            "worst margin",
            "unit",
            "tolerance",
            "result",
        ];
        let rows: Vec<[String; 6]> = self
            .families
            .iter()
            .map(|f| {
                [
                    f.name.to_string(),
                    f.checked.to_string(),
                    if f.checked == 0 {
                        "-".into()
                    } else {
                        fmt_num(f.worst_margin)
                    },
                    f.unit.to_string(),
                    fmt_num(f.tolerance),
                    if f.passed() { "PASS" } else { "FAIL" }.into(),
                ]
            })
            .collect();
        let mut width = head.map(|h| h.chars().count());
        for r in &rows {
            for (w, c) in width.iter_mut().zip(r) {
                *w = (*w).max(c.chars().count());
            }
        }
        let mut out = String::new();
        let line = |out: &mut String, cells: &[String]| {
            let mut s = String::new();
            for (i, c) in cells.iter().enumerate() {
                let pad = width[i].saturating_sub(c.chars().count());
                if i + 1 == cells.len() {
                    s.push_str(c);
                } else if i == 1 || i == 2 || i == 4 {
                    s.push_str(&" ".repeat(pad));
                    s.push_str(c);
                    s.push_str("  ");
                } else {
                    s.push_str(c);
                    s.push_str(&" ".repeat(pad + 2));
                }
            }
            out.push_str(s.trim_end());
            out.push('\n');
        };
        line(&mut out, &head.map(String::from));
        line(&mut out, &width.map(|w| "-".repeat(w)));
        // where the worst margin is, under its row, wrapped to the table's width (at least
        // 60 columns): the table stays about 100 columns wide (it was 210 with the place as a
        // seventh column)
        let total: usize = width.iter().sum::<usize>() + 2 * (width.len() - 1);
        for (r, f) in rows.iter().zip(&self.families) {
            line(&mut out, r);
            for piece in wrap_words(&f.where_, total.max(60) - WHERE_INDENT.len()) {
                out.push_str(WHERE_INDENT);
                out.push_str(&piece);
                out.push('\n');
            }
        }
        if !self.objectives.is_empty() {
            out.push('\n');
            let _ = writeln!(
                out,
                "{:<8} {:<6} {:<7} {:>22} {:>22} {:>10}",
                "window", "stage", "term", "stored", "recomputed", "rel. diff"
            );
            for o in &self.objectives {
                for (term, a, b) in [
                    ("energy", o.stored.energy, o.recomputed.energy),
                    ("depth", o.stored.depth, o.recomputed.depth),
                    ("height", o.stored.height, o.recomputed.height),
                    ("usv", o.stored.usv, o.recomputed.usv),
                    ("total", o.stored.total, o.recomputed.total),
                ] {
                    let (recomputed, diff) = if term == "total" && o.stage == "final" {
                        ("not checked".to_string(), "-".to_string())
                    } else {
                        let rel = (a - b).abs() / a.abs().max(b.abs()).max(f64::MIN_POSITIVE);
                        let rel = if a == b { 0.0 } else { rel };
                        (format!("{b:.12e}"), format!("{rel:.1e}"))
                    };
                    let _ = writeln!(
                        out,
                        "{:<8} {:<6} {:<7} {:>22} {:>22} {:>10}",
                        o.window,
                        o.stage,
                        term,
                        format!("{a:.12e}"),
                        recomputed,
                        diff
                    );
                }
            }
        }
        if self.problems.len() > 1 {
            out.push('\n');
            let _ = writeln!(out, "structure problems ({}):", self.problems.len());
            for p in self.problems.iter().take(20) {
                let _ = writeln!(out, "  {p}");
            }
            if self.problems.len() > 20 {
                let _ = writeln!(out, "  … and {} more", self.problems.len() - 20);
            }
        }
        out.push('\n');
        let failures = self.failures();
        if failures.is_empty() {
            let _ = writeln!(
                out,
                "PASS: every constraint family holds within its tolerance"
            );
        } else {
            let names: Vec<&str> = failures.iter().map(|f| f.name).collect();
            let _ = writeln!(
                out,
                "FAIL: {} famil{} violated: {}",
                names.len(),
                if names.len() == 1 { "y" } else { "ies" },
                names.join(", ")
            );
        }
        // the places and problems quote the plan file (statuses, method, format)
        crate::report::printable_lines(&out).into_owned()
    }
}

/// Compact number: scientific for very small or large magnitudes.
fn fmt_num(v: f64) -> String {
    if v.is_infinite() || v.is_nan() {
        format!("{v}")
    } else if v == 0.0 {
        "0".into()
    } else if v.abs() < 1e-3 || v.abs() >= 1e6 {
        format!("{v:.3e}")
    } else {
        format!("{v:.6}")
    }
}

/// Errors of loading the floor a plan names.
#[derive(Debug, Error)]
pub enum CheckError {
    /// Reading the floor's grid file failed.
    #[error("cannot read the seafloor {path}: {source}")]
    ReadFloor {
        /// The file's path.
        path: PathBuf,
        /// Why it could not be read.
        #[source]
        source: SeafloorError,
    },
    /// Regenerating the synthetic floor from the plan's scenario failed.
    #[error(
        "cannot regenerate the synthetic seafloor (seed {seed}) from the plan's scenario: {source}"
    )]
    Synthetic {
        /// The scenario's random seed (`plan.scenario.seed`).
        seed: u64,
        /// Why the floor could not be made.
        #[source]
        source: SeafloorError,
    },
    /// The plan's floor source is "file" but neither the plan's seafloor record nor its scenario
    /// holds a path, and no floor was given explicitly.
    #[error(
        "the plan's seafloor source is \"file\" but it records no path; give the floor explicitly"
    )]
    NoFloorPath,
    /// The plan's floor source (`plan.seafloor.source`) is neither "synthetic" nor "file"; holds
    /// the recorded source.
    #[error("the plan's seafloor source \"{0}\" is neither \"synthetic\" nor \"file\"")]
    UnknownSource(String),
    /// The loaded floor's fingerprint differs from the one the plan records.
    #[error(
        "this is not the floor the plan was made on: {origin} has fingerprint {found}, the plan \
         records {expected}"
    )]
    FingerprintMismatch {
        /// Where the floor came from (path or "the synthetic floor (seed …)").
        origin: String,
        /// The fingerprint recorded in the plan.
        expected: String,
        /// The fingerprint of the loaded floor.
        found: String,
    },
}

/// Load the floor the plan names: regenerate the synthetic one from
/// `plan.scenario.seafloor.synthetic` and `plan.scenario.seed`, or read `plan.seafloor.path`
/// (the planner records it as an absolute path; a relative one resolves against the current
/// directory); `override_path` (a grid file: .asc, .tif, .tiff) replaces it. A file is loaded
/// as the planner loaded it: the recorded sign convention (`values`) and, for a geographic
/// grid, the recorded frame origin; and only the recorded node lattice (`nx`, `ny`, `x0`, `y0`)
/// is read, or the whole file when it does not hold that lattice. The floor must have the
/// fingerprint the plan records, otherwise [`CheckError::FingerprintMismatch`].
pub fn load_floor(plan: &Plan, override_path: Option<&Path>) -> Result<Seafloor, CheckError> {
    let rec = &plan.seafloor;
    let read = |path: &Path| {
        let opts = |region| LoadOptions {
            values: rec.values,
            origin: rec.origin,
            crs: plan.scenario.seafloor.crs.clone(),
            region,
        };
        let l = &rec.lattice;
        let window = Region::Nodes {
            x0: l.x0,
            y0: l.y0,
            nx: l.nx,
            ny: l.ny,
        };
        match load(path, &opts(window)) {
            Err(SeafloorError::Region { .. }) => load(path, &opts(Region::All)),
            r => r,
        }
        .map(|l| l.floor)
        .map_err(|source| CheckError::ReadFloor {
            path: path.to_path_buf(),
            source,
        })
    };
    let (floor, origin) = match override_path {
        Some(path) => (read(path)?, path.display().to_string()),
        None => match rec.source.as_str() {
            "file" => {
                let path = rec
                    .path
                    .as_deref()
                    .or(plan.scenario.seafloor.file.as_deref())
                    .ok_or(CheckError::NoFloorPath)?;
                (read(Path::new(path))?, path.to_string())
            }
            "synthetic" => {
                let seed = plan.scenario.seed;
                let floor = Seafloor::synthetic(&plan.scenario.seafloor.synthetic, seed)
                    .map_err(|source| CheckError::Synthetic { seed, source })?;
                (floor, format!("the synthetic floor (seed {seed})"))
            }
            other => return Err(CheckError::UnknownSource(other.to_string())),
        },
    };
    let found = floor.fingerprint();
    if found != rec.fingerprint {
        return Err(CheckError::FingerprintMismatch {
            origin,
            expected: rec.fingerprint.clone(),
            found,
        });
    }
    Ok(floor)
}

/// Check every constraint of `plan` against `floor`, with the limits recorded in the plan.
/// Never panics: malformed plans give a "structure" failure (and −∞ margins where a check
/// cannot be evaluated).
pub fn check_plan(plan: &Plan, floor: &Seafloor) -> CheckReport {
    run::run(plan, floor, &plan.scenario, LimitsUsed::recorded())
}

/// [`check_plan`] with the limits ([`LIMITS`]) of `stated`, the user's scenario, in place of
/// those the plan records: a plan whose recorded limits were raised by hand fails against the
/// vehicle's real ones. `source` says where `stated` came from, as [`limits_source`] words it.
/// The plan's geometry ([`GEOMETRY_KEYS`]: team size, steps, step length, windows) must be
/// `stated`'s, otherwise [`LimitsError::Geometry`]; the other settings (weights, solver,
/// seafloor, dynamics coefficients, seed) are the plan's own and are not used.
pub fn check_plan_against(
    plan: &Plan,
    floor: &Seafloor,
    stated: &Scenario,
    source: &str,
) -> Result<CheckReport, LimitsError> {
    let recorded = &plan.scenario;
    for (key, value) in GEOMETRY_KEYS {
        let (a, b) = (value(stated), value(recorded));
        if a != b {
            return Err(LimitsError::Geometry {
                from: source.to_string(),
                key,
                stated: a,
                recorded: b,
            });
        }
    }
    let changed = LIMITS
        .iter()
        .filter_map(|l| {
            let (a, b) = ((l.value)(stated), (l.value)(recorded));
            (a != b).then_some(LimitChange {
                key: l.key,
                stated: a,
                recorded: b,
            })
        })
        .collect();
    let ignored = differing_keys(stated, recorded)
        .into_iter()
        .filter(|k| !LIMITS.iter().any(|l| l.key == k))
        .collect();
    // the plan held to `stated`'s limits, everything else its own
    let mut limits = recorded.clone();
    for l in LIMITS {
        (l.set)(&mut limits, (l.value)(stated));
    }
    let used = LimitsUsed {
        source: source.to_string(),
        changed,
        ignored,
    };
    Ok(run::run(plan, floor, &limits, used))
}

/// How `shoal check` names the limits it used: "as recorded in the plan", "from mission.toml",
/// and either with " with --set KEY=VALUE …" for the overrides.
pub fn limits_source(file: Option<&str>, overrides: &[String]) -> String {
    let base = match file {
        Some(f) => format!("from {f}"),
        None => RECORDED.to_string(),
    };
    let sets: Vec<String> = overrides.iter().map(|o| format!("--set {o}")).collect();
    match sets.is_empty() {
        true => base,
        false => format!("{base} with {}", sets.join(" ")),
    }
}

const RECORDED: &str = "as recorded in the plan";

/// A limit of the plan: a bound the vehicles, their modems or the mission must keep, which a
/// user may state for `shoal check --scenario/--set`.
pub struct Limit {
    /// The dotted scenario key.
    pub key: &'static str,
    /// The families it bounds.
    pub families: &'static str,
    /// Its value in a scenario.
    pub value: fn(&Scenario) -> f64,
    /// Set it in a scenario.
    pub set: fn(&mut Scenario, f64),
}

/// The limits: vehicle speeds and turn rate, clearances, acoustic ranges. Everything else of a
/// scenario either makes the plan's geometry ([`GEOMETRY_KEYS`]) or is how the plan was made
/// (weights, solver, seafloor, the dynamics' coefficients, which the plan records as its model).
pub const LIMITS: &[Limit] = &[
    Limit {
        key: "auv.max_speed",
        families: "C1_7 AUV speed",
        value: |s| s.auv.max_speed,
        set: |s, v| s.auv.max_speed = v,
    },
    Limit {
        key: "auv.max_heading_rate",
        families: "C1_14 heading rate",
        value: |s| s.auv.max_heading_rate,
        set: |s, v| s.auv.max_heading_rate = v,
    },
    Limit {
        key: "auv.min_heading_speed",
        families: "C1_14 heading rate (applied above it)",
        value: |s| s.auv.min_heading_speed,
        set: |s, v| s.auv.min_heading_speed = v,
    },
    Limit {
        key: "auv.max_depth",
        families: "depth rating",
        value: |s| s.auv.max_depth,
        set: |s, v| s.auv.max_depth = v,
    },
    Limit {
        key: "auv.max_flight_path_angle",
        families: "flight-path angle",
        value: |s| s.auv.max_flight_path_angle,
        set: |s, v| s.auv.max_flight_path_angle = v,
    },
    Limit {
        key: "auv.level_speed",
        families: "flight-path angle (climbs)",
        value: |s| s.auv.level_speed,
        set: |s, v| s.auv.level_speed = v,
    },
    Limit {
        key: "auv.climb_per_speed",
        families: "flight-path angle (climbs)",
        value: |s| s.auv.climb_per_speed,
        set: |s, v| s.auv.climb_per_speed = v,
    },
    Limit {
        key: "auv.min_speed",
        families: "cruise floor",
        value: |s| s.auv.min_speed,
        set: |s, v| s.auv.min_speed = v,
    },
    Limit {
        key: "auv.floor_clearance",
        families: "C2_2 floor clearance",
        value: |s| s.auv.floor_clearance,
        set: |s, v| s.auv.floor_clearance = v,
    },
    Limit {
        key: "auv.surface_clearance",
        families: "C1_4 underwater",
        value: |s| s.auv.surface_clearance,
        set: |s, v| s.auv.surface_clearance = v,
    },
    Limit {
        key: "auv.min_separation",
        families: "AUV separation",
        value: |s| s.auv.min_separation,
        set: |s, v| s.auv.min_separation = v,
    },
    Limit {
        key: "usv.max_speed",
        families: "USV speed",
        value: |s| s.usv.max_speed,
        set: |s, v| s.usv.max_speed = v,
    },
    Limit {
        key: "acoustic.sonar_range",
        families: "C1_6 sonar range, link bands (with the plan's ρ), acoustic connectivity",
        value: |s| s.acoustic.sonar_range,
        set: |s, v| s.acoustic.sonar_range = v,
    },
    Limit {
        key: "acoustic.max_range",
        families: "C1_5 range ≤ d_max",
        value: |s| s.acoustic.max_range,
        set: |s, v| s.acoustic.max_range = v,
    },
];

/// A setting's dotted key and its value in a scenario.
pub type Setting = (&'static str, fn(&Scenario) -> f64);

/// The settings that make a plan's shape: a scenario stating limits must have the plan's.
pub const GEOMETRY_KEYS: &[Setting] = &[
    ("team.auvs", |s| s.team.auvs as f64),
    ("horizon.steps", |s| s.horizon.steps as f64),
    ("horizon.dt", |s| s.horizon.dt),
    ("windows", |s| s.windows as f64),
];

/// A limit the user stated that differs from the plan's record.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitChange {
    /// The dotted key.
    pub key: &'static str,
    /// The user's value, which the plan was checked against.
    pub stated: f64,
    /// The value the plan records.
    pub recorded: f64,
}

/// Whose limits a check used.
#[derive(Debug, Clone, PartialEq)]
pub struct LimitsUsed {
    /// "as recorded in the plan", or where the stated ones came from ([`limits_source`]).
    pub source: String,
    /// The stated limits that differ from the plan's record.
    pub changed: Vec<LimitChange>,
    /// Other settings of the stated scenario that differ from the plan's and were not used
    /// (not limits: the plan's own), as dotted keys.
    pub ignored: Vec<String>,
}

impl LimitsUsed {
    /// The plan's own limits.
    pub fn recorded() -> LimitsUsed {
        LimitsUsed {
            source: RECORDED.to_string(),
            changed: Vec::new(),
            ignored: Vec::new(),
        }
    }

    /// What `shoal check` prints above its table: "limits: …", then one line per stated limit
    /// that differs from the recorded one, and the settings that were not used.
    pub fn lines(&self) -> Vec<String> {
        let mut out = vec![format!("limits: {}", self.source)];
        if self.source != RECORDED && self.changed.is_empty() {
            out.push("  (every limit as recorded in the plan)".to_string());
        }
        for c in &self.changed {
            out.push(format!(
                "  {} = {} (stated), {} as recorded in the plan",
                c.key, c.stated, c.recorded
            ));
        }
        if !self.ignored.is_empty() {
            out.push(format!(
                "  not limits, the plan's own (not used): {}",
                self.ignored.join(", ")
            ));
        }
        out
    }
}

/// Why a plan cannot be checked against the limits a user states.
#[derive(Debug, Error)]
pub enum LimitsError {
    /// The stated scenario's geometry is not the plan's.
    #[error(
        "the limits {from} give {key} = {stated}, but the plan was made with {key} = \
         {recorded}: {key} shapes the plan (team size, steps, step length and windows must be \
         the plan's), it is not a limit; state the plan's value or plan again"
    )]
    Geometry {
        /// Where the stated limits came from ([`limits_source`]).
        from: String,
        /// The dotted key.
        key: &'static str,
        /// The stated value.
        stated: f64,
        /// The plan's value.
        recorded: f64,
    },
}

/// The dotted keys whose values differ between two scenarios (arrays compared whole).
fn differing_keys(a: &Scenario, b: &Scenario) -> Vec<String> {
    fn flatten(v: &serde_json::Value, prefix: &str, out: &mut Vec<(String, serde_json::Value)>) {
        match v {
            serde_json::Value::Object(map) => {
                for (k, child) in map {
                    let key = match prefix.is_empty() {
                        true => k.clone(),
                        false => format!("{prefix}.{k}"),
                    };
                    flatten(child, &key, out);
                }
            }
            other => out.push((prefix.to_string(), other.clone())),
        }
    }
    let leaves = |s: &Scenario| {
        let mut out = Vec::new();
        if let Ok(v) = serde_json::to_value(s) {
            flatten(&v, "", &mut out);
        }
        out
    };
    let (la, lb) = (leaves(a), leaves(b));
    let mut keys: Vec<String> = la
        .iter()
        .filter(|(k, v)| lb.iter().find(|(kb, _)| kb == k).map(|(_, vb)| vb) != Some(v))
        .map(|(k, _)| k.clone())
        .collect();
    for (k, _) in &lb {
        if !la.iter().any(|(ka, _)| ka == k) {
            keys.push(k.clone());
        }
    }
    keys
}
