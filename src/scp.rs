//! Sequential convex programming with a trust region and an exact-penalty merit function, after
//! SCvx (Mao, Szmuk, Açıkmeşe, 2018) and Malyuta et al., "Convex Optimization for Trajectory
//! Generation", IEEE Control Systems 2022, §"SCvx".
//!
//! The paper (Section IV-A) solves P2 "in an iterative manner where after each iteration Z_n\[k\]
//! is found and bounded" with no safeguard; a plain fixed-point iteration of that kind stalls or
//! oscillates against a steep floor. Here every nonconvex constraint g(x) ≤ 0 is linearised about
//! the reference iterate x̄ and softened with a penalised slack ν ≥ 0 (virtual control), the
//! model is trusted only within a radius Δ of x̄, and a candidate is accepted by the ratio
//!
//!   ρ = (φ(x̄) − φ(x*)) / (φ(x̄) − L(x*)),   φ = J + λ·Σ max(0, g),   L = its convex model,
//!
//! growing Δ when ρ is high and shrinking it when ρ is low. The loop stops when the model
//! predicts a decrease below `tolerance`·(1 + Σ|weighted objective terms|) and the true
//! violation is below the feasibility tolerance; if
//! the decrease vanishes while a violation remains, λ is raised (up to 10⁴·λ₀) before the
//! constraint is declared impossible.
//!
//! Ours (issue 22): a rejected step shrinks Δ to half the step it took (at most 16-fold at
//! once), where the problem can measure it (`ScpProblem::step_length`); and, with
//! `scp.momentum`, after good steps the model is built about the reference extrapolated along
//! its last step (Nesterov's sequence) and its candidate kept only if it lowers the merit by
//! more than the tolerance: the linearised concave terms make the model a majorant, whose
//! steps shrink geometrically (docs/method.md, "Momentum steps"). Each model is solved only to
//! the accuracy the stopping test reads (`ACCURACY_SHARE`), and the test allows for it. The
//! loop that stops converged ends on its last candidate if that one is feasible and better
//! (`ScpProblem::ends_on_a_better_candidate`): it was solved and judged already.

use crate::scenario::Scp;
use std::time::Instant;

/// What a problem solved by SCP must provide.
pub trait ScpProblem {
    /// A point of the problem (a trajectory, a vector).
    type Iterate: Clone;
    /// The problem's error type.
    type Error;
    /// What the problem reports of one convex solve (status, solver iterations, time), handed
    /// to the observer in each [`Iteration`].
    type Report: Clone;
    /// Solve the convex model about `reference` with trust radius `radius` and penalty
    /// `penalty`. Returns the candidate, the model merit L(candidate) and the solver's report.
    fn solve_model(
        &mut self,
        reference: &Self::Iterate,
        radius: f64,
        penalty: f64,
    ) -> Result<(Self::Iterate, f64, Self::Report), Self::Error>;
    /// The point x + β·(x − previous), a step of the iteration's momentum beyond the last
    /// accepted iterate x (for trajectories: the inputs extrapolated and rolled through the
    /// dynamics), or None (the default) when the problem does not support it, which turns the
    /// momentum off.
    fn extrapolate(
        &self,
        _x: &Self::Iterate,
        _previous: &Self::Iterate,
        _beta: f64,
    ) -> Option<Self::Iterate> {
        None
    }
    /// Whether the loop, stopping converged, may end on its last candidate rather than on its
    /// reference, when that candidate meets every constraint (within `scp.feasibility_tol`)
    /// and has the lower merit. The model predicted a negligible decrease, but the candidate
    /// was solved and judged already: the better point costs nothing. True by default.
    fn ends_on_a_better_candidate(&self) -> bool {
        true
    }
    /// The length of the step from `from` to `to` in the trust region's own norm, or None
    /// (the default) if the problem cannot say. A rejected step then shrinks the radius to
    /// below the step it took, not only to half the radius: a model trusted to 12.8 km whose
    /// step of 40 m fails is next trusted to 20 m, not 6.4 km (8 solves saved).
    fn step_length(&self, _from: &Self::Iterate, _to: &Self::Iterate) -> Option<f64> {
        None
    }
    /// The true objective J and the weighted sum of true violations V (so φ = J + λV), and the
    /// largest single violation (in the constraint's own unit).
    fn evaluate(&self, x: &Self::Iterate) -> Evaluation;
    /// An error for a constraint that stays violated at convergence with the largest penalty.
    fn infeasible(&self, x: &Self::Iterate) -> Self::Error;
    /// An error for a constraint still violated when the loop stopped at its iteration limit
    /// after `iterations` iterations (by default the same as [`infeasible`](Self::infeasible)).
    fn unfinished(&self, x: &Self::Iterate, iterations: usize) -> Self::Error {
        let _ = iterations;
        self.infeasible(x)
    }
    /// Whether `e`, from [`solve_model`](ScpProblem::solve_model), is the convex solver's
    /// numerical trouble with this model (not an infeasible model): the loop then treats the
    /// iteration as a rejected step and shrinks the trust region. None by default.
    fn numerical_trouble(&self, _e: &Self::Error) -> bool {
        false
    }
    /// Told of every candidate the loop judged, and whether it became the reference: a problem
    /// whose model keeps only some of its constraints' rows (screened by the reference) can add
    /// the ones a rejected candidate broke, so that the next model about the same reference
    /// is not the same model again. Nothing by default.
    fn judged(&mut self, _candidate: &Self::Iterate, _accepted: bool) {}
    /// Told, before each model is solved, the absolute error in the model's optimal value that
    /// the loop can tolerate (`ACCURACY_SHARE` of its stopping threshold): a problem whose
    /// convex solver can stop early at a duality gap may use it. Nothing by default.
    fn set_accuracy(&mut self, _gap: f64) {}
    /// The violation the last model's solution keeps by choice: its penalised slacks, Σ
    /// weight·ν, in the unit of [`Evaluation::violation`]; None (the default) if the problem
    /// cannot say. A model that keeps as much violation as its reference has is one whose
    /// penalty λ is too small (`STANDING_STEPS`), which a true violation alone cannot tell
    /// from a linearisation's error (the hyperbola of the tests breaks its constraint by
    /// 10⁻³ with no slack in its model).
    fn kept_violation(&self) -> Option<f64> {
        None
    }
}

