//! The four measures the panels show, in panel order ([`METRICS`]): which field of a [`Row`]
//! each reads, whether its panel is on a log scale, its caption and its axis title.

use crate::compare::Row;

/// A panel's measure.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Metric {
    Wall,
    Height,
    Area,
    Energy,
}

pub(super) const METRICS: [Metric; 4] =
    [Metric::Wall, Metric::Height, Metric::Area, Metric::Energy];

impl Metric {
    pub(super) fn value(self, r: &Row) -> f64 {
        match self {
            Metric::Wall => r.wall_s,
            Metric::Height => r.mean_height_m,
            Metric::Area => r.explored_km2,
            Metric::Energy => r.energy,
        }
    }

    pub(super) fn log(self) -> bool {
        matches!(self, Metric::Wall | Metric::Energy)
    }

    pub(super) fn caption(self) -> &'static str {
        match self {
            Metric::Wall => "(a) Wall time per plan",
            Metric::Height => "(b) Mean height above the floor (OF1_2: lower)",
            Metric::Area => "(c) Explored area at survey altitude",
            Metric::Energy => "(d) Input energy Σ‖U‖² (OF1_1: lower)",
        }
    }

    pub(super) fn y_desc(self) -> &'static str {
        match self {
            Metric::Wall => "wall time (s, log scale)",
            Metric::Height => "mean height (m)",
            Metric::Area => "explored area (km²)",
            Metric::Energy => "Σ‖U‖² ((m/s²)², log scale)",
        }
    }

    /// The value as plotted: log10 on a log panel; `None` when it cannot be shown.
    pub(super) fn plotted(self, v: f64) -> Option<f64> {
        match (v.is_finite(), self.log()) {
            (false, _) => None,
            (true, true) => (v > 0.0).then(|| v.log10()),
            (true, false) => Some(v),
        }
    }
}
