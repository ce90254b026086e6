//! Latitude/longitude to the planner's local metric frame: a local tangent plane on the WGS84
//! ellipsoid.
//!
//! A point (φ, λ) on the ellipsoid (height 0) is taken to Earth-centred Cartesian coordinates
//! and then to east/north/up (ENU) at the mission origin (φ0, λ0); the planner's (x, y) are the
//! east and north components (the orthographic projection onto the tangent plane). The map is
//! exact ECEF→ENU arithmetic; its inverse is solved by Newton's method from the equirectangular
//! guess (meridional and prime-vertical radii of curvature at the origin) and is accurate to
//! about 1e-9 m.
//!
//! # Error of the flat frame
//!
//! The frame is flat, the Earth is not. Measured against geodesic distances on the ellipsoid
//! (Vincenty's inverse formula, in this module's tests, origins at 0°, 30°, 45°, 60° and 80°
//! latitude, 16 bearings):
//!
//! | distance from the origin | distance-from-origin error | scale error of a 150 m link |
//! |---|---|---|
//! | 10 km | 4.2 mm (4.2e-7 relative) | 1.3e-6 (0.19 mm) |
//! | 50 km | 0.52 m (1.0e-5 relative) | 3.1e-5 (4.7 mm) |
//!
//! The tangent plane shortens distances radially by cos(d/R) ≈ 1 − d²/(2R²) and keeps them
//! tangentially, so the error does not depend on latitude to first order. Positions given in
//! latitude/longitude map to the frame and back exactly (to 1e-9 m); only lengths and angles
//! are distorted, as above. Beyond [`MAX_FRAME_DISTANCE`] the frame is refused.

use super::SeafloorError;

/// WGS84 semi-major axis, metres.
pub const WGS84_A: f64 = 6_378_137.0;
/// WGS84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;
/// WGS84 first eccentricity squared, e² = f(2 − f).
const E2: f64 = WGS84_F * (2.0 - WGS84_F);

/// Largest |latitude| of a mission origin, degrees. The Newton start (equirectangular) needs
/// cos φ0 well away from 0.
pub const MAX_ORIGIN_LATITUDE: f64 = 85.0;

/// Farthest a point of the planner's frame may lie from the origin, metres (radial scale error
/// 7.7e-4 there; see the module docs).
pub const MAX_FRAME_DISTANCE: f64 = 250_000.0;

/// Meridional radius of curvature M(φ), metres.
pub fn meridional_radius(lat_deg: f64) -> f64 {
    let s = lat_deg.to_radians().sin();
    WGS84_A * (1.0 - E2) / (1.0 - E2 * s * s).powf(1.5)
}

/// Prime-vertical radius of curvature N(φ), metres.
pub fn prime_vertical_radius(lat_deg: f64) -> f64 {
    let s = lat_deg.to_radians().sin();
    WGS84_A / (1.0 - E2 * s * s).sqrt()
}

/// The local tangent plane (x east, y north, metres) at a mission origin on WGS84.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFrame {
    lat0: f64,
    lon0: f64,
    sin0: f64,
    cos0: f64,
    /// ECEF of the origin in the frame rotated to λ0 = 0: (X0, Z0) (Y0 = 0).
    x0: f64,
    z0: f64,
}

impl LocalFrame {
    /// The frame at (lat0, lon0), degrees. Requires finite values and |lat0| ≤
    /// [`MAX_ORIGIN_LATITUDE`].
    pub fn new(lat0: f64, lon0: f64) -> Result<LocalFrame, SeafloorError> {
        if !(lat0.is_finite() && lat0.abs() <= MAX_ORIGIN_LATITUDE) {
            return Err(SeafloorError::InvalidQuery {
                what: "origin latitude",
                reason: format!(
                    "{lat0}°: expected a latitude within ±{MAX_ORIGIN_LATITUDE}° \
                     (the local tangent plane is not set up nearer the poles)"
                ),
            });
        }
        if !(lon0.is_finite() && lon0.abs() <= 360.0) {
            return Err(SeafloorError::InvalidQuery {
                what: "origin longitude",
                reason: format!("{lon0}°: expected a longitude within ±360°"),
            });
        }
        let (sin0, cos0) = lat0.to_radians().sin_cos();
        let n0 = prime_vertical_radius(lat0);
        Ok(LocalFrame {
            lat0,
            lon0,
            sin0,
            cos0,
            x0: n0 * cos0,
            z0: n0 * (1.0 - E2) * sin0,
        })
    }

