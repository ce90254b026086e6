//! Problem P3 (OF3 with C3_1, C3_2): the A2U link of one step. P3 minimises
//! Σ_n σ_n,USV ‖P_n − P_USV‖² over 0 ≤ σ ≤ 1, Σ σ = 1: a linear program whose optimum is the
//! vertex at the AUV nearest the USV (the paper says so too). [`a2u_link`] computes that argmin
//! directly.

/// P3: the AUV nearest the USV, which sits on the surface (z = 0), so the distance is
/// ‖(x − x_USV, y − y_USV, z)‖. Ties go to the lowest index; NaN distances rank last.
/// Returns `None` for an empty team.
pub fn a2u_link(usv: [f64; 2], auvs: &[[f64; 3]]) -> Option<usize> {
    let mut best: Option<(usize, f64)> = None;
    for (n, p) in auvs.iter().enumerate() {
        let d = (p[0] - usv[0]).powi(2) + (p[1] - usv[1]).powi(2) + p[2] * p[2];
        let d = if d.is_nan() { f64::INFINITY } else { d };
        if best.map_or(true, |(_, b)| d < b) {
            best = Some((n, d));
        }
    }
    best.map(|(n, _)| n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a2u_link_picks_nearest() {
        let o = [0.0, 0.0];
        assert_eq!(a2u_link(o, &[]), None);
        // Distances √101, 5, 5, 5: a tie among 1, 2 and 3, lowest index wins.
        let auvs = [
            [10.0, 0.0, -1.0],
            [0.0, 3.0, -4.0],
            [5.0, 0.0, 0.0],
            [3.0, 0.0, -4.0],
        ];
        assert_eq!(a2u_link(o, &auvs), Some(1));
        // Depth counts: (1, 1, −9) is farther from a USV at (1, 1) than (4, 1, −1) is.
        let auvs = [[1.0, 1.0, -9.0], [4.0, 1.0, -1.0]];
        assert_eq!(a2u_link([1.0, 1.0], &auvs), Some(1));
        assert_eq!(a2u_link(o, &[[f64::NAN, 0.0, 0.0], [9.0; 3]]), Some(1));
    }
}
