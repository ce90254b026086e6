//! A thin layer over Clarabel for problems whose sparsity pattern is fixed and whose values change
//! from one SCP iteration to the next.
//!
//! Problems are min ½xᵀPx + qᵀx s.t. Ax + s = b, s ∈ K (Clarabel's standard form). Matrices are
//! assembled once from triplets into CSC; each triplet remembers its slot in the CSC value array,
//! so an update writes new values in triplet order and the solver keeps its symbolic
//! factorisation (`update_P`/`update_A`, presolve off, structural zeros kept).
//!
//! Variables may be given a scale d (x = d ∘ x̃, `ConicSolver::with_scale`): the solver then sees
//! x̃ of order one whatever the unit of x (positions of 10³ m beside inputs of 10⁻² m/s²), and
//! returns x. Clarabel's own equilibration scales the data too, but its tolerances then hold for
//! the equilibrated problem, and a variable 10⁵ times smaller than its neighbours was known only
//! to about 10⁻⁴ relative (see `team::Layout::scale`).

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, SupportedConeT,
};
use thiserror::Error;

/// Errors of the conic layer (building or solving).
#[derive(Debug, Error, Clone, PartialEq)]
pub enum ConicError {
    #[error("the conic solver rejected the problem data: {0}")]
    Setup(String),
    #[error("a data update changed the problem's sparsity pattern: {0}")]
    Update(String),
    #[error("could not write the model to {path}: {reason}")]
    Save { path: String, reason: String },
}

/// Triplets (row, col, value) in insertion order.
#[derive(Debug, Default, Clone)]
pub struct Triplets {
    pub rows: Vec<usize>,
    pub cols: Vec<usize>,
    pub vals: Vec<f64>,
}

impl Triplets {
    pub fn push(&mut self, row: usize, col: usize, val: f64) {
        self.rows.push(row);
        self.cols.push(col);
        self.vals.push(val);
    }
    pub fn len(&self) -> usize {
        self.vals.len()
    }
    pub fn is_empty(&self) -> bool {
        self.vals.is_empty()
    }
    pub fn clear_values(&mut self) {
        self.vals.clear();
    }
}

/// A CSC matrix built from triplets, with the map triplet → CSC slot. Duplicate (row, col)
/// triplets are summed into one slot.
#[derive(Debug, Clone)]
pub struct Pattern {
    pub matrix: CscMatrix<f64>,
    slot: Vec<usize>,
    /// Factor of each triplet's value (1 until `scale_columns`/`scale_symmetric`).
    factor: Vec<f64>,
}

impl Pattern {
    pub fn new(m: usize, n: usize, t: &Triplets) -> Pattern {
        let mut order: Vec<usize> = (0..t.len()).collect();
        order.sort_by_key(|&i| (t.cols[i], t.rows[i]));
        let mut colptr = vec![0usize; n + 1];
        let mut rowval = Vec::with_capacity(t.len());
        let mut slot = vec![0usize; t.len()];
        let mut last: Option<(usize, usize)> = None;
        for &i in &order {
            let key = (t.cols[i], t.rows[i]);
            if last != Some(key) {
                rowval.push(key.1);
                colptr[key.0 + 1] += 1;
                last = Some(key);
            }
            slot[i] = rowval.len() - 1;
        }
        for c in 0..n {
            colptr[c + 1] += colptr[c];
        }
        let nnz = rowval.len();
        let mut pattern = Pattern {
            matrix: CscMatrix::new(m, n, colptr, rowval, vec![0.0; nnz]),
            slot,
            factor: vec![1.0; t.len()],
        };
        pattern.matrix.nzval = pattern.values(&t.vals);
        pattern
    }

    /// Scale column j by d\[j\] (A of Ax with x = d ∘ x̃), for these triplets and every update.
    fn scale_columns(&mut self, t: &Triplets, d: &[f64]) {
        for (i, f) in self.factor.iter_mut().enumerate() {
            *f = d[t.cols[i]];
        }
        self.matrix.nzval = self.values(&t.vals);
    }