/// One SCP iteration, as the loop reports it to its observer.
#[derive(Debug, Clone, PartialEq)]
pub struct Iteration<R> {
    /// Trust radius Δ of this iteration.
    pub trust_region: f64,
    /// φ(x̄) of the reference.
    pub merit_before: f64,
    /// φ(x*) of the candidate.
    pub merit_after: f64,
    /// Predicted decrease φ(x̄) − L(x*).
    pub predicted: f64,
    /// ρ = actual / predicted decrease.
    pub ratio: f64,
    /// Whether the candidate became the reference.
    pub accepted: bool,
    /// The candidate's largest true violation.
    pub violation: f64,
    /// λ, the penalty of the merit at this iteration (the merits and the prediction are
    /// measured with it; it grows when violations persist, `STANDING_STEPS`).
    pub penalty: f64,
    /// Whether the model was built about the extrapolated point of the momentum step (then
    /// `merit_before` is still the reference's, and `predicted` and `ratio` are measured from
    /// the extrapolated point).
    pub extrapolated: bool,
    /// The problem's report of the convex solve.
    pub solve: R,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Evaluation {
    pub objective: f64,
    pub violation: f64,
    pub max_violation: f64,
    /// Σ |weighted objective term|: the size of the objective, against which the convergence
    /// tolerance is measured. (|J| itself is useless as a scale when the terms nearly cancel,
    /// as −w8·OF1_8 and w1·OF1_1 do in P2.)
    pub magnitude: f64,
}

impl Evaluation {
    pub fn merit(&self, penalty: f64) -> f64 {
        self.objective + penalty * self.violation
    }

    /// Whether every constraint holds within `tol` (the settings' `feasibility_tol`).
    pub fn feasible(&self, tol: f64) -> bool {
        self.max_violation <= tol
    }
}

/// Why the SCP loop stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ScpStatus {
    /// The predicted decrease fell below the tolerance with every constraint met.
    Converged,
    /// Iteration limit reached; the returned iterate is feasible within tolerance.
    MaxIterations,
    /// The trust region collapsed below its minimum (or the penalty reached its largest value
    /// with no decrease left) before the tolerance was met; the returned iterate is feasible
    /// within tolerance, and no better one was found near it.
    Stalled,
    /// The convex solver ended in numerical trouble at the radius of the last iteration and
    /// at each of `TROUBLE_RETRIES` halvings of it; the returned iterate is the best feasible
    /// one found before.
    SolverTrouble,
}

impl ScpStatus {
    /// "converged", "max_iterations", "stalled" or "solver_trouble", as the plan file
    /// records it.
    pub fn as_str(&self) -> &'static str {
        match self {
            ScpStatus::Converged => "converged",
            ScpStatus::MaxIterations => "max_iterations",
            ScpStatus::Stalled => "stalled",
            ScpStatus::SolverTrouble => "solver_trouble",
        }
    }
}

/// The result of an SCP run.
#[derive(Debug, Clone)]
pub struct ScpOutcome<X> {
    /// The last accepted iterate (or the best feasible one at the iteration limit).
    pub iterate: X,
    /// Why the loop stopped.
    pub status: ScpStatus,
    /// The iterate's objective and violations.
    pub evaluation: Evaluation,
    /// SCP iterations run (each reported to the observer).
    pub iterations: usize,
    /// Wall-clock time of the loop, seconds.
    pub solve_time_s: f64,
}

