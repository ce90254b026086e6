//! Values that are valid but implausible for a REMUS 100-class team: most likely a unit slip
//! (degrees typed as radians, minutes as seconds, knots as m/s, kilometres as metres, feet as
//! metres). [`validate`](super::validate) refuses what cannot be planned; this only warns, so a
//! deliberate choice (a turn-rate limit set high to switch C1_14 off, say) still plans.
//!
//! Every rule is one row of [`TABLE`]: the key, the range outside which a value is far from
//! what the vehicle, the modem or the paper uses (with its source), and the slips to suggest. A
//! unit slip is suggested only when the value, read in the other unit, falls inside the range:
//! `horizon.dt = 1.67` suggests minutes (1.67 min = 100.2 s), `acoustic.sonar_range = 10` does
//! not suggest kilometres (10 km is beyond an acoustic modem too).

use super::Scenario;
use std::f64::consts::{PI, TAU};

/// Which side of its range a value is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Below the range's low end.
    Below,
    /// Above the range's high end.
    Above,
}

/// A likely slip behind an implausible value.
#[derive(Debug, Clone, Copy)]
pub struct Slip {
    /// What was probably done, e.g. "degrees per second typed as radians".
    pub what: &'static str,
    /// The unit the value was probably typed in, as written after the number (e.g. "°/s",
    /// " min"), and the factor that turns a value in it into the key's unit; `None` for a slip
    /// that is not a unit (suggested whenever the value is on `side`).
    pub unit: Option<(&'static str, f64)>,
    /// The side of the range the slip puts a value on.
    pub side: Side,
}

/// One row of the table: a key, its plausible range and its likely slips.
#[derive(Debug, Clone, Copy)]
pub struct Plausible {
    /// The dotted key.
    pub key: &'static str,
    /// The key's unit, as written after the number (e.g. " rad/s", " m").
    pub unit: &'static str,
    /// Values below this are far from what is usual (`None`: no low end).
    pub low: Option<f64>,
    /// Values above this are far from what is usual (`None`: no high end).
    pub high: Option<f64>,
    /// What is usual, and whose figure it is, e.g. "a REMUS 100's ~0.2–0.5 rad/s".
    pub usual: &'static str,
    /// The likely slips.
    pub slips: &'static [Slip],
    /// The key's value in a scenario.
    pub value: fn(&Scenario) -> f64,
    /// The value in another unit, shown after it (e.g. "286°/s"), if that helps to see it.
    pub aside: Option<fn(f64) -> String>,
    /// What the value does to this scenario's mission, if that helps to see it.
    pub effect: Option<fn(&Scenario, f64) -> String>,
}

const DEG: f64 = PI / 180.0;
const KNOT: f64 = 1852.0 / 3600.0;
const FOOT: f64 = 0.3048;

const KNOTS: Slip = Slip {
    what: "knots typed as m/s",
    unit: Some((" kn", KNOT)),
    side: Side::Above,
};
const KMH: Slip = Slip {
    what: "km/h typed as m/s",
    unit: Some((" km/h", 1.0 / 3.6)),
    side: Side::Above,
};
const KILOMETRES: Slip = Slip {
    what: "kilometres typed as metres",
    unit: Some((" km", 1000.0)),
    side: Side::Below,
};
const FEET: Slip = Slip {
    what: "feet typed as metres",
    unit: Some((" ft", FOOT)),
    side: Side::Above,
};
const DEGREES: Slip = Slip {
    what: "degrees typed as radians",
    unit: Some(("°", DEG)),
    side: Side::Above,
};

/// The rules, one per key where a unit slip is plausible. Ranges are deliberately wider than
/// what is usual ("far" from it); the sources are in the comments.
pub const TABLE: &[Plausible] = &[
    // The paper, Section V: δ = 100 s. Ten seconds moves a REMUS 100 at 1.5 m/s 15 m, a tenth
    // of d_s; beyond 1000 s a step jumps 1.5 km, ten times d_s, past any floor detail.
    Plausible {
        key: "horizon.dt",
        unit: " s",
        low: Some(10.0),
        high: Some(1000.0),
        usual: "the paper's δ = 100 s (Section V)",
        slips: &[Slip {
            what: "minutes typed as seconds",
            unit: Some((" min", 60.0)),
            side: Side::Below,
        }],
        value: |s| s.horizon.dt,
        aside: None,
        effect: Some(|s, v| {
            format!(
                "a window of K = {} steps spans {} s",
                s.horizon.steps,
                num(s.horizon.steps as f64 * v)
            )
        }),
    },
    // REMUS 100 (Hydroid/Kongsberg specification): 0.25–2.6 m/s, i.e. up to 5 kn; Fossen
    // (2021, §8.4) models it to 2.5 m/s.
    Plausible {
        key: "auv.max_speed",
        unit: " m/s",
        low: None,
        high: Some(3.0),
        usual: "a REMUS 100's 0.25–2.6 m/s (up to 5 kn)",
        slips: &[KNOTS, KMH],
        value: |s| s.auv.max_speed,
        aside: None,
        effect: None,
    },
    // The paper gives no USV speed. The team moves at the AUVs' pace (≤ 2.6 m/s for a REMUS
    // 100), and survey USVs cruise at 1–5 m/s (2–10 kn).
    Plausible {
        key: "usv.max_speed",
        unit: " m/s",
        low: None,
        high: Some(6.0),
        usual: "a survey USV's 1–5 m/s (2–10 kn), and the team keeps the AUVs' ≤ 2.6 m/s",
        slips: &[KNOTS, KMH],
        value: |s| s.usv.max_speed,
        aside: None,
        effect: None,
    },
    // A REMUS 100 turns at ~0.2–0.5 rad/s at full rudder (Prestero 2001's turning trials);
    // the default 0.005 rad/s (0.5 rad per 100 s step) is a planning limit well inside it.
    Plausible {
        key: "auv.max_heading_rate",
        unit: " rad/s",
        low: None,
        high: Some(1.0),
        usual: "a REMUS 100's ~0.2–0.5 rad/s",
        slips: &[Slip {
            what: "degrees per second typed as radians",
            unit: Some(("°/s", DEG)),
            side: Side::Above,
        }],
        value: |s| s.auv.max_heading_rate,
        aside: Some(|v| format!("{:.0}°/s", v / DEG)),
        effect: None,
    },
    // An angle in radians: one turn either way covers every heading.
    Plausible {
        key: "usv.initial_heading",
        unit: " rad",
        low: Some(-TAU),
        high: Some(TAU),
        usual: "a heading in radians, within ±2π",
        slips: &[
            DEGREES,
            Slip {
                side: Side::Below,
                ..DEGREES
            },
        ],
        value: |s| s.usv.initial_heading,
        aside: Some(|v| format!("{:.0}°", v / DEG)),
        effect: None,
    },
    // The paper, Section V: d_s = 150 m. A WHOI Micro-Modem links over a few kilometres
    // (Freitag et al., "The WHOI Micro-Modem", OCEANS 2005). Below the default 50 m swath the
    // chain holds the AUVs closer than their own swaths.
    Plausible {
        key: "acoustic.sonar_range",
        unit: " m",
        low: Some(50.0),
        high: Some(5000.0),
        usual: "the paper's d_s = 150 m (Section V), a WHOI Micro-Modem's up to a few km",
        slips: &[KILOMETRES],
        value: |s| s.acoustic.sonar_range,
        aside: None,
        effect: Some(|s, v| {
            format!(
                "the {} AUVs start within {} m of the USV and their chain holds them as close",
                s.team.auvs,
                num(v)
            )
        }),
    },
    // d_max: the default 400 m; the same modems as d_s.
    Plausible {
        key: "acoustic.max_range",
        unit: " m",
        low: Some(50.0),
        high: Some(10_000.0),
        usual: "the default d_max = 400 m, a WHOI Micro-Modem's up to a few km",
        slips: &[KILOMETRES],
        value: |s| s.acoustic.max_range,
        aside: None,
        effect: None,
    },
    // REMUS 100 side-scan surveys fly 3–10 m above the floor; its 1.2 MHz DVL keeps bottom
    // lock to ~30 m.
    Plausible {
        key: "auv.floor_clearance",
        unit: " m",
        low: None,
        high: Some(50.0),
        usual: "a REMUS 100 survey's 3–10 m above the floor",
        slips: &[
            FEET,
            Slip {
                what: "a depth typed where a height above the floor is meant",
                unit: None,
                side: Side::Above,
            },
        ],
        value: |s| s.auv.floor_clearance,
        aside: None,
        effect: None,
    },
    // Depth ratings: the REMUS 100's 100 m (Hydroid/Kongsberg specification sheet), the
    // REMUS 6000's 6000 m; no AUV is rated deeper.
    Plausible {
        key: "auv.max_depth",
        unit: " m",
        low: None,
        high: Some(6000.0),
        usual: "a REMUS 100's 100 m depth rating (6000 m for the deepest AUVs)",
        slips: &[FEET],
        value: |s| s.auv.max_depth,
        aside: None,
        effect: None,
    },
    // A REMUS keeps its pitch within about ±15–20° in operation (Prestero 2001); steeper
    // than 35° (0.6 rad) is no survey AUV's flight.
    Plausible {
        key: "auv.max_flight_path_angle",
        unit: " rad",
        low: None,
        high: Some(0.6),
        usual: "a REMUS's pitch of about ±15–20° (0.26–0.35 rad)",
        slips: &[DEGREES],
        // (from NO_ANGLE_LIMIT on the value means no limit, which is no slip)
        value: |s| match s.auv.max_flight_path_angle {
            a if a >= super::NO_ANGLE_LIMIT => 0.0,
            a => a,
        },
        aside: Some(|v| format!("{:.0}°", v / DEG)),
        effect: None,
    },
    // REMUS 100 (specification sheet): cruise ~1.5 m/s (3 kn), 0.25–2.6 m/s in all.
    Plausible {
        key: "auv.min_speed",
        unit: " m/s",
        low: None,
        high: Some(2.0),
        usual: "a REMUS 100's fins holding it from ~1 m/s, cruise ~1.5 m/s (3 kn)",
        slips: &[KNOTS, KMH],
        value: |s| s.auv.min_speed,
        aside: None,
        effect: None,
    },
    // The REMUS 100 is rated to 100 m depth.
    Plausible {
        key: "auv.surface_clearance",
        unit: " m",
        low: None,
        high: Some(100.0),
        usual: "a REMUS 100's 100 m depth rating",
        slips: &[FEET],
        value: |s| s.auv.surface_clearance,
        aside: None,
        effect: None,
    },
    // Side-scan sonars survey from 10 % of their range per side (3–15 m for a REMUS 100's
    // 900 kHz side-scan); the DVL's bottom lock ends near 30 m.
    Plausible {
        key: "auv.survey_altitude",
        unit: " m",
        low: None,
        high: Some(100.0),
        usual: "a REMUS 100 side-scan's 3–15 m altitude",
        slips: &[FEET],
        value: |s| s.auv.survey_altitude,
        aside: None,
        effect: None,
    },
    // A REMUS 100 side-scan (900 kHz) covers 30–75 m per side: a swath of 60–150 m.
    Plausible {
        key: "auv.swath_width",
        unit: " m",
        low: Some(5.0),
        high: Some(1000.0),
        usual: "a REMUS 100 side-scan's 60–150 m swath",
        slips: &[KILOMETRES, FEET],
        value: |s| s.auv.swath_width,
        aside: None,
        effect: None,
    },
    // Teledyne RDI: a 1200 kHz DVL (the REMUS 100's) bottom-tracks to ~30 m, a 300 kHz one to
    // ~200 m.
    Plausible {
        key: "navigation.dvl_max_altitude",
        unit: " m",
        low: Some(5.0),
        high: Some(300.0),
        usual: "a 1200 kHz DVL's ~30 m (300 kHz: ~200 m)",
        slips: &[FEET, KILOMETRES],
        value: |s| s.navigation.dvl_max_altitude,
        aside: None,
        effect: None,
    },
    // DVL, compass, depth and GPS at 1–10 Hz (the default: 1 s).
    Plausible {
        key: "navigation.sample_period",
        unit: " s",
        low: None,
        high: Some(2.0),
        usual: "sensors sampled at 1–10 Hz (0.1–1 s)",
        slips: &[Slip {
            what: "milliseconds typed as seconds",
            unit: Some((" ms", 1e-3)),
            side: Side::Above,
        }],
        value: |s| s.navigation.sample_period,
        aside: None,
        effect: None,
    },
    // Eustice et al., J. Field Robotics 28(1), 2011: a synchronous-clock cycle of ~10 s.
    Plausible {
        key: "navigation.acoustic_period",
        unit: " s",
        low: Some(1.0),
        high: Some(600.0),
        usual: "an acoustic cycle of ~10 s (Eustice et al. 2011)",
        slips: &[Slip {
            what: "minutes typed as seconds",
            unit: Some((" min", 60.0)),
            side: Side::Below,
        }],
        value: |s| s.navigation.acoustic_period,
        aside: None,
        effect: None,
    },
    // Kinsey, Eustice, Whitcomb (IFAC MCMC 2006): magnetic compasses 1–10°, gyrocompasses 0.1°.
    Plausible {
        key: "navigation.heading_noise",
        unit: " rad",
        low: None,
        high: Some(0.2),
        usual: "a compass's 0.1–10° (0.002–0.17 rad; Kinsey et al. 2006)",
        slips: &[DEGREES],
        value: |s| s.navigation.heading_noise,
        aside: Some(|v| format!("{:.1}°", v / DEG)),
        effect: None,
    },
    Plausible {
        key: "navigation.heading_bias",
        unit: " rad",
        low: None,
        high: Some(0.2),
        usual: "a compass's 0.1–10° (0.002–0.17 rad; Kinsey et al. 2006)",
        slips: &[DEGREES],
        value: |s| s.navigation.heading_bias,
        aside: Some(|v| format!("{:.1}°", v / DEG)),
        effect: None,
    },
    // Sound in seawater: 1450–1550 m/s (temperature, salinity and depth; Mackenzie 1981).
    Plausible {
        key: "navigation.sound_speed",
        unit: " m/s",
        low: Some(1400.0),
        high: Some(1600.0),
        usual: "seawater's 1450–1550 m/s",
        slips: &[
            Slip {
                what: "km/s typed as m/s",
                unit: Some((" km/s", 1000.0)),
                side: Side::Below,
            },
            Slip {
                what: "feet per second typed as m/s",
                unit: Some((" ft/s", FOOT)),
                side: Side::Above,
            },
        ],
        value: |s| s.navigation.sound_speed,
        aside: None,
        effect: None,
    },
];

impl Plausible {
    /// Whether `v` lies inside the plausible range.
    pub fn contains(&self, v: f64) -> bool {
        self.low.map_or(true, |lo| v >= lo) && self.high.map_or(true, |hi| v <= hi)
    }