    /// Scale entry (i, j) by d\[i\]·d\[j\] (P of xᵀPx with x = d ∘ x̃).
    fn scale_symmetric(&mut self, t: &Triplets, d: &[f64]) {
        for (i, f) in self.factor.iter_mut().enumerate() {
            *f = d[t.rows[i]] * d[t.cols[i]];
        }
        self.matrix.nzval = self.values(&t.vals);
    }

    /// CSC values for triplet values given in the original triplet order.
    pub fn values(&self, vals: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; self.matrix.nzval.len()];
        for (i, v) in vals.iter().enumerate() {
            out[self.slot[i]] += v * self.factor[i];
        }
        out
    }
}

/// How a convex solve ended: Clarabel's status, as shoal reports it (its `Display` is the
/// variant's name, as the plan file's `solver_status` records it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolverStatus {
    /// The solver has not run.
    Unsolved,
    /// Solved to the requested tolerances.
    Solved,
    /// A certificate of primal infeasibility.
    PrimalInfeasible,
    /// A certificate of dual infeasibility (unbounded objective).
    DualInfeasible,
    /// Solved to reduced accuracy.
    AlmostSolved,
    /// Primal infeasible, to reduced accuracy.
    AlmostPrimalInfeasible,
    /// Dual infeasible, to reduced accuracy.
    AlmostDualInfeasible,
    /// The interior-point iteration limit.
    MaxIterations,
    /// The time limit.
    MaxTime,
    /// A numerical error.
    NumericalError,
    /// No progress.
    InsufficientProgress,
    /// Stopped by a callback.
    CallbackTerminated,
}

impl From<clarabel::solver::SolverStatus> for SolverStatus {
    fn from(s: clarabel::solver::SolverStatus) -> SolverStatus {
        use clarabel::solver::SolverStatus as C;
        match s {
            C::Unsolved => SolverStatus::Unsolved,
            C::Solved => SolverStatus::Solved,
            C::PrimalInfeasible => SolverStatus::PrimalInfeasible,
            C::DualInfeasible => SolverStatus::DualInfeasible,
            C::AlmostSolved => SolverStatus::AlmostSolved,
            C::AlmostPrimalInfeasible => SolverStatus::AlmostPrimalInfeasible,
            C::AlmostDualInfeasible => SolverStatus::AlmostDualInfeasible,
            C::MaxIterations => SolverStatus::MaxIterations,
            C::MaxTime => SolverStatus::MaxTime,
            C::NumericalError => SolverStatus::NumericalError,
            C::InsufficientProgress => SolverStatus::InsufficientProgress,
            C::CallbackTerminated => SolverStatus::CallbackTerminated,
        }
    }
}

impl std::fmt::Display for SolverStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{self:?}")
    }
}

impl SolverStatus {
    /// True for Solved and AlmostSolved (reduced accuracy, still usable by the SCP, which
    /// re-evaluates every constraint itself).
    pub fn usable(self) -> bool {
        matches!(self, SolverStatus::Solved | SolverStatus::AlmostSolved)
    }

    /// True for an interior-point run that failed numerically (NumericalError,
    /// InsufficientProgress), with no certificate either way.
    pub fn numerical_trouble(self) -> bool {
        matches!(
            self,
            SolverStatus::NumericalError | SolverStatus::InsufficientProgress
        )
    }

    /// True for a certificate of primal infeasibility, full or reduced accuracy.
    pub fn infeasible(self) -> bool {
        matches!(
            self,
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible
        )
    }
}

/// What the SCP records of one convex solve: its status, interior-point iterations and time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveReport {
    /// How the solve ended.
    pub status: SolverStatus,
    /// Interior-point iterations.
    pub iterations: u32,
    /// Clarabel's solve time, seconds.
    pub solve_time_s: f64,
}

/// Outcome of one conic solve.
#[derive(Debug, Clone)]
pub struct ConicSolution {
    pub status: SolverStatus,
    pub x: Vec<f64>,
    pub objective: f64,
    pub iterations: u32,
    pub solve_time_s: f64,
}

