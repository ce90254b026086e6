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
    /// The slacks priced by the SCP's penalty λ, each with its weight (q = λ·weight): what
    /// the model's solution still violates, Σ weight·ν, in the unit of the true violations.
    pub penalised: Vec<(usize, f64)>,
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
            penalised: Vec::new(),
        }
    }

    /// Price the slack `col` at `penalty`·`weight` in the objective (one unit of the slack is
    /// `weight` of true violation).
    pub(super) fn penalise(&mut self, col: usize, weight: f64, penalty: f64) {
        self.q[col] = penalty * weight;
        self.penalised.push((col, weight));
    }

    /// Σ weight·ν of the penalised slacks at the solution `x`: the violation the model keeps.
    pub(super) fn kept_violation(&self, x: &[f64]) -> f64 {
        self.penalised.iter().map(|&(c, w)| w * x[c].max(0.0)).sum()
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A penalised slack is priced λ·weight and its kept violation is weight·ν; slacks a
    /// solver returns a hair below zero count as none, and unpriced columns not at all.
    #[test]
    fn penalised_slacks_are_priced_and_counted_by_their_weight() {
        let mut m = Assembly::new(4);
        m.q[0] = 7.0; // an objective term, not a slack
        m.penalise(1, 1.0, 1e3);
        m.penalise(2, 17.5, 1e3);
        m.penalise(3, 1.0, 1e3);
        assert_eq!(m.q, vec![7.0, 1e3, 17.5e3, 1e3]);
        let x = [5.0, 0.25, 2.0, -1e-9];
        assert_eq!(m.kept_violation(&x), 0.25 + 35.0);
    }
}