// Ratio thresholds and trust-region factors (Malyuta et al., Table of SCvx parameters).
const RHO0: f64 = 0.0;
const RHO1: f64 = 0.25;
const RHO2: f64 = 0.7;
const SHRINK: f64 = 2.0;
const GROW: f64 = 2.0;
const PENALTY_GROWTH: f64 = 10.0;
/// Retries, each with half the trust radius, of a convex solve that ends in numerical trouble.
const TROUBLE_RETRIES: usize = 3;
const PENALTY_MAX_FACTOR: f64 = 1e4;
/// Accepted steps in a row whose model kept a violation standing (a candidate that breaks a
/// constraint by more than `feasibility_tol`, from a model whose penalised slacks keep at least
/// 1 − [`VIOLATION_PROGRESS`] of the reference's violation, [`ScpProblem::kept_violation`])
/// before λ grows. The merit then prefers the violation to what removing it costs: λ is too
/// small for this problem, and converging at that λ only to raise it afterwards wastes the
/// iterations between (issue 22; issue 13's draw 3033 crawled 45 accepted steps of P5 with a
/// heading-rate violation fixed at 3.053 rad while its objective fell by 0.2 % a step, to
/// the iteration limit).
const STANDING_STEPS: usize = 3;
/// The share of the reference's violation a model must remove for its step not to count as
/// leaving the violation standing.
const VIOLATION_PROGRESS: f64 = 0.1;
/// The most a single rejected step shrinks the radius by (to below the step's length).
const MAX_SHRINK: f64 = 16.0;
/// Accepted iterations after a rejection during which Δ may not grow. Without it a floor that
/// the model can trust for 25 m but not 50 m makes the loop alternate accept (25 m, ρ ≈ 1, grow)
/// and reject (50 m, ρ ≪ 0, shrink), wasting every other iteration (seen with N = 10).
const GROWTH_COOLDOWN: usize = 3;
/// The share of the stopping threshold, `tolerance`·(1 + magnitude), to which each model's
/// optimal value is solved ([`ScpProblem::set_accuracy`]). A model solved to an absolute
/// duality gap g returns a point whose model merit is within g of the model's optimum, so the
/// predicted decrease, φ(x̄) − L(x*), is understated by at most g: a tenth of the threshold
/// cannot make the loop stop, or go on, where the exact model would not by more than that.
/// Clarabel's own tolerance (10⁻⁶ relative) solves the models 2–4 interior-point iterations
/// past what the test can use (issue 22: a window's interior-point iterations 0.84–0.89× at
/// N = 3–20; the objectives unchanged on average over 32 seeds, each window moved either way
/// as any change of the path moves it; docs/design-decisions.md, "Solves as exact as the
/// stopping test").
const ACCURACY_SHARE: f64 = 0.1;