    /// The warning for `s`, or None when its value is plausible.
    pub fn check(&self, s: &Scenario) -> Option<String> {
        let v = (self.value)(s);
        let side = match (self.low, self.high) {
            (Some(lo), _) if v < lo => Side::Below,
            (_, Some(hi)) if v > hi => Side::Above,
            _ => return None,
        };
        if !v.is_finite() {
            return None; // validation refuses these
        }
        let aside = self.aside.map_or(String::new(), |f| format!(" ({})", f(v)));
        let far = match side {
            Side::Below => "below",
            Side::Above => "above",
        };
        let mut text = format!(
            "{} = {v}{}{aside} is far {far} {}",
            self.key, self.unit, self.usual
        );
        if let Some(effect) = self.effect {
            text.push_str(&format!("; {}", effect(s, v)));
        }
        let slips: Vec<String> = self
            .slips
            .iter()
            .filter(|slip| slip.side == side)
            .filter_map(|slip| match slip.unit {
                None => Some(format!("{}?", slip.what)),
                Some((unit, factor)) => {
                    let meant = v * factor;
                    self.contains(meant).then(|| {
                        format!("{}? ({v}{unit} = {}{})", slip.what, num(meant), self.unit)
                    })
                }
            })
            .collect();
        if slips.is_empty() {
            text.push_str(&format!(" (check the value and its unit,{})", self.unit));
        } else {
            text.push_str(&format!(": {}", slips.join(" or ")));
        }
        Some(text)
    }
}

/// A warning for every value of `s` outside its plausible range ([`TABLE`]), in table order.
pub fn warnings(s: &Scenario) -> Vec<String> {
    TABLE.iter().filter_map(|row| row.check(s)).collect()
}

/// A number for a person: no exponent, at most three significant digits below 10 (two below
/// 1), one decimal below 1000, trailing zeros dropped; never "-0".
fn num(v: f64) -> String {
    let a = v.abs();
    let text = if a >= 1000.0 {
        format!("{v:.0}")
    } else if a >= 10.0 {
        format!("{v:.1}")
    } else if a >= 1.0 {
        format!("{v:.2}")
    } else if a > 0.0 {
        let decimals = (1 - a.log10().floor() as i32).clamp(1, 12) as usize;
        format!("{v:.decimals$}")
    } else {
        "0".to_string()
    };
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    };
    crate::report::no_negative_zero(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default scenario with `key` = `value` (and a link band that fits a short sonar
    /// range, an acoustic cycle that fits a long sampling period).
    fn with(key: &str, value: &str) -> Scenario {
        let mut set = vec![format!("{key}={value}")];
        if key == "acoustic.sonar_range" {
            set.push("acoustic.band_tolerance=0.01".to_string());
        }
        if key == "navigation.sample_period" {
            set.push(format!("navigation.acoustic_period={value}"));
        }
        if key == "auv.surface_clearance" {
            // a depth rating below any clearance tried
            set.push("auv.max_depth=1000".to_string());
        }
        super::super::default_with(&set).expect("a valid override")
    }

    #[test]
    fn the_default_scenario_warns_of_nothing() {
        assert_eq!(warnings(&Scenario::default()), Vec::<String>::new());
        let s = super::super::default_with(&[]).unwrap();
        assert_eq!(warnings(&s), Vec::<String>::new());
    }

    #[test]
    fn every_row_holds_its_default_and_warns_outside_its_range() {
        let d = Scenario::default();
        for row in TABLE {
            let v = (row.value)(&d);
            assert!(
                row.contains(v),
                "{}: default {v} outside its range",
                row.key
            );
            for (bound, outside) in [
                (row.low, row.low.map(|lo| lo - lo.abs().max(1.0) * 0.5)),
                (row.high, row.high.map(|hi| hi + hi.abs().max(1.0) * 0.5)),
            ] {
                let (Some(_), Some(x)) = (bound, outside) else {
                    continue;
                };
                // keep the value valid: the scenario must still load
                let Ok(s) = super::super::default_with(&[format!("{}={x}", row.key)]) else {
                    continue;
                };
                let w = row
                    .check(&s)
                    .unwrap_or_else(|| panic!("{} = {x}: no warning", row.key));
                assert!(w.starts_with(&format!("{} = {x}", row.key)), "{w}");
                assert!(w.contains(row.usual), "{w}");
            }
            // every row's source range is stated in its text
            assert!(!row.usual.is_empty(), "{}", row.key);
        }
    }

    #[test]
    fn slips_are_suggested_only_where_the_other_unit_fits() {
        // (key, value, the slip's text expected in the warning, or "" for none)
        let cases = [
            (
                "horizon.dt",
                "1.67",
                "minutes typed as seconds? (1.67 min = 100.2 s)",
            ),
            ("horizon.dt", "5000", ""),
            (
                "auv.max_speed",
                "5",
                "knots typed as m/s? (5 kn = 2.57 m/s)",
            ),
            (
                "usv.max_speed",
                "9",
                "km/h typed as m/s? (9 km/h = 2.5 m/s)",
            ),
            (
                "usv.initial_heading",
                "90",
                "degrees typed as radians? (90° = 1.57 rad)",
            ),
            (
                "usv.initial_heading",
                "-90",
                "degrees typed as radians? (-90° = -1.57 rad)",
            ),
            (
                "acoustic.sonar_range",
                "0.15",
                "kilometres typed as metres? (0.15 km = 150 m)",
            ),
            ("acoustic.sonar_range", "10", ""),
            (
                "auv.floor_clearance",
                "100",
                "feet typed as metres? (100 ft = 30.5 m)",
            ),
            ("auv.floor_clearance", "100", "a depth typed where a height"),
            (
                "auv.surface_clearance",
                "300",
                "feet typed as metres? (300 ft = 91.4 m)",
            ),
            (
                "navigation.heading_noise",
                "0.4",
                "degrees typed as radians? (0.4° = 0.007 rad)",
            ),
            (
                "navigation.sound_speed",
                "1.5",
                "km/s typed as m/s? (1.5 km/s = 1500 m/s)",
            ),
            (
                "navigation.sound_speed",
                "4900",
                "feet per second typed as m/s? (4900 ft/s = 1494 m/s)",
            ),
            (
                "navigation.sample_period",
                "10",
                "milliseconds typed as seconds? (10 ms = 0.01 s)",
            ),
        ];
        for (key, value, slip) in cases {
            let s = with(key, value);
            let w = warnings(&s);
            assert_eq!(w.len(), 1, "{key} = {value}: {w:?}");
            if slip.is_empty() {
                assert!(w[0].contains("check the value and its unit"), "{}", w[0]);
                assert!(!w[0].contains("typed as"), "{}", w[0]);
            } else {
                assert!(w[0].contains(slip), "{key} = {value}: {}", w[0]);
            }
        }
    }

    #[test]
    fn regression_degrees_per_second_typed_as_radians_warns() {
        let s = with("auv.max_heading_rate", "5");
        assert_eq!(
            warnings(&s),
            [
                "auv.max_heading_rate = 5 rad/s (286°/s) is far above a REMUS 100's ~0.2–0.5 \
              rad/s: degrees per second typed as radians? (5°/s = 0.087 rad/s)"
            ]
        );
    }

    #[test]
    fn regression_minutes_typed_as_seconds_warns() {
        let s = with("horizon.dt", "1.67");
        let w = warnings(&s);
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].starts_with(
                "horizon.dt = 1.67 s is far below the paper's δ = 100 s (Section V); a window \
                 of K = 20 steps spans 33.4 s: minutes typed as seconds? (1.67 min = 100.2 s)"
            ),
            "{}",
            w[0]
        );
    }

