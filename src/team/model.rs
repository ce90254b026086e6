//! The convex model's data, in Clarabel's form: min ½xᵀPx + qᵀx s.t. Ax + s = b, s ∈ cones.
//! Each constraint family appends its rows to an [`Assembly`]; `assemble` calls them in cone
//! order.

use crate::conic::Triplets;
use clarabel::solver::SupportedConeT;

/// b of a padding row (0·x − ν + s = 1): always satisfied, never binding.
pub(super) const INACTIVE: f64 = 1.0;

/// The convex model's data in Clarabel's form: min ½xᵀPx + qᵀx s.t. Ax + s = b, s ∈ cones.
pub(crate) struct Assembly {
    pub p: Triplets,
    pub q: Vec<f64>,
    pub a: Triplets,
    pub b: Vec<f64>,
    pub cones: Vec<SupportedConeT<f64>>,
    /// Constant of the model objective (so model merit = ½xᵀPx + qᵀx + constant).
    pub constant: f64,
    /// Groups of convex constraints by name, each with the rows whose b (a bound) disables the
    /// group when made huge: what `ConicSolver::diagnose` needs to name an infeasible one.
    pub groups: Vec<(&'static str, Vec<usize>)>,
}

impl Assembly {
    /// An empty model over `variables` variables.
    pub(super) fn new(variables: usize) -> Assembly {
        Assembly {
            p: Triplets::default(),
            q: vec![0.0; variables],
            a: Triplets::default(),
            b: Vec::new(),
            cones: Vec::new(),
            constant: 0.0,
            groups: Vec::new(),
        }
    }

    /// A new row with right-hand side `b`; returns its index.
    pub(super) fn row(&mut self, b: f64) -> usize {
        self.b.push(b);
        self.b.len() - 1
    }

    /// The row −x[col] ≤ 0 (in the nonnegative cone): a slack is nonnegative.
    pub(super) fn nonnegative(&mut self, col: usize) {
        let row = self.row(0.0);
        self.a.push(row, col, -1.0);
    }

    /// Record `row` as a bound of the group `name`.
    pub(super) fn group(&mut self, name: &'static str, row: usize) {
        match self.groups.iter_mut().find(|g| g.0 == name) {
            Some(g) => g.1.push(row),
            None => self.groups.push((name, vec![row])),
        }
    }
}
