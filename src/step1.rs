//! Step 1 of Section IV-A: problem P2 — energy-efficient, floor-following, collision-free paths
//! for the USV and the AUVs, with the graph terms of P1 relaxed (Algorithm 1, line 9).
//!
//!   OF2:  min Σ_k ( w1·OF1_1 + w2·OF1_2 ) − w8·OF1_8     (or + w8_2·OF1_8_2)
//!   s.t.  C2_1 = C1_1…C1_7, C2_2 (floor clearance), C1_14 (heading rate)
//!
//! P2 is the window problem of `team` without acoustic links (every constraint family is
//! there, one file each), solved by the SCvx loop of `scp` from the formation guess of
//! `team::guess`. With `usv.courses` > 1 the first window first tries that many first guesses,
//! one SCP iteration each, and starts from the best (`first_course`).

use crate::conic::SolveReport;
use crate::error::PlanError;
use crate::plan::Course;
use crate::scenario::UsvObjective;
use crate::scp::{Iteration, ScpOutcome};
use crate::team::TeamProblem;
use crate::trajectory::Trajectory;

/// Solve P2 for the window of `problem` (built without links). `heading` is the USV's course at
/// the end of the previous window, if any: the first guess continues it. `observer` hears of
/// every SCP iteration. Returns the outcome and the first courses tried (empty unless this is
/// the first window, with objective "away" and `usv.courses` > 1).
pub fn solve(
    problem: &mut TeamProblem,
    heading: Option<f64>,
    observer: &mut dyn FnMut(&Iteration<SolveReport>),
) -> Result<(ScpOutcome<Trajectory>, Vec<Course>), PlanError> {
    let usv = &problem.scenario().usv;
    let (heading, trials) =
        if heading.is_none() && usv.objective == UsvObjective::Away && usv.courses > 1 {
            let trials = first_course(problem);
            // every solve failed: the initial heading, as with one course
            let best = Course::best(&trials).map_or(usv.initial_heading, |c| c.heading);
            (Some(best), trials)
        } else {
            (heading, Vec::new())
        };
    let guess = problem.initial_guess(heading);
    Ok((problem.solve(guess, observer)?, trials))
}

/// The first window's courses: `usv.initial_heading` and `usv.courses − 1` more, evenly spaced
/// round the compass, each scored by the merit one SCP iteration reaches from its formation
/// guess. The SCP is a local method: from one course it keeps close to it (each linearised
/// model of the concave OF1_8 charges a turn), and over a window's courses the objective
/// spreads by 6–20 % at N = 3 and 5 (docs/method.md, "OF1_8"; docs/design-decisions.md, "First courses").
/// From three courses on, one more is tried: at the vertex of the parabola through the best
/// course's merit and its two neighbours' (`vertex`), between the courses the even spacing left
/// out.
fn first_course(problem: &mut TeamProblem) -> Vec<Course> {
    let usv = &problem.scenario().usv;
    let (first, m) = (usv.initial_heading, usv.courses);
    let mut probe = |heading: f64| {
        let guess = problem.initial_guess(Some(heading));
        let merit = problem.first_merit(guess).ok().filter(|m| m.is_finite());
        Course { heading, merit }
    };
    let mut courses: Vec<Course> = (0..m)
        .map(|j| probe(first + j as f64 * std::f64::consts::TAU / m as f64))
        .collect();
    if let Some(heading) = vertex(&courses) {
        courses.push(probe(heading));
    }
    courses
}

/// The vertex of the parabola through the merits of the best of `courses` (evenly spaced round
/// the compass) and of its two neighbours, within half a spacing of the best; `None` with
/// fewer than three courses, a neighbour whose solve failed, or no curvature.
fn vertex(courses: &[Course]) -> Option<f64> {
    let m = courses.len();
    if m < 3 {
        return None;
    }
    let best = Course::best(courses)?;
    let j = courses.iter().position(|c| std::ptr::eq(c, best))?;
    let (fl, f0, fr) = (
        courses[(j + m - 1) % m].merit?,
        best.merit?,
        courses[(j + 1) % m].merit?,
    );
    let h = std::f64::consts::TAU / m as f64;
    let curvature = fl - 2.0 * f0 + fr;
    if curvature <= 0.0 {
        return None;
    }
    let offset = (h * (fl - fr) / (2.0 * curvature)).clamp(-h / 2.0, h / 2.0);
    (offset.abs() > 1e-9 * h).then_some(best.heading + offset)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn course(heading: f64, merit: Option<f64>) -> Course {
        Course { heading, merit }
    }

    #[test]
    fn the_least_merit_wins_and_the_first_on_a_tie() {
        let t = [
            course(0.0, Some(-5.0)),
            course(1.0, Some(-7.0)),
            course(2.0, None),
            course(3.0, Some(-7.0)),
        ];
        assert_eq!(Course::best(&t).map(|c| c.heading), Some(1.0));
    }

    #[test]
    fn the_vertex_of_a_parabola_is_found_between_the_courses() {
        // merits (θ − 1)² about eight evenly spaced courses: the vertex is θ = 1
        let h = std::f64::consts::TAU / 8.0;
        let t: Vec<Course> = (0..8)
            .map(|j| {
                let theta = j as f64 * h;
                course(theta, Some((theta - 1.0).powi(2)))
            })
            .collect();
        let v = vertex(&t).expect("a vertex");
        assert!((v - 1.0).abs() < 1e-12, "{v}");
    }

    #[test]
    fn no_vertex_without_three_courses_a_neighbour_or_curvature() {
        assert_eq!(
            vertex(&[course(0.0, Some(1.0)), course(3.0, Some(0.0))]),
            None
        );
        let t = [
            course(0.0, Some(0.0)),
            course(2.0, None),
            course(4.0, Some(1.0)),
        ];
        assert_eq!(vertex(&t), None);
        let flat = [0.0, 2.0, 4.0].map(|h| course(h, Some(-1.0)));
        assert_eq!(vertex(&flat), None);
    }

    #[test]
    fn every_solve_failed_leaves_no_best() {
        assert_eq!(Course::best(&[course(1.0, None)]), None);
        assert_eq!(Course::best(&[]), None);
    }
}