    /// [lat0, lon0], degrees.
    pub fn origin(&self) -> [f64; 2] {
        [self.lat0, self.lon0]
    }

    /// Metres per degree east and north at the origin: N(φ0)·cos φ0 and M(φ0), per degree.
    pub fn metres_per_degree(&self) -> [f64; 2] {
        let rad = std::f64::consts::PI / 180.0;
        [
            prime_vertical_radius(self.lat0) * self.cos0 * rad,
            meridional_radius(self.lat0) * rad,
        ]
    }

    /// (x east, y north), metres, of the ellipsoid point (lat, lon), degrees.
    pub fn to_local(&self, lat: f64, lon: f64) -> [f64; 2] {
        let (sp, cp) = lat.to_radians().sin_cos();
        let (sl, cl) = (lon - self.lon0).to_radians().sin_cos();
        let n = prime_vertical_radius(lat);
        let (px, py, pz) = (n * cp * cl, n * cp * sl, n * (1.0 - E2) * sp);
        [py, -self.sin0 * (px - self.x0) + self.cos0 * (pz - self.z0)]
    }

    /// Whether (lat, lon) is within [`MAX_FRAME_DISTANCE`] of the origin, by the frame's own
    /// (x, y) and a check that the point is on the origin's side of the Earth.
    pub fn within_range(&self, lat: f64, lon: f64) -> bool {
        let dlon = (lon - self.lon0).to_radians();
        let (sp, cp) = lat.to_radians().sin_cos();
        let cos_angle = self.sin0 * sp + self.cos0 * cp * dlon.cos();
        let [x, y] = self.to_local(lat, lon);
        cos_angle > 0.9 && x.hypot(y) <= MAX_FRAME_DISTANCE
    }