impl ConicSolution {
    /// True for Solved and AlmostSolved (reduced accuracy, still usable by the SCP, which
    /// re-evaluates every constraint itself).
    pub fn usable(&self) -> bool {
        self.status.usable()
    }

    /// Its status, interior-point iterations and time.
    pub fn report(&self) -> SolveReport {
        SolveReport {
            status: self.status,
            iterations: self.iterations,
            solve_time_s: self.solve_time_s,
        }
    }
}

/// Clarabel's duality-gap tolerances (absolute and relative) and its feasibility tolerance.
/// Its defaults (10⁻⁸) solve each convex model far past what the SCP can use: the SCP stops at
/// a predicted decrease of 10⁻³ relative and re-simulates the plan from the inputs, and every
/// bound is tightened by margins of 10⁻⁶ or more (`team`). docs/design-decisions.md, "Solver settings",
/// has the measurements behind the choice.
pub const GAP_TOL: f64 = 1e-6;
/// See [`GAP_TOL`].
pub const FEAS_TOL: f64 = 1e-7;

/// Solver settings used throughout: presolve off and structural zeros kept so that data updates
/// are always allowed; tolerances [`GAP_TOL`] and [`FEAS_TOL`]; no iterative refinement.
///
/// Iterative refinement polishes each Newton direction against the unregularised KKT matrix:
/// per interior-point iteration a residual product with the KKT matrix and one more pair of
/// triangular solves, for each of the two right-hand sides. Clarabel judges convergence by
/// residuals computed from the problem data, not from the factorisation, so a less exact
/// direction can cost iterations but cannot make a wrong answer pass as `Solved`. On our models
/// it costs none (docs/design-decisions.md, "Solver settings").
pub fn settings() -> DefaultSettings<f64> {
    DefaultSettingsBuilder::default()
        .verbose(false)
        .presolve_enable(false)
        .input_sparse_dropzeros(false)
        .max_iter(200)
        .tol_gap_abs(GAP_TOL)
        .tol_gap_rel(GAP_TOL)
        .tol_feas(FEAS_TOL)
        .iterative_refinement_enable(false)
        .build()
        .expect("static Clarabel settings are valid")
}

/// The size of the LDLᵀ factorisation of a model's KKT matrix (QDLDL's symbolic analysis
/// under its AMD ordering, as Clarabel factorises it): what one interior-point iteration costs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fill {
    /// Nonzeros of the KKT matrix's upper triangle, [P A'; A −H], H the cones' blocks.
    pub kkt_nonzeros: usize,
    /// Nonzeros of L (strictly lower).
    pub factor_nonzeros: usize,
    /// Σ over L's columns of (nonzeros)²: the multiply-adds of one numeric factorisation.
    pub multiply_adds: f64,
}