/// Run SCvx from `initial`, handing every iteration to `observer` as it ends. The first model
/// solution is always accepted: the initial guess need not satisfy the convex constraints, so
/// comparing merits against it means nothing.
pub fn solve<P: ScpProblem>(
    problem: &mut P,
    initial: P::Iterate,
    settings: &Scp,
    observer: &mut dyn FnMut(&Iteration<P::Report>),
) -> Result<ScpOutcome<P::Iterate>, P::Error>
where
    P::Error: From<ScpFailure>,
{
    let start = Instant::now();
    let mut reference = initial;
    let mut reference_eval = problem.evaluate(&reference);
    let mut radius = settings.trust_region;
    let max_radius = settings.trust_region * 64.0;
    let mut penalty = settings.penalty;
    let mut iterations = 0usize;
    let mut have_feasible_reference = false;
    let mut cooldown = 0usize;
    // the best accepted iterate that meets every constraint: returned at the iteration limit
    // if the last accepted one (the merit tolerates small violations) does not
    // (a feasible initial reference, such as Step 1's plan for P5, counts)
    let mut best: Option<(P::Iterate, Evaluation)> = reference_eval
        .feasible(settings.feasibility_tol)
        .then(|| (reference.clone(), reference_eval));

    // why the loop ends if it does not converge
    let mut status = ScpStatus::MaxIterations;
    let mut troubles = 0usize;
    // accepted steps in a row that left a violation standing (`STANDING_STEPS`)
    let mut standing = 0usize;
    // the momentum step: the reference before the last accepted step, Nesterov's t, and
    // whether the steps since the last restart were all good ones
    let mut previous: Option<P::Iterate> = None;
    let mut momentum = 1.0f64;
    let mut good_run = false;
    // the limit counts the iterations of the log (the solves that ended), not the retries
    // after numerical trouble: counting those stopped a window at "max_iterations" with 49
    // entries of 50, and its plan failed `shoal check` (issue 13's sweep, draw 1056)
    while iterations < settings.max_iterations {
        let next_momentum = 0.5 * (1.0 + (1.0 + 4.0 * momentum * momentum).sqrt());
        let beta = (momentum - 1.0) / next_momentum;
        let ahead = match &previous {
            Some(prev) if settings.momentum && good_run && beta > 0.0 => {
                problem.extrapolate(&reference, prev, beta).map(|z| {
                    let e = problem.evaluate(&z);
                    (z, e)
                })
            }
            _ => None,
        };
        let model_reference = ahead.as_ref().map_or(&reference, |(z, _)| z);
        // the model's optimal value is needed only to within a share of the stopping threshold
        let threshold = settings.tolerance * (1.0 + reference_eval.magnitude);
        let accuracy = ACCURACY_SHARE * threshold;
        problem.set_accuracy(accuracy);
        let (candidate, model_merit, report) =
            match problem.solve_model(model_reference, radius, penalty) {
                Ok(solved) => solved,
                // the solver's numerical trouble: a smaller model, as after a rejected step (at
                // most `TROUBLE_RETRIES` in a row; not an iteration of the log, which holds solves)
                Err(e) if problem.numerical_trouble(&e) && troubles < TROUBLE_RETRIES => {
                    troubles += 1;
                    radius /= SHRINK;
                    continue;
                }
                // trouble that persists with a feasible iterate in hand: stop there (N = 20:
                // a NumericalError at a radius of 1.9 km and at every retry ended a mission
                // whose window had a feasible plan). Not a stall: the log, which holds the
                // solves that ended, shows no collapsed trust region (`shoal check` knows)
                Err(e) if problem.numerical_trouble(&e) && best.is_some() => {
                    status = ScpStatus::SolverTrouble;
                    have_feasible_reference = true;
                    break;
                }
                Err(e) => return Err(e),
            };
        troubles = 0;
        let candidate_eval = problem.evaluate(&candidate);
        // whether the model kept its own reference's violation standing (`steer`)
        let stands = stands(
            settings,
            ahead
                .as_ref()
                .map_or(reference_eval.violation, |(_, e)| e.violation),
            problem.kept_violation(),
            candidate_eval.max_violation,
        );
        let phi_ref = reference_eval.merit(penalty);
        let phi_cand = candidate_eval.merit(penalty);
        // the model's own reference: the extrapolated point in a momentum step
        let phi_model = ahead.as_ref().map_or(phi_ref, |(_, e)| e.merit(penalty));
        let predicted = phi_model - model_merit;
        let actual = phi_model - phi_cand;
        let ratio = if predicted.abs() > 0.0 {
            actual / predicted
        } else {
            1.0
        };
        let first = iterations == 0;
        // a model solved to within `accuracy` may understate the decrease by that much: the
        // loop stops only where the exact model would have stopped too
        let negligible = !first && predicted + accuracy <= threshold;

        let mut record = Iteration {
            trust_region: radius,
            merit_before: phi_ref,
            merit_after: phi_cand,
            predicted,
            ratio,
            accepted: false,
            violation: candidate_eval.max_violation,
            penalty,
            extrapolated: ahead.is_some(),
            solve: report,
        };

        let step = problem.step_length(&reference, &candidate);
        if ahead.is_some() {
            // a momentum step is kept only if it lowers the merit below the reference's and
            // its model was good; otherwise the momentum restarts and the next iteration is
            // an ordinary one about the reference, with the same radius
            iterations += 1;
            // (its gain is judged against the reference: the prediction from the
            // extrapolated point also counts the violations the extrapolation made)
            let gain = phi_ref - phi_cand;
            if !negligible && ratio >= RHO1 && gain > threshold {
                record.accepted = true;
                problem.judged(&candidate, true);
                momentum = next_momentum;
                // a kept momentum step is a good step: the radius may grow
                cooldown = cooldown.saturating_sub(1);
                if cooldown == 0 {
                    radius = (radius * GROW).min(max_radius);
                }
                steer(&mut standing, &mut penalty, settings, stands);
                previous = Some(std::mem::replace(&mut reference, candidate));
                reference_eval = candidate_eval;
                keep_if_best(
                    &mut best,
                    &reference,
                    reference_eval,
                    settings.feasibility_tol,
                );
            } else {
                problem.judged(&candidate, false);
                momentum = 1.0;
                good_run = false;
            }
            observer(&record);
            continue;
        }

        if negligible {
            iterations += 1;
            let tol = settings.feasibility_tol;
            if reference_eval.feasible(tol) {
                // the last candidate, solved and judged already, if it is feasible and better
                let better = candidate_eval.feasible(tol)
                    && phi_cand < phi_ref
                    && problem.ends_on_a_better_candidate();
                record.accepted = better;
                observer(&record);
                let (iterate, evaluation) = if better {
                    (candidate, candidate_eval)
                } else {
                    (reference, reference_eval)
                };
                return Ok(ScpOutcome {
                    iterate,
                    status: ScpStatus::Converged,
                    evaluation,
                    iterations,
                    solve_time_s: start.elapsed().as_secs_f64(),
                });
            }
            if candidate_eval.feasible(tol) && phi_cand < phi_ref {
                // the model promised nothing (its linearised rows keep a slack the true
                // constraints do not need), yet its solution is feasible and better than an
                // infeasible reference: take it, and go on from there (the default scenario, 3
                // windows, seed 5: Step 1 of window 1 raised λ to 10⁷ against a feasible
                // candidate and gave up with two AUVs 1.58 m apart)
                record.accepted = true;
                problem.judged(&candidate, true);
                observer(&record);
                previous = Some(std::mem::replace(&mut reference, candidate));
                reference_eval = candidate_eval;
                have_feasible_reference = true;
                keep_if_best(&mut best, &reference, reference_eval, tol);
                continue;
            }
            observer(&record);
            if penalty < settings.penalty * PENALTY_MAX_FACTOR {
                penalty *= PENALTY_GROWTH;
                standing = 0;
                continue;
            }
            status = ScpStatus::Stalled;
            break; // stuck infeasible: the best feasible iterate, if any, or the error below
        }

        if first || ratio >= RHO0 {
            record.accepted = true;
            problem.judged(&candidate, true);
            // the momentum builds over good steps (ρ ≥ RHO2: the model is trusted)
            good_run = !first && ratio >= RHO2;
            momentum = if good_run { next_momentum } else { 1.0 };
            steer(&mut standing, &mut penalty, settings, stands);
            previous = Some(std::mem::replace(&mut reference, candidate));
            reference_eval = candidate_eval;
            have_feasible_reference = true;
            keep_if_best(
                &mut best,
                &reference,
                reference_eval,
                settings.feasibility_tol,
            );
        } else {
            problem.judged(&candidate, false);
            good_run = false;
            momentum = 1.0;
        }
        if !first {
            if ratio < RHO0 {
                cooldown = GROWTH_COOLDOWN;
            } else {
                cooldown = cooldown.saturating_sub(1);
            }
            if ratio < RHO1 {
                radius = shrunk(radius, step);
            } else if ratio > RHO2 && cooldown == 0 {
                radius = (radius * GROW).min(max_radius);
            }
        }
        iterations += 1;
        observer(&record);
        if radius < settings.min_trust_region {
            status = ScpStatus::Stalled;
            break;
        }
    }

    if !reference_eval.feasible(settings.feasibility_tol) {
        if let Some((x, e)) = best {
            (reference, reference_eval) = (x, e);
        }
    }
    if have_feasible_reference && reference_eval.feasible(settings.feasibility_tol) {
        Ok(ScpOutcome {
            iterate: reference,
            status,
            evaluation: reference_eval,
            iterations,
            solve_time_s: start.elapsed().as_secs_f64(),
        })
    } else if have_feasible_reference && status == ScpStatus::MaxIterations {
        Err(problem.unfinished(&reference, iterations))
    } else if have_feasible_reference {
        Err(problem.infeasible(&reference))
    } else {
        Err(ScpFailure::NoIterate.into())
    }
}

