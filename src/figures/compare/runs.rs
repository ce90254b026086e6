//! From [`Row`]s to what the panels plot: the methods (ordered, coloured), the N slots (per
//! scenario), one [`Run`] per row with its status and measures, each run's place and jittered x
//! in its slot, the plotted points of a panel and the medians over the seeds.

use super::metric::{Metric, METRICS};
use super::{legend, Compare, FURTHER, MPC, RRT_LIKE, SLOT_USED, WIDTH};
use crate::compare::Row;
use crate::figures::style::Frame;
use crate::figures::FigureError;
use plotters::style::RGBColor;

#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Status {
    Passed,
    Violated,
    Failed,
}

pub(super) struct Method {
    pub(super) name: String,
    pub(super) colour: RGBColor,
}

/// An x position: one team size of one scenario.
pub(super) struct Slot {
    pub(super) scenario: usize,
    pub(super) auvs: usize,
}

pub(super) struct Run {
    pub(super) slot: usize,
    pub(super) method: usize,
    pub(super) seed: u64,
    pub(super) status: Status,
    /// The measures, in the order of [`METRICS`] (NaN when missing).
    pub(super) values: [f64; 4],
}

impl Compare {
    pub(super) fn new(rows: &[Row], title: &str) -> Result<Compare, FigureError> {
        let bad = |why: String| Err(FigureError::Compare(why));
        if rows.is_empty() {
            return bad("there are no runs to plot".into());
        }
        if rows.iter().all(|r| !r.planned()) {
            return bad(format!(
                "none of the {} runs made a plan, so there is nothing to measure",
                rows.len()
            ));
        }

        // Methods: MPC, RRT-like, then the others in order of appearance.
        let mut names: Vec<&str> = Vec::new();
        for r in rows {
            if !names.contains(&r.method.as_str()) {
                names.push(&r.method);
            }
        }
        let rank = |m: &str| match m {
            crate::plan::METHOD_MPC => 0,
            crate::plan::METHOD_RRT_LIKE => 1,
            _ => 2,
        };
        names.sort_by_key(|m| rank(m)); // stable: the others keep their order
        let mut further = FURTHER.iter().cycle();
        let methods: Vec<Method> = names
            .iter()
            .map(|&m| Method {
                name: m.to_string(),
                colour: match rank(m) {
                    0 => MPC,
                    1 => RRT_LIKE,
                    _ => *further.next().unwrap_or(&FURTHER[0]),
                },
            })
            .collect();

        // Slots: per scenario (in order of appearance), its team sizes in increasing order.
        let mut scenarios: Vec<String> = Vec::new();
        for r in rows {
            if !scenarios.contains(&r.scenario) {
                scenarios.push(r.scenario.clone());
            }
        }
        let mut slots = Vec::new();
        for (s, name) in scenarios.iter().enumerate() {
            let mut sizes: Vec<usize> = rows
                .iter()
                .filter(|r| &r.scenario == name)
                .map(|r| r.auvs)
                .collect();
            sizes.sort_unstable();
            sizes.dedup();
            slots.extend(sizes.into_iter().map(|auvs| Slot { scenario: s, auvs }));
        }

        let runs: Vec<Run> = rows
            .iter()
            .map(|r| Run {
                slot: slots
                    .iter()
                    .position(|s| scenarios[s.scenario] == r.scenario && s.auvs == r.auvs)
                    .unwrap_or(0),
                method: names.iter().position(|&m| m == r.method).unwrap_or(0),
                seed: r.seed,
                status: match r.status.as_str() {
                    "failed" => Status::Failed,
                    "violated" => Status::Violated,
                    _ => Status::Passed,
                },
                values: METRICS.map(|m| m.value(r)),
            })
            .collect();

        let entries = legend::entries(&methods, &runs);

        let mut fig = Compare {
            frame: Frame::new(title.to_string(), entries, WIDTH),
            methods,
            scenarios,
            slots,
            runs,
            axes: Vec::new(),
        };
        fig.axes = METRICS.iter().map(|&m| fig.axis(m)).collect();
        Ok(fig)
    }

    /// Index of `metric` in [`METRICS`].
    pub(super) fn index(metric: Metric) -> usize {
        METRICS.iter().position(|&m| m == metric).unwrap_or(0)
    }

    /// Whether a run is drawn in `metric`'s panel: runs with a plan, and in the wall-time panel
    /// also those without (the time they took to give up).
    pub(super) fn shown(run: &Run, metric: Metric) -> bool {
        run.status != Status::Failed || metric == Metric::Wall
    }

    /// The plotted values of `metric`'s panel: (run, y).
    pub(super) fn points(&self, metric: Metric) -> impl Iterator<Item = (&Run, f64)> + '_ {
        let i = Self::index(metric);
        self.runs
            .iter()
            .filter(move |r| Self::shown(r, metric))
            .filter_map(move |r| metric.plotted(r.values[i]).map(|y| (r, y)))
    }

    /// Whether the wall-time panel counts runs without a plan under its slots.
    pub(super) fn counts_failures(&self, metric: Metric) -> bool {
        metric == Metric::Wall && self.runs.iter().any(|r| r.status == Status::Failed)
    }

    /// The medians over seeds of `metric`'s panel, per slot and method, of the runs with a plan:
    /// (slot, method, y).
    pub(super) fn medians(&self, metric: Metric) -> Vec<(usize, usize, f64)> {
        let i = Self::index(metric);
        let mut medians = Vec::new();
        for slot in 0..self.slots.len() {
            for method in 0..self.methods.len() {
                let mut vs: Vec<f64> = self
                    .runs
                    .iter()
                    .filter(|r| r.slot == slot && r.method == method)
                    .filter(|r| r.status != Status::Failed)
                    .map(|r| r.values[i])
                    .filter(|v| metric.plotted(*v).is_some())
                    .collect();
                if let Some(y) = median(&mut vs).and_then(|v| metric.plotted(v)) {
                    medians.push((slot, method, y));
                }
            }
        }
        medians
    }

    /// Centre of `method`'s place in `slot`, and its width.
    pub(super) fn place(&self, slot: usize, method: usize) -> (f64, f64) {
        let band = SLOT_USED / self.methods.len() as f64;
        (
            slot as f64 - SLOT_USED / 2.0 + (method as f64 + 0.5) * band,
            band,
        )
    }

    /// A run's x: its place in its slot, jittered by its seed.
    pub(super) fn x(&self, run: &Run) -> f64 {
        let (centre, band) = self.place(run.slot, run.method);
        centre + 0.6 * band * jitter(run.seed)
    }
}

/// The median of `vs` (finite values), if any.
pub(super) fn median(vs: &mut [f64]) -> Option<f64> {
    if vs.is_empty() {
        return None;
    }
    vs.sort_by(f64::total_cmp);
    let n = vs.len();
    Some(if n % 2 == 1 {
        vs[n / 2]
    } else {
        0.5 * (vs[n / 2 - 1] + vs[n / 2])
    })
}

/// A run's offset within its place, in [−0.5, 0.5): the fractional part of seed × the golden
/// ratio, so that consecutive seeds spread evenly and the same seed always lands in the same
/// spot.
pub(super) fn jitter(seed: u64) -> f64 {
    ((seed % 1_000_003) as f64 * 0.618_033_988_749_895).fract() - 0.5
}