    #[test]
    fn regression_a_ten_metre_sonar_range_warns() {
        let s = super::super::default_with(&[
            "acoustic.sonar_range=10".to_string(),
            "acoustic.band_tolerance=2".to_string(),
            "team.auvs=7".to_string(),
        ])
        .unwrap();
        let w = warnings(&s);
        assert_eq!(w.len(), 1, "{w:?}");
        assert!(
            w[0].starts_with(
                "acoustic.sonar_range = 10 m is far below the paper's d_s = 150 m (Section V)"
            ) && w[0].contains("the 7 AUVs start within 10 m of the USV"),
            "{}",
            w[0]
        );
    }

    #[test]
    fn the_example_scenarios_warn_of_nothing() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
        let mut seen = 0;
        for sub in ["bathymetry", "sweep", "slurm"] {
            for entry in std::fs::read_dir(dir.join(sub)).unwrap() {
                let path = entry.unwrap().path();
                if path.extension().and_then(|e| e.to_str()) != Some("toml") {
                    continue;
                }
                // a scenario file, or a study whose scenario is the default with its [set]
                let s = match super::super::load(&path, &[]) {
                    Ok(s) => s,
                    Err(_) => study_scenario(&path),
                };
                assert_eq!(warnings(&s), Vec::<String>::new(), "{}", path.display());
                seen += 1;
            }
        }
        assert!(seen >= 4, "{seen} example files");
    }

    /// The scenario of a study file: its `scenario` (default: the embedded default) with the
    /// overrides of its `[set]`.
    fn study_scenario(path: &std::path::Path) -> Scenario {
        let text = std::fs::read_to_string(path).unwrap();
        let study: toml::Table = text.parse().unwrap();
        let set: Vec<String> = study
            .get("set")
            .and_then(|s| s.as_table())
            .map(|t| t.iter().map(|(k, v)| format!("{k}={v}")).collect())
            .unwrap_or_default();
        match study.get("scenario").and_then(|s| s.as_str()) {
            Some(file) => super::super::load(&path.parent().unwrap().join(file), &set).unwrap(),
            None => super::super::default_with(&set).unwrap(),
        }
    }

    #[test]
    fn numbers_are_short_and_never_negative_zero() {
        assert_eq!(num(100.2), "100.2");
        assert_eq!(num(0.0872664), "0.087");
        assert_eq!(num(2.5722), "2.57");
        assert_eq!(num(1494.48), "1494");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(-1e-300), "0");
    }
}