/// Keep `x` as the best accepted iterate if it meets every constraint (within `tol`) and its
/// objective is the lowest so far.
fn keep_if_best<X: Clone>(best: &mut Option<(X, Evaluation)>, x: &X, e: Evaluation, tol: f64) {
    if e.feasible(tol)
        && best
            .as_ref()
            .map_or(true, |(_, b)| e.objective < b.objective)
    {
        *best = Some((x.clone(), e));
    }
}

/// Whether a step from a model reference with violation `before` (Σ, [`Evaluation`]), whose
/// model kept `kept` of it and whose candidate's largest violation is `after`, leaves a
/// violation standing (`STANDING_STEPS`).
fn stands(settings: &Scp, before: f64, kept: Option<f64>, after: f64) -> bool {
    let tol = settings.feasibility_tol;
    after > tol
        && kept.is_some_and(|kept| kept > tol && kept >= (1.0 - VIOLATION_PROGRESS) * before)
}

/// After an accepted step that did (`stands`) or did not leave a violation standing: count it,
/// and grow λ after `STANDING_STEPS` such steps in a row (up to `PENALTY_MAX_FACTOR`·λ₀), as
/// the loop does when it converges with a violation, but without converging first.
fn steer(standing: &mut usize, penalty: &mut f64, settings: &Scp, stands: bool) {
    *standing = if stands { *standing + 1 } else { 0 };
    if *standing >= STANDING_STEPS && *penalty < settings.penalty * PENALTY_MAX_FACTOR {
        *penalty *= PENALTY_GROWTH;
        *standing = 0;
    }
}

/// The radius after a rejected step (ρ < RHO1) of length `step` (None: unknown): half the
/// step, or half the radius if the step reached it, but at most `MAX_SHRINK`-fold at once.
fn shrunk(radius: f64, step: Option<f64>) -> f64 {
    let floor = radius / MAX_SHRINK;
    step.map_or(radius, |s| s.min(radius)).max(floor * SHRINK) / SHRINK
}