/// [`Fill`] of the KKT matrix of P (n × n, upper triangle used), A (m × n) and `cones`: the
/// pattern of Clarabel's KKT system, second-order cones of dimension ≤ 4 as dense blocks (as
/// Clarabel stores them; every cone of shoal's models is that small) and larger ones as their
/// diagonal (Clarabel's sparse expansion adds two columns per cone, not counted). Cones other
/// than zero, nonnegative and second-order are an error.
pub fn fill(
    p: &CscMatrix<f64>,
    a: &CscMatrix<f64>,
    cones: &[SupportedConeT<f64>],
) -> Result<Fill, ConicError> {
    use clarabel::qdldl::{QDLDLFactorisation, QDLDLSettingsBuilder};
    let (n, m) = (p.n, a.m);
    let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n + m];
    for (j, col) in cols.iter_mut().enumerate().take(n) {
        col.extend(
            (p.colptr[j]..p.colptr[j + 1])
                .map(|i| p.rowval[i])
                .filter(|&i| i <= j),
        );
        col.push(j);
    }
    for j in 0..n {
        for idx in a.colptr[j]..a.colptr[j + 1] {
            cols[n + a.rowval[idx]].push(j);
        }
    }
    let mut row = n;
    for cone in cones {
        let (d, dense) = match *cone {
            SupportedConeT::SecondOrderConeT(d) => (d, d <= 4),
            SupportedConeT::ZeroConeT(d) | SupportedConeT::NonnegativeConeT(d) => (d, false),
            _ => {
                return Err(ConicError::Setup(format!(
                    "fill: {cone:?} is not a cone of shoal's models"
                )))
            }
        };
        for i in 0..d {
            let first = if dense { row } else { row + i };
            cols[row + i].extend(first..=row + i);
        }
        row += d;
    }
    let (mut colptr, mut rowval) = (vec![0], Vec::new());
    for col in cols.iter_mut() {
        col.sort_unstable();
        col.dedup();
        rowval.extend_from_slice(col);
        colptr.push(rowval.len());
    }
    let nnz = rowval.len();
    let kkt = CscMatrix::new(n + m, n + m, colptr, rowval, vec![1.0; nnz]);
    let signs = (0..n + m).map(|i| if i < n { 1 } else { -1 }).collect();
    let settings = QDLDLSettingsBuilder::default()
        .logical(true)
        .Dsigns(signs)
        .build()
        .map_err(|e| ConicError::Setup(e.to_string()))?;
    let f = QDLDLFactorisation::<f64>::new(&kkt, Some(settings))
        .map_err(|e| ConicError::Setup(format!("{e:?}")))?;
    let l = &f.L;
    let multiply_adds = (0..l.n)
        .map(|j| ((l.colptr[j + 1] - l.colptr[j]) as f64).powi(2))
        .sum();
    Ok(Fill {
        kkt_nonzeros: nnz,
        factor_nonzeros: l.colptr[l.n],
        multiply_adds,
    })
}

/// A Clarabel solver over fixed P and A patterns.
pub struct ConicSolver {
    solver: DefaultSolver<f64>,
    p: Pattern,
    a: Pattern,
    cones: Vec<SupportedConeT<f64>>,
    /// x = scale ∘ x̃ (all ones without `with_scale`).
    scale: Vec<f64>,
    /// Clarabel's absolute duality-gap tolerance for the next solves ([`GAP_TOL`] until
    /// [`ConicSolver::set_gap_tolerance`]).
    gap_abs: f64,
}

impl ConicSolver {
    pub fn new(
        p: Pattern,
        q: &[f64],
        a: Pattern,
        b: &[f64],
        cones: &[SupportedConeT<f64>],
    ) -> Result<ConicSolver, ConicError> {
        let scale = vec![1.0; p.matrix.n];
        let solver = DefaultSolver::new(&p.matrix, q, &a.matrix, b, cones, settings())
            .map_err(|e| ConicError::Setup(e.to_string()))?;
        Ok(ConicSolver {
            solver,
            p,
            a,
            cones: cones.to_vec(),
            scale,
            gap_abs: GAP_TOL,
        })
    }

    /// The same over variables scaled by `scale` (x = scale ∘ x̃; every entry positive): `p_t`
    /// and `a_t` are the triplets the patterns were built from, in the units of x, as are later
    /// updates; solutions are returned in the units of x.
    #[allow(clippy::too_many_arguments)]
    pub fn with_scale(
        mut p: Pattern,
        p_t: &Triplets,
        q: &[f64],
        mut a: Pattern,
        a_t: &Triplets,
        b: &[f64],
        cones: &[SupportedConeT<f64>],
        scale: Vec<f64>,
    ) -> Result<ConicSolver, ConicError> {
        p.scale_symmetric(p_t, &scale);
        a.scale_columns(a_t, &scale);
        let qs: Vec<f64> = q.iter().zip(&scale).map(|(v, d)| v * d).collect();
        let solver = DefaultSolver::new(&p.matrix, &qs, &a.matrix, b, cones, settings())
            .map_err(|e| ConicError::Setup(e.to_string()))?;
        Ok(ConicSolver {
            solver,
            p,
            a,
            cones: cones.to_vec(),
            scale,
            gap_abs: GAP_TOL,
        })
    }

