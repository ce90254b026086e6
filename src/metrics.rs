//! TEMPORARY stub until the metrics branch lands.
use crate::plan::{Link, Metrics, Stage};
use crate::seafloor::Seafloor;
pub struct MetricParams {
    pub dt: f64,
    pub sonar_range: f64,
    pub resolution: f64,
    pub swath_width: f64,
}
pub fn window_metrics(
    _: &Stage,
    _: &[Vec<Link>],
    _: &Seafloor,
    _: &MetricParams,
    t: [f64; 3],
) -> Metrics {
    Metrics {
        step1_time_s: t[0],
        step2_time_s: t[1],
        step3_time_s: t[2],
        ..Default::default()
    }
}
pub fn mission_metrics(
    _: &[(&Stage, &[Vec<Link>])],
    _: &Seafloor,
    _: &MetricParams,
    _: &[[f64; 3]],
) -> Metrics {
    Metrics::default()
}