/// Failures of the SCP loop itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum ScpFailure {
    #[error("sequential convex programming produced no iterate")]
    NoIterate,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::conic::{ConicSolution, ConicSolver, Pattern, Triplets};
    use clarabel::solver::SupportedConeT::*;

    /// Solve min ½xᵀPx + qᵀx s.t. Ax + s = b, s ∈ `cones` over `n` variables in the solver of
    /// `slot`, built at the first call and updated (same pattern) at the later ones.
    fn solve_in(
        slot: &mut Option<ConicSolver>,
        n: usize,
        (p, q): (&Triplets, &[f64]),
        (a, b): (&Triplets, &[f64]),
        cones: &[clarabel::solver::SupportedConeT<f64>],
    ) -> ConicSolution {
        let s = match slot {
            Some(s) => {
                s.update(&p.vals, q, &a.vals, b).unwrap();
                s
            }
            None => slot.insert(
                ConicSolver::new(
                    Pattern::new(n, n, p),
                    q,
                    Pattern::new(b.len(), n, a),
                    b,
                    cones,
                )
                .unwrap(),
            ),
        };
        s.solve()
    }

    /// min x² + y² s.t. the nonconvex constraint x·y ≥ 1 (so g = 1 − xy ≤ 0), from (3, 0.5).
    /// The optimum is x = y = 1, objective 2.
    struct Hyperbola {
        solver: Option<ConicSolver>,
        /// A model with a trust radius above this fails as a solver in numerical trouble
        /// would (`Fail::Trouble`).
        trouble_above: f64,
    }

    #[derive(Debug, PartialEq)]
    enum Fail {
        Other,
        Trouble,
    }
    impl From<ScpFailure> for Fail {
        fn from(_: ScpFailure) -> Self {
            Fail::Other
        }
    }

    impl ScpProblem for Hyperbola {
        type Iterate = [f64; 2];
        type Error = Fail;
        type Report = ();
        fn solve_model(
            &mut self,
            r: &[f64; 2],
            radius: f64,
            penalty: f64,
        ) -> Result<([f64; 2], f64, ()), Fail> {
            if radius > self.trouble_above {
                return Err(Fail::Trouble);
            }
            // variables x, y, ν; g_lin = 1 − x̄ȳ − ȳ(x − x̄) − x̄(y − ȳ) ≤ ν
            let mut p = Triplets::default();
            p.push(0, 0, 2.0);
            p.push(1, 1, 2.0);
            let mut a = Triplets::default();
            a.push(0, 0, -r[1]);
            a.push(0, 1, -r[0]);
            a.push(0, 2, -1.0);
            a.push(1, 2, -1.0);
            a.push(3, 0, -1.0);
            a.push(4, 1, -1.0);
            let b = [-1.0 - r[0] * r[1], 0.0, radius, -r[0], -r[1]];
            let q = [0.0, 0.0, penalty];
            let cones = [NonnegativeConeT(2), SecondOrderConeT(3)];
            let sol = solve_in(&mut self.solver, 3, (&p, &q), (&a, &b), &cones);
            assert!(sol.usable());
            let x = [sol.x[0], sol.x[1]];
            let merit = sol.x[0].powi(2) + sol.x[1].powi(2) + penalty * sol.x[2];
            Ok((x, merit, ()))
        }
        fn evaluate(&self, x: &[f64; 2]) -> Evaluation {
            let v = (1.0 - x[0] * x[1]).max(0.0);
            Evaluation {
                objective: x[0] * x[0] + x[1] * x[1],
                violation: v,
                max_violation: v,
                magnitude: x[0] * x[0] + x[1] * x[1],
            }
        }
        fn infeasible(&self, _: &[f64; 2]) -> Fail {
            Fail::Other
        }
        fn numerical_trouble(&self, e: &Fail) -> bool {
            *e == Fail::Trouble
        }
    }

    /// min −x s.t. x ≤ 1, whose model is the problem itself: the merit −x + λ·max(0, x − 1)
    /// has its minimum at x = 1 for λ > 1 and none for λ < 1 (it falls without end past 1).
    /// `kept`: the violation the last model's solution kept.
    struct Ceiling {
        kept: f64,
    }

    impl ScpProblem for Ceiling {
        type Iterate = f64;
        type Error = Fail;
        type Report = ();
        fn solve_model(
            &mut self,
            r: &f64,
            radius: f64,
            penalty: f64,
        ) -> Result<(f64, f64, ()), Fail> {
            let x = if penalty < 1.0 {
                r + radius
            } else {
                1.0f64.clamp(r - radius, r + radius)
            };
            self.kept = (x - 1.0).max(0.0);
            Ok((x, -x + penalty * self.kept, ()))
        }
        fn kept_violation(&self) -> Option<f64> {
            Some(self.kept)
        }
        fn evaluate(&self, x: &f64) -> Evaluation {
            let v = (x - 1.0).max(0.0);
            Evaluation {
                objective: -x,
                violation: v,
                max_violation: v,
                magnitude: x.abs(),
            }
        }
        fn infeasible(&self, _: &f64) -> Fail {
            Fail::Other
        }
    }

    /// Issue 22 (issue 13's draw 3033): a penalty too small for the problem is raised after
    /// `STANDING_STEPS` accepted steps that leave a violation standing, not only when the loop
    /// converges with it. With λ₀ = 0.5 each model steps x up by the whole (growing) radius,
    /// predicting a decrease that never becomes negligible: the loop used to walk past the
    /// ceiling to its iteration limit. Steered, λ becomes 5 after three such steps and the
    /// next step lands on the optimum x = 1.
    #[test]
    fn a_violation_left_standing_raises_the_penalty_before_convergence() {
        let settings = Scp {
            trust_region: 0.5,
            penalty: 0.5,
            tolerance: 1e-7,
            ..Scp::default()
        };
        let (mut violations, mut penalties) = (Vec::new(), Vec::new());
        let out = solve(&mut Ceiling { kept: 0.0 }, 0.0, &settings, &mut |it| {
            violations.push(it.violation);
            penalties.push(it.penalty);
        })
        .unwrap();
        // each iteration reports the λ its merits were measured with: λ₀ for the five steps up
        // to the third standing one, then 10·λ₀
        assert_eq!(penalties, [0.5, 0.5, 0.5, 0.5, 0.5, 5.0, 5.0]);
        assert_eq!(out.status, ScpStatus::Converged);
        assert!((out.iterate - 1.0).abs() < 1e-12, "x = {}", out.iterate);
        assert_eq!(out.evaluation.max_violation, 0.0);
        // two feasible steps (0.5, then 1 with the radius grown to 1), three that leave the
        // violation standing (x = 2, 4, 8), the step back to the ceiling and the negligible
        // one that ends the loop
        assert_eq!(out.iterations, 7, "violations {violations:?}");
        assert_eq!(
            violations
                .iter()
                .filter(|&&v| v > settings.feasibility_tol)
                .count(),
            STANDING_STEPS
        );
    }

    /// The SCP settings of the hyperbola tests: a tight tolerance, a small first radius.
    fn settings() -> Scp {
        Scp {
            trust_region: 0.5,
            penalty: 10.0,
            tolerance: 1e-7,
            ..Scp::default()
        }
    }

    #[test]
    fn scvx_finds_the_known_optimum_of_a_nonconvex_problem() {
        let settings = settings();
        let mut seen = 0;
        let out = solve(
            &mut Hyperbola {
                solver: None,
                trouble_above: f64::INFINITY,
            },
            [3.0, 0.5],
            &settings,
            &mut |_| seen += 1,
        )
        .unwrap();
        assert_eq!(out.status, ScpStatus::Converged);
        assert_eq!(seen, out.iterations);
        assert!((out.iterate[0] - 1.0).abs() < 1e-4, "{:?}", out.iterate);
        assert!((out.iterate[1] - 1.0).abs() < 1e-4, "{:?}", out.iterate);
        assert!(out.evaluation.max_violation < 1e-6);
    }

    /// The hyperbola, noting the accuracy the loop asks for before each model and the
    /// reference each model is built about.
    struct Recording {
        inner: Hyperbola,
        asked: Vec<f64>,
        references: Vec<[f64; 2]>,
    }

    impl ScpProblem for Recording {
        type Iterate = [f64; 2];
        type Error = Fail;
        type Report = ();
        fn solve_model(
            &mut self,
            r: &[f64; 2],
            radius: f64,
            penalty: f64,
        ) -> Result<([f64; 2], f64, ()), Fail> {
            self.references.push(*r);
            self.inner.solve_model(r, radius, penalty)
        }
        fn evaluate(&self, x: &[f64; 2]) -> Evaluation {
            self.inner.evaluate(x)
        }
        fn infeasible(&self, x: &[f64; 2]) -> Fail {
            self.inner.infeasible(x)
        }
        fn set_accuracy(&mut self, gap: f64) {
            self.asked.push(gap);
        }
    }

    /// Issue 22: each model is solved only as exactly as the stopping test reads it, a tenth
    /// of tolerance·(1 + magnitude) of the model's reference, asked for before every solve.
    #[test]
    fn each_model_is_asked_for_a_tenth_of_the_stopping_threshold() {
        let settings = settings();
        let mut problem = Recording {
            inner: Hyperbola {
                solver: None,
                trouble_above: f64::INFINITY,
            },
            asked: Vec::new(),
            references: Vec::new(),
        };
        let out = solve(&mut problem, [3.0, 0.5], &settings, &mut |_| {}).unwrap();
        assert_eq!(problem.asked.len(), out.iterations);
        assert_eq!(problem.references.len(), out.iterations);
        for (gap, r) in problem.asked.iter().zip(&problem.references) {
            let threshold = settings.tolerance * (1.0 + problem.inner.evaluate(r).magnitude);
            assert!(
                (gap - 0.1 * threshold).abs() <= 1e-15 * threshold,
                "{gap} for {r:?}"
            );
        }
        // the first reference, (3, 0.5): magnitude 9.25
        assert!((problem.asked[0] - 0.1 * 1e-7 * 10.25).abs() < 1e-20);
    }

    /// Regression (issue 13's property test: "step3: the convex subproblem failed: Clarabel
    /// status NumericalError" on a feasible mission): a convex solve in numerical trouble ended
    /// the plan. The loop now treats it as a rejected step, and the smaller model solves: here
    /// every model with a radius above 0.2 fails, and the loop still finds the optimum from a
    /// radius of 0.5; with trouble at every radius it gives up after 3 retries in a row, with
    /// the error from an infeasible start, and from a feasible one with that start and the
    /// status "solver_trouble".
    #[test]
    fn regression_a_solve_in_numerical_trouble_is_a_rejected_step() {
        let settings = settings();
        let mut problem = Hyperbola {
            solver: None,
            trouble_above: 0.2,
        };
        let out = solve(&mut problem, [3.0, 0.5], &settings, &mut |it| {
            assert!(it.trust_region <= 0.2 * GROW);
        });
        let out = out.unwrap();
        assert!((out.iterate[0] - 1.0).abs() < 1e-4, "{:?}", out.iterate);
        let mut always = Hyperbola {
            solver: None,
            trouble_above: 0.0,
        };
        let e = solve(&mut always, [0.5, 0.5], &settings, &mut |_| {});
        assert_eq!(e.err(), Some(Fail::Trouble));
        let mut always = Hyperbola {
            solver: None,
            trouble_above: 0.0,
        };
        let out = solve(&mut always, [3.0, 0.5], &settings, &mut |_| {}).unwrap();
        assert_eq!(
            (out.status, out.iterate),
            (ScpStatus::SolverTrouble, [3.0, 0.5])
        );
    }

    /// Regression (issue 13's sweep, draw 1056: `shoal check` failed a plan whose Step 3 was
    /// "max_iterations" with 49 entries in its log of 50): retries after numerical trouble
    /// counted against scp.max_iterations. The limit now counts the solves of the log; here
    /// the first model's radius (0.5) fails twice before one solves, and the loop still logs
    /// as many iterations as it is allowed.
    #[test]
    fn regression_retries_after_numerical_trouble_are_not_iterations() {
        let settings = Scp {
            max_iterations: 3,
            ..settings()
        };
        let mut problem = Hyperbola {
            solver: None,
            trouble_above: 0.2,
        };
        let mut logged = 0;
        let out = solve(&mut problem, [3.0, 0.5], &settings, &mut |_| logged += 1).unwrap();
        assert_eq!(out.status, ScpStatus::MaxIterations);
        assert_eq!((logged, out.iterations), (3, 3));
    }

    /// min a/2·‖x − t‖² − b/2·‖x‖² over x ∈ ℝ², b < a: the concave reward −b/2·‖x‖² is
    /// linearised about the reference (a majorant, as OF1_5 and OF1_8 are), so the SCP is a
    /// majorisation-minimisation whose steps shrink by b/a each (0.95 here): the slow tail of
    /// issue 22. The optimum is x* = a·t/(a − b).
    struct Tail {
        solver: Option<ConicSolver>,
        /// `ScpProblem::ends_on_a_better_candidate`.
        ends_on_candidate: bool,
    }
    impl Tail {
        fn new() -> Tail {
            Tail {
                solver: None,
                ends_on_candidate: true,
            }
        }
    }
    const A: f64 = 1.0;
    const B: f64 = 0.95;
    const T: [f64; 2] = [1.0, -0.5];

    impl ScpProblem for Tail {
        type Iterate = [f64; 2];
        type Error = Fail;
        type Report = ();
        fn solve_model(
            &mut self,
            r: &[f64; 2],
            radius: f64,
            _penalty: f64,
        ) -> Result<([f64; 2], f64, ()), Fail> {
            // a/2·‖x‖² − (a·t + b·r)ᵀx (+ constant) s.t. ‖x − r‖ ≤ Δ
            let mut p = Triplets::default();
            p.push(0, 0, A);
            p.push(1, 1, A);
            let q = [-(A * T[0] + B * r[0]), -(A * T[1] + B * r[1])];
            let mut a = Triplets::default();
            a.push(1, 0, -1.0);
            a.push(2, 1, -1.0);
            let b = [radius, -r[0], -r[1]];
            let cones = [SecondOrderConeT(3)];
            let sol = solve_in(&mut self.solver, 2, (&p, &q), (&a, &b), &cones);
            assert!(sol.usable());
            let x = [sol.x[0], sol.x[1]];
            let rr = r[0] * r[0] + r[1] * r[1];
            let model = A / 2.0 * ((x[0] - T[0]).powi(2) + (x[1] - T[1]).powi(2))
                - B / 2.0 * rr
                - B * (r[0] * (x[0] - r[0]) + r[1] * (x[1] - r[1]));
            Ok((x, model, ()))
        }
        fn extrapolate(&self, x: &[f64; 2], prev: &[f64; 2], beta: f64) -> Option<[f64; 2]> {
            Some([
                x[0] + beta * (x[0] - prev[0]),
                x[1] + beta * (x[1] - prev[1]),
            ])
        }
        fn step_length(&self, a: &[f64; 2], b: &[f64; 2]) -> Option<f64> {
            Some((a[0] - b[0]).hypot(a[1] - b[1]))
        }
        fn ends_on_a_better_candidate(&self) -> bool {
            self.ends_on_candidate
        }
        fn evaluate(&self, x: &[f64; 2]) -> Evaluation {
            let f = A / 2.0 * ((x[0] - T[0]).powi(2) + (x[1] - T[1]).powi(2))
                - B / 2.0 * (x[0] * x[0] + x[1] * x[1]);
            Evaluation {
                objective: f,
                violation: 0.0,
                max_violation: 0.0,
                magnitude: f.abs(),
            }
        }
        fn infeasible(&self, _: &[f64; 2]) -> Fail {
            Fail::Other
        }
    }

    /// Issue 22: the loop that stops converged ends on its last candidate, which it solved and
    /// judged already, when that one is feasible and better than the reference; the problem
    /// can decline it (P2 does: `TeamProblem::ends_on_a_better_candidate`), and the loop then
    /// ends on the reference, one tail step behind.
    #[test]
    fn a_converged_loop_ends_on_its_last_candidate_when_that_one_is_better() {
        let settings = Scp {
            trust_region: 100.0,
            tolerance: 1e-3,
            max_iterations: 1000,
            ..Scp::default()
        };
        let run = |ends_on_candidate: bool| {
            let mut log = Vec::new();
            let mut tail = Tail {
                ends_on_candidate,
                ..Tail::new()
            };
            let out = solve(&mut tail, [0.0, 0.0], &settings, &mut |it| {
                log.push(it.clone())
            })
            .unwrap();
            assert_eq!(out.status, ScpStatus::Converged);
            (out, log)
        };
        let (kept, log) = run(true);
        let last = log.last().unwrap();
        assert!(last.accepted, "the last candidate is kept");
        assert!(last.merit_after < last.merit_before);
        assert_eq!(kept.evaluation.objective, last.merit_after);
        let (declined, log2) = run(false);
        assert_eq!(log2.len(), log.len(), "the same iterations either way");
        assert!(!log2.last().unwrap().accepted);
        assert_eq!(declined.evaluation.objective, last.merit_before);
        assert!(kept.evaluation.objective < declined.evaluation.objective);
    }

    /// Issue 22: a rejected step shrinks the radius to half the step it took, at most 16-fold
    /// (a model trusted to 12.8 km whose 40 m step failed took eight halvings to get there).
    #[test]
    fn a_rejected_step_shrinks_the_radius_below_the_step_it_took() {
        assert_eq!(shrunk(100.0, Some(40.0)), 20.0);
        assert_eq!(shrunk(100.0, Some(1000.0)), 50.0);
        assert_eq!(shrunk(100.0, None), 50.0);
        assert_eq!(shrunk(12_800.0, Some(40.0)), 800.0);
        assert_eq!(shrunk(12_800.0, Some(0.0)), 800.0);
    }

    /// Issue 22: the momentum step (scp.momentum) reaches the known optimum of a slow
    /// majorisation-minimisation tail in a fraction of the iterations the plain SCvx needs.
    #[test]
    fn momentum_shortens_a_slow_majorisation_tail_to_the_same_optimum() {
        let optimum = T.map(|t| A * t / (A - B));
        let run = |momentum: bool| {
            let settings = Scp {
                trust_region: 100.0,
                tolerance: 1e-9,
                max_iterations: 1000,
                momentum,
                ..Scp::default()
            };
            let out = solve(&mut Tail::new(), [0.0, 0.0], &settings, &mut |_| {}).unwrap();
            assert_eq!(out.status, ScpStatus::Converged);
            for i in 0..2 {
                assert!(
                    (out.iterate[i] - optimum[i]).abs() < 1e-3 * optimum[i].abs(),
                    "momentum {momentum}: {:?} against {optimum:?}",
                    out.iterate
                );
            }
            out.iterations
        };
        let (plain, with) = (run(false), run(true));
        assert!(with * 3 < plain, "with momentum {with}, without {plain}");
    }
}