    /// Solve the next models only until their absolute duality gap is below `gap_abs` (in the
    /// objective's own units; never tighter than [`GAP_TOL`], which stays the relative
    /// tolerance, nor than the feasibility tolerance [`FEAS_TOL`], which is unchanged: every
    /// constraint holds as exactly as before, only the objective stops nearer or farther from
    /// its optimum). Clarabel stops when either the absolute or the relative gap is met.
    pub fn set_gap_tolerance(&mut self, gap_abs: f64) {
        let gap_abs = if gap_abs.is_finite() {
            gap_abs.max(GAP_TOL)
        } else {
            GAP_TOL
        };
        if gap_abs != self.gap_abs {
            self.gap_abs = gap_abs;
            // settings that validate once validate with another positive tolerance
            let _ = self.solver.update_settings(self.settings());
        }
    }

    /// [`settings`] with this solver's gap tolerance.
    fn settings(&self) -> DefaultSettings<f64> {
        DefaultSettings {
            tol_gap_abs: self.gap_abs,
            ..settings()
        }
    }

    /// The [`Fill`] of this model's factorisation.
    pub fn fill(&self) -> Result<Fill, ConicError> {
        fill(&self.p.matrix, &self.a.matrix, &self.cones)
    }

    /// Write the model of the last update (P, q, A, b, cones and the settings, in the solver's
    /// units x̃ = x / scale) as Clarabel's JSON problem file, whole or not at all: what any
    /// Clarabel interface reads back (`clarabel.load_from_file` in Python), so that other solvers
    /// can be measured on exactly the models the SCP solves (docs/design-decisions.md, "The convex
    /// solver").
    pub fn save_to_file(&self, path: &std::path::Path) -> Result<(), ConicError> {
        use clarabel::solver::SolverJSONReadWrite;
        let fail = |e: std::io::Error| ConicError::Save {
            path: path.display().to_string(),
            reason: e.to_string(),
        };
        let mut tmp = crate::atomic_file::temp_for(path).map_err(fail)?;
        self.solver.save_to_file(tmp.as_file_mut()).map_err(fail)?;
        crate::atomic_file::persist(tmp, path).map_err(fail)
    }

    /// New values for P (triplet order), q, A (triplet order) and b. Patterns must not change.
    pub fn update(
        &mut self,
        p_vals: &[f64],
        q: &[f64],
        a_vals: &[f64],
        b: &[f64],
    ) -> Result<(), ConicError> {
        let err = |e: clarabel::solver::DataUpdateError| ConicError::Update(e.to_string());
        self.solver.update_P(&self.p.values(p_vals)).map_err(err)?;
        let q: Vec<f64> = q.iter().zip(&self.scale).map(|(v, d)| v * d).collect();
        self.solver.update_q(&q).map_err(err)?;
        self.solver.update_A(&self.a.values(a_vals)).map_err(err)?;
        self.solver.update_b(&b.to_vec()).map_err(err)?;
        Ok(())
    }