    /// (lat, lon), degrees, of the frame point (x, y), metres: the inverse of
    /// [`to_local`](Self::to_local). None when (x, y) is not finite or farther than
    /// [`MAX_FRAME_DISTANCE`] from the origin.
    pub fn to_geographic(&self, x: f64, y: f64) -> Option<[f64; 2]> {
        if !(x.is_finite() && y.is_finite()) || x.hypot(y) > MAX_FRAME_DISTANCE {
            return None;
        }
        let [me, mn] = self.metres_per_degree();
        let (mut lat, mut dlon) = (self.lat0 + y / mn, x / me);
        for _ in 0..20 {
            let [e, n] = self.to_local(lat, self.lon0 + dlon);
            let (rx, ry) = (x - e, y - n);
            if rx.abs() < 1e-10 && ry.abs() < 1e-10 {
                break;
            }
            // Jacobian of (e, n) with respect to (φ, Δλ), per radian.
            let (sp, cp) = lat.to_radians().sin_cos();
            let (sl, cl) = dlon.to_radians().sin_cos();
            let (m, nn) = (meridional_radius(lat), prime_vertical_radius(lat));
            let (e_p, e_l) = (-m * sp * sl, nn * cp * cl);
            let (n_p, n_l) = (
                m * (self.sin0 * sp * cl + self.cos0 * cp),
                nn * cp * self.sin0 * sl,
            );
            let det = e_p * n_l - e_l * n_p;
            if det.abs() < 1e-6 {
                return None;
            }
            let dp = (rx * n_l - ry * e_l) / det;
            let dl = (ry * e_p - rx * n_p) / det;
            lat += dp.to_degrees();
            dlon += dl.to_degrees();
        }
        let back = self.to_local(lat, self.lon0 + dlon);
        ((back[0] - x).abs() < 1e-6 && (back[1] - y).abs() < 1e-6)
            .then_some([lat, self.lon0 + dlon])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Geodesic distance on WGS84 between two points, metres: Vincenty's inverse formula
    /// (T. Vincenty, Survey Review 23(176), 1975), an independent reference for the frame.
    fn vincenty(lat1: f64, lon1: f64, lat2: f64, lon2: f64) -> f64 {
        let (a, f) = (WGS84_A, WGS84_F);
        let b = a * (1.0 - f);
        let l = (lon2 - lon1).to_radians();
        let u1 = ((1.0 - f) * lat1.to_radians().tan()).atan();
        let u2 = ((1.0 - f) * lat2.to_radians().tan()).atan();
        let (su1, cu1) = u1.sin_cos();
        let (su2, cu2) = u2.sin_cos();
        let mut lambda = l;
        for _ in 0..200 {
            let (sl, cl) = lambda.sin_cos();
            let sin_sigma = ((cu2 * sl).powi(2) + (cu1 * su2 - su1 * cu2 * cl).powi(2)).sqrt();
            if sin_sigma == 0.0 {
                return 0.0;
            }
            let cos_sigma = su1 * su2 + cu1 * cu2 * cl;
            let sigma = sin_sigma.atan2(cos_sigma);
            let sin_alpha = cu1 * cu2 * sl / sin_sigma;
            let cos2_alpha = 1.0 - sin_alpha * sin_alpha;
            let cos_2sm = if cos2_alpha == 0.0 {
                0.0
            } else {
                cos_sigma - 2.0 * su1 * su2 / cos2_alpha
            };
            let c = f / 16.0 * cos2_alpha * (4.0 + f * (4.0 - 3.0 * cos2_alpha));
            let prev = lambda;
            lambda = l
                + (1.0 - c)
                    * f
                    * sin_alpha
                    * (sigma
                        + c * sin_sigma
                            * (cos_2sm + c * cos_sigma * (-1.0 + 2.0 * cos_2sm * cos_2sm)));
            if (lambda - prev).abs() < 1e-13 {
                let u_sq = cos2_alpha * (a * a - b * b) / (b * b);
                let ka = 1.0
                    + u_sq / 16384.0 * (4096.0 + u_sq * (-768.0 + u_sq * (320.0 - 175.0 * u_sq)));
                let kb = u_sq / 1024.0 * (256.0 + u_sq * (-128.0 + u_sq * (74.0 - 47.0 * u_sq)));
                let d_sigma = kb
                    * sin_sigma
                    * (cos_2sm
                        + kb / 4.0
                            * (cos_sigma * (-1.0 + 2.0 * cos_2sm * cos_2sm)
                                - kb / 6.0
                                    * cos_2sm
                                    * (-3.0 + 4.0 * sin_sigma * sin_sigma)
                                    * (-3.0 + 4.0 * cos_2sm * cos_2sm)));
                return b * ka * (sigma - d_sigma);
            }
        }
        panic!("Vincenty did not converge");
    }

    /// ECEF → ENU with the full rotation (not the λ0 = 0 shortcut of the frame).
    fn enu_reference(lat0: f64, lon0: f64, lat: f64, lon: f64) -> [f64; 2] {
        let ecef = |lat: f64, lon: f64| {
            let (sp, cp) = lat.to_radians().sin_cos();
            let (sl, cl) = lon.to_radians().sin_cos();
            let n = prime_vertical_radius(lat);
            [n * cp * cl, n * cp * sl, n * (1.0 - E2) * sp]
        };
        let (p, o) = (ecef(lat, lon), ecef(lat0, lon0));
        let d = [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
        let (sp, cp) = lat0.to_radians().sin_cos();
        let (sl, cl) = lon0.to_radians().sin_cos();
        [
            -sl * d[0] + cl * d[1],
            -sp * cl * d[0] - sp * sl * d[1] + cp * d[2],
        ]
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]

        /// lat/lon → frame → lat/lon gives the point back within 1e-9°, for every origin the
        /// frame accepts and every point it maps (within MAX_FRAME_DISTANCE of the origin).
        #[test]
        fn geographic_to_local_and_back_is_exact(
            lat0 in -MAX_ORIGIN_LATITUDE..=MAX_ORIGIN_LATITUDE,
            lon0 in -180.0f64..180.0,
            bearing in 0.0f64..std::f64::consts::TAU,
            fraction in 0.0f64..=1.0,
        ) {
            let f = LocalFrame::new(lat0, lon0).unwrap();
            // a point up to 0.99·MAX_FRAME_DISTANCE away (the latitude/longitude offsets are
            // taken from the frame's scale at the origin, then kept only inside the range)
            let [me, mn] = f.metres_per_degree();
            let d = 0.99 * MAX_FRAME_DISTANCE * fraction;
            let (lat, lon) = (lat0 + d * bearing.cos() / mn, lon0 + d * bearing.sin() / me);
            proptest::prop_assume!(lat.abs() < 90.0 && f.within_range(lat, lon));
            let [x, y] = f.to_local(lat, lon);
            let back = f.to_geographic(x, y);
            proptest::prop_assert!(back.is_some(), "({lat}, {lon}) → ({x}, {y}): no inverse");
            let [lat2, lon2] = back.unwrap();
            proptest::prop_assert!(
                (lat2 - lat).abs() < 1e-9 && (lon2 - lon).abs() < 1e-9,
                "({lat}, {lon}) → ({x}, {y}) → ({lat2}, {lon2})"
            );
        }
    }

    #[test]
    fn radii_of_curvature_are_wgs84s() {
        // Equator: M = a(1 − e²), N = a; pole: M = N = a / sqrt(1 − e²).
        assert!((meridional_radius(0.0) - 6_335_439.327).abs() < 1e-3);
        assert!((prime_vertical_radius(0.0) - WGS84_A).abs() < 1e-9);
        assert!((meridional_radius(90.0) - 6_399_593.626).abs() < 1e-3);
        assert!((prime_vertical_radius(90.0) - 6_399_593.626).abs() < 1e-3);
    }

    #[test]
    fn frame_is_ecef_to_enu_and_inverts_exactly() {
        for (lat0, lon0) in [
            (0.0, 0.0),
            (45.0, -5.0),
            (-33.9, 151.2),
            (60.0, 179.9),
            (80.0, 20.0),
        ] {
            let f = LocalFrame::new(lat0, lon0).unwrap();
            assert_eq!(f.to_local(lat0, lon0), [0.0, 0.0]);
            for k in 0..16 {
                let a = std::f64::consts::TAU * k as f64 / 16.0;
                for d in [100.0, 10e3, 50e3, 200e3] {
                    let (x, y) = (d * a.sin(), d * a.cos());
                    let [lat, lon] = f.to_geographic(x, y).unwrap();
                    let back = f.to_local(lat, lon);
                    assert!((back[0] - x).abs() < 1e-8 && (back[1] - y).abs() < 1e-8);
                    let r = enu_reference(lat0, lon0, lat, lon);
                    assert!((r[0] - x).abs() < 1e-6 && (r[1] - y).abs() < 1e-6, "{r:?}");
                    assert!(f.within_range(lat, lon));
                }
            }
        }
        let f = LocalFrame::new(45.0, 0.0).unwrap();
        assert_eq!(f.to_geographic(MAX_FRAME_DISTANCE + 1.0, 0.0), None);
        assert_eq!(f.to_geographic(f64::NAN, 0.0), None);
        assert!(!f.within_range(-45.0, 180.0));
        assert!(LocalFrame::new(86.0, 0.0).is_err());
        assert!(LocalFrame::new(f64::NAN, 0.0).is_err());
        assert!(LocalFrame::new(0.0, 400.0).is_err());
    }

    /// The figures quoted in the module docs: distance from the origin against the geodesic,
    /// and the scale error of a 150 m link, at 10 and 50 km. Run with --nocapture to see them.
    #[test]
    fn flat_frame_error_against_geodesics() {
        for (dist, max_origin_err, max_link_scale) in [(10e3, 0.005, 1.3e-6), (50e3, 0.53, 3.2e-5)]
        {
            let (mut worst_d, mut worst_s) = (0.0f64, 0.0f64);
            for lat0 in [0.0, 30.0, 45.0, 60.0, 80.0] {
                let f = LocalFrame::new(lat0, 10.0).unwrap();
                for k in 0..16 {
                    let a = std::f64::consts::TAU * k as f64 / 16.0;
                    let (x, y) = (dist * a.sin(), dist * a.cos());
                    let [lat, lon] = f.to_geographic(x, y).unwrap();
                    let geodesic = vincenty(lat0, 10.0, lat, lon);
                    worst_d = worst_d.max((x.hypot(y) - geodesic).abs());
                    // a 150 m link at that point, in both directions
                    for b in [a, a + std::f64::consts::FRAC_PI_2] {
                        let (x2, y2) = (x + 150.0 * b.sin(), y + 150.0 * b.cos());
                        let [lat2, lon2] = f.to_geographic(x2, y2).unwrap();
                        let g = vincenty(lat, lon, lat2, lon2);
                        worst_s = worst_s.max((150.0 - g).abs() / g);
                    }
                }
            }
            println!(
                "at {:.0} km: distance-from-origin error ≤ {worst_d:.4} m ({:.2e} relative), \
                 150 m link scale error ≤ {worst_s:.2e}",
                dist / 1e3,
                worst_d / dist
            );
            assert!(worst_d <= max_origin_err, "{worst_d}");
            assert!(worst_s <= max_link_scale, "{worst_s}");
        }
    }
}
