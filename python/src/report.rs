//! The checker's report as JSON for Python (`shoal.CheckReport`).

use shoal::check::CheckReport;

/// The report as JSON: passed, the families (their margins), problems and fingerprints.
pub(crate) fn report_json(r: &CheckReport) -> String {
    // margins may be ±∞ (nothing checked, or not evaluable): JSON has no infinity, so they
    // travel as strings and Python turns them back into floats
    let num = |v: f64| {
        if v.is_finite() {
            serde_json::json!(v)
        } else {
            serde_json::json!(v.to_string())
        }
    };
    let families: Vec<serde_json::Value> = r
        .families
        .iter()
        .map(|f| {
            serde_json::json!({
                "name": f.name,
                "checked": f.checked,
                "worst_margin": num(f.worst_margin),
                "unit": f.unit,
                "tolerance": num(f.tolerance),
                "where": f.where_,
                "passed": f.passed(),
            })
        })
        .collect();
    serde_json::json!({
        "passed": r.passed(),
        "families": families,
        "problems": r.problems,
        "plan_fingerprint": r.plan_fingerprint,
        "floor_fingerprint": r.floor_fingerprint,
    })
    .to_string()
}