    /// Name the first group of constraints without which the problem (last data `b`) becomes
    /// solvable: each group in turn has its bound rows set to a huge value (a deletion filter;
    /// the pattern is unchanged). Leaves the solver with `b` restored. Only for failures: one
    /// solve per group.
    pub fn diagnose<'g>(
        &mut self,
        b: &[f64],
        groups: &'g [(&'g str, Vec<usize>)],
    ) -> Option<&'g str> {
        const RELAXED: f64 = 1e9;
        let mut found = None;
        for (name, rows) in groups {
            let mut relaxed = b.to_vec();
            for &r in rows {
                relaxed[r] = RELAXED;
            }
            if self.solver.update_b(&relaxed).is_err() {
                break;
            }
            if self.solve().usable() {
                found = Some(*name);
                break;
            }
        }
        let _ = self.solver.update_b(&b.to_vec());
        found
    }

    /// Solve with the current data. A solve that ends in numerical trouble
    /// ([`SolverStatus::numerical_trouble`]) or at reduced accuracy (`AlmostSolved`: issue 22's
    /// scaling run found a Step 1 whose AlmostSolved candidate, re-simulated, broke C1_6 by
    /// 3.3·10⁻⁴ m, beyond the model's 10⁻³ m margin) is solved once more with iterative refinement on
    /// (Clarabel's default, off in [`settings`] for speed), which polishes each Newton
    /// direction against the unregularised KKT matrix. Issue 13's property test found a Step 3
    /// (N = 4, δ = 49 s) whose models ended in NumericalError and InsufficientProgress; with
    /// this retry and the SCP's smaller trust region after a failed solve, it plans. The report
    /// is the second solve's; its time includes the first.
    pub fn solve(&mut self) -> ConicSolution {
        self.solver.solve();
        let status = SolverStatus::from(self.solver.solution.status);
        if status.numerical_trouble() || status == SolverStatus::AlmostSolved {
            let first = self.solver.solution.solve_time;
            let mut refined = self.settings();
            refined.iterative_refinement_enable = true;
            if self.solver.update_settings(refined).is_ok() {
                self.solver.solve();
                self.solver.solution.solve_time += first;
                // back to the fast settings for the next solve
                let _ = self.solver.update_settings(self.settings());
            }
        }
        let s = &self.solver.solution;
        ConicSolution {
            status: s.status.into(),
            x: s.x.iter().zip(&self.scale).map(|(v, d)| v * d).collect(),
            objective: s.obj_val,
            iterations: s.iterations,
            solve_time_s: s.solve_time,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clarabel::solver::SupportedConeT::*;

    /// Two variables and one row coupling them: a star with the row at its centre, which AMD
    /// eliminates last, so L has only the two original entries.
    #[test]
    fn fill_of_a_star_has_no_fill_in() {
        let p = CscMatrix::new(2, 2, vec![0, 1, 2], vec![0, 1], vec![1.0, 1.0]);
        let a = CscMatrix::new(1, 2, vec![0, 1, 2], vec![0, 0], vec![1.0, 1.0]);
        let f = fill(&p, &a, &[NonnegativeConeT(1)]).unwrap();
        assert_eq!(f.kkt_nonzeros, 5);
        assert_eq!(f.factor_nonzeros, 2);
        assert_eq!(f.multiply_adds, 2.0);
    }

    /// One variable in three rows of a second-order cone: the cone's block is dense, so the
    /// 4 × 4 KKT matrix and its L are full (6 entries below the diagonal; 3² + 2² + 1²).
    #[test]
    fn fill_counts_a_small_cone_as_a_dense_block() {
        let p = CscMatrix::new(1, 1, vec![0, 1], vec![0], vec![1.0]);
        let a = CscMatrix::new(3, 1, vec![0, 3], vec![0, 1, 2], vec![1.0; 3]);
        let f = fill(&p, &a, &[SecondOrderConeT(3)]).unwrap();
        assert_eq!(f.kkt_nonzeros, 10);
        assert_eq!(f.factor_nonzeros, 6);
        assert_eq!(f.multiply_adds, 14.0);
    }

    #[test]
    fn pattern_sums_duplicates_and_maps_slots() {
        let mut t = Triplets::default();
        t.push(1, 0, 2.0);
        t.push(0, 1, 3.0);
        t.push(1, 0, 4.0);
        let p = Pattern::new(2, 2, &t);
        assert_eq!(p.matrix.colptr, vec![0, 1, 2]);
        assert_eq!(p.matrix.rowval, vec![1, 0]);
        assert_eq!(p.matrix.nzval, vec![6.0, 3.0]);
        assert_eq!(p.values(&[1.0, 1.0, 1.0]), vec![2.0, 1.0]);
    }

    /// min (x−1)² + (y−2)² s.t. ‖(x, y)‖ ≤ r: the projection of (1, 2) onto the disc of radius
    /// r, (1, 2)·r/√5, for r = 1 and, after a data update, r = 2; solved with the variables
    /// scaled by `scale` when given.
    /// The projection of (1, 2) onto the disc of radius b[0]: min ‖x‖² − 2x − 4y s.t.
    /// ‖(x, y)‖ ≤ b[0], as (P, A, q, cones).
    fn projection() -> (Triplets, Triplets, [f64; 2], [SupportedConeT<f64>; 1]) {
        let mut pt = Triplets::default();
        pt.push(0, 0, 2.0);
        pt.push(1, 1, 2.0);
        let mut at = Triplets::default();
        at.push(1, 0, -1.0);
        at.push(2, 1, -1.0);
        (pt, at, [-2.0, -4.0], [SecondOrderConeT(3)])
    }

    fn projection_survives_an_update(scale: Option<Vec<f64>>) {
        let (pt, at, q, cones) = projection();
        let b = [1.0, 0.0, 0.0];
        let (p, a) = (Pattern::new(2, 2, &pt), Pattern::new(3, 2, &at));
        let mut s = match scale {
            None => ConicSolver::new(p, &q, a, &b, &cones),
            Some(d) => ConicSolver::with_scale(p, &pt, &q, a, &at, &b, &cones, d),
        }
        .unwrap();
        let n = 5f64.sqrt();
        // at a duality-gap tolerance of GAP_TOL, x is good to about 10·GAP_TOL (7e-6 seen)
        let tol = 100.0 * GAP_TOL;
        let r = s.solve();
        assert!(r.usable());
        assert!((r.x[0] - 1.0 / n).abs() < tol && (r.x[1] - 2.0 / n).abs() < tol);
        // ½xᵀPx + qᵀx = ‖x‖² − 2x − 4y = 1 − 10/√5 at the projection
        assert!(
            (r.objective - (1.0 - 10.0 / n)).abs() < tol,
            "{}",
            r.objective
        );
        // radius 2: the target (1, 2) is still outside (norm √5 > 2)
        s.update(&pt.vals, &q, &at.vals, &[2.0, 0.0, 0.0]).unwrap();
        let r = s.solve();
        assert!((r.x[0] - 2.0 / n).abs() < tol && (r.x[1] - 4.0 / n).abs() < tol);
    }

    /// A saved model is the model last updated, in the solver's units: Clarabel reads it back
    /// and solves it to the same point (x̃ = x / scale); a file that cannot be written is an
    /// error naming it, and leaves nothing behind.
    #[test]
    fn a_saved_model_reloads_and_solves_to_the_same_point() {
        use clarabel::solver::SolverJSONReadWrite;
        let (pt, at, q, cones) = projection();
        let (p, a) = (Pattern::new(2, 2, &pt), Pattern::new(3, 2, &at));
        let scale = vec![4.0, 0.5];
        let mut s =
            ConicSolver::with_scale(p, &pt, &q, a, &at, &[1.0, 0.0, 0.0], &cones, scale.clone())
                .unwrap();
        // the model saved is the one of the last update (radius 2), not the first
        s.update(&pt.vals, &q, &at.vals, &[2.0, 0.0, 0.0]).unwrap();
        let r = s.solve();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("model.json");
        s.save_to_file(&path).unwrap();
        let mut file = std::fs::File::open(&path).unwrap();
        let mut again = DefaultSolver::<f64>::load_from_file(&mut file, Some(settings())).unwrap();
        again.solve();
        assert_eq!(
            SolverStatus::from(again.solution.status),
            SolverStatus::Solved
        );
        let tol = 100.0 * GAP_TOL;
        for i in 0..2 {
            let x = again.solution.x[i] * scale[i];
            assert!((x - r.x[i]).abs() < tol, "x[{i}]: {x} against {}", r.x[i]);
        }

        let missing = dir.path().join("no such directory").join("model.json");
        let e = s.save_to_file(&missing).unwrap_err();
        assert!(
            e.to_string().contains("no such directory/model.json"),
            "{e}"
        );
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(left.len(), 1, "only model.json");
    }

    #[test]
    fn socp_projection_matches_closed_form_and_survives_an_update() {
        projection_survives_an_update(None);
    }

    /// x measured in tens and y in tenths (x = 10·x̃, y = 0.1·ỹ): the solver sees other
    /// numbers, the caller the same answer and objective.
    #[test]
    fn scaled_variables_give_the_same_solution_in_the_callers_units() {
        projection_survives_an_update(Some(vec![10.0, 0.1]));
    }

    /// min Σ‖x_i − c_i‖² s.t. ‖x_i‖ ≤ 1 for 40 points c_i outside the unit disc: the optimum
    /// projects each onto the circle, objective (in ½xᵀPx + qᵀx = Σ‖x_i − c_i‖² − ‖c_i‖²)
    /// Σ(‖c_i‖ − 1)² − ‖c_i‖². Solved to an absolute gap of 10⁻², the objective is within
    /// 10⁻² of that (10⁻³ above it) and every cone holds as exactly as at the default
    /// tolerance, in fewer interior-point iterations (4 against 5).
    #[test]
    fn a_looser_gap_stops_within_it_and_keeps_the_constraints() {
        let n = 40;
        let (mut pt, mut at) = (Triplets::default(), Triplets::default());
        let (mut q, mut b, mut cones) = (vec![0.0; 2 * n], Vec::new(), Vec::new());
        let mut optimum = 0.0;
        for i in 0..n {
            let angle = i as f64 * 0.7;
            let c = [
                (2.0 + (i % 3) as f64) * angle.cos(),
                (2.0 + (i % 3) as f64) * angle.sin(),
            ];
            let norm = c[0].hypot(c[1]);
            optimum += (norm - 1.0).powi(2) - norm * norm;
            for d in 0..2 {
                pt.push(2 * i + d, 2 * i + d, 2.0);
                q[2 * i + d] = -2.0 * c[d];
            }
            b.extend([1.0, 0.0, 0.0]);
            at.push(3 * i + 1, 2 * i, -1.0);
            at.push(3 * i + 2, 2 * i + 1, -1.0);
            cones.push(SecondOrderConeT(3));
        }
        let solve = |gap: Option<f64>| {
            let (p, a) = (
                Pattern::new(2 * n, 2 * n, &pt),
                Pattern::new(3 * n, 2 * n, &at),
            );
            let mut s = ConicSolver::new(p, &q, a, &b, &cones).unwrap();
            if let Some(g) = gap {
                s.set_gap_tolerance(g);
            }
            s.solve()
        };
        let (exact, loose) = (solve(None), solve(Some(1e-2)));
        assert!(exact.usable() && loose.usable());
        assert!((exact.objective - optimum).abs() < 1e-4 * optimum.abs());
        assert!(
            loose.objective - optimum < 1e-2,
            "{} against {optimum}",
            loose.objective
        );
        assert!(loose.iterations < exact.iterations);
        for i in 0..n {
            assert!(loose.x[2 * i].hypot(loose.x[2 * i + 1]) <= 1.0 + 1e-6);
        }
    }

    /// x ≥ 1 (group "lower") and x ≤ 0 (group "upper") conflict; y ≤ 5 ("other") does not.
    /// The deletion filter skips "other" and names "lower", then leaves the data as it was.
    #[test]
    fn diagnose_names_the_group_whose_removal_restores_feasibility() {
        let mut pt = Triplets::default();
        pt.push(0, 0, 1.0);
        pt.push(1, 1, 1.0);
        let mut at = Triplets::default();
        at.push(0, 1, 1.0); // y ≤ 5
        at.push(1, 0, -1.0); // −x ≤ −1
        at.push(2, 0, 1.0); // x ≤ 0
        let b = [5.0, -1.0, 0.0];
        let mut s = ConicSolver::new(
            Pattern::new(2, 2, &pt),
            &[0.0, 0.0],
            Pattern::new(3, 2, &at),
            &b,
            &[NonnegativeConeT(3)],
        )
        .unwrap();
        assert_eq!(s.solve().status, SolverStatus::PrimalInfeasible);
        let groups = [("other", vec![0]), ("lower", vec![1]), ("upper", vec![2])];
        assert_eq!(s.diagnose(&b, &groups), Some("lower"));
        assert_eq!(s.diagnose(&b, &groups[..1]), None);
        assert_eq!(s.solve().status, SolverStatus::PrimalInfeasible);
    }
}
