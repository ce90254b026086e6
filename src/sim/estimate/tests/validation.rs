//! Validation: every broken problem gives the right error, naming the measurement.

use super::*;

fn base() -> Problem {
    let cov = diag(1.0, 1.0, 1.0);
    Problem {
        vehicles: 2,
        epochs: 3,
        priors: vec![
            Prior {
                node: node(0, 0),
                mean: [0.0; 3],
                cov,
            },
            Prior {
                node: node(1, 0),
                mean: [50.0, 0.0, 0.0],
                cov,
            },
        ],
        odometry: (0..2)
            .flat_map(|e| {
                (0..2).map(move |v| Odometry {
                    vehicle: v,
                    epoch: e,
                    delta: [1.0, 0.0, 0.0],
                    cov,
                })
            })
            .collect(),
        depths: vec![Depth {
            node: node(0, 1),
            z: -1.0,
            sigma: 0.1,
        }],
        ranges: vec![Range {
            a: node(0, 2),
            b: node(1, 2),
            range: 50.0,
            sigma: 1.0,
        }],
        ..Default::default()
    }
}

/// Each broken problem gives the named error from both estimators.
#[test]
fn validation_names_the_measurement() {
    assert!(smooth(&base(), &[]).is_ok() && filter(&base()).is_ok());
    type Edit = fn(&mut Problem);
    let cases: Vec<(Edit, &str)> = vec![
        (|p| p.depths[0].sigma = 0.0, "depth #0"),
        (|p| p.ranges[0].sigma = -1.0, "range #0"),
        (|p| p.ranges[0].range = f64::NAN, "range #0"),
        (|p| p.ranges[0].range = -1.0, "range #0"),
        (|p| p.ranges[0].b = p.ranges[0].a, "range #0"),
        (|p| p.priors[1].mean[2] = f64::NAN, "prior #1"),
        (|p| p.odometry[3].delta[0] = f64::INFINITY, "odometry #3"),
        (
            |p| p.odometry[2].cov = [[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            "odometry #2",
        ),
        (
            |p| p.priors[0].cov = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            "prior #0",
        ),
        (|p| p.priors[0].cov[1][1] = f64::NAN, "prior #0"),
        (|p| p.depths[0].node.vehicle = 2, "depth #0"),
        (|p| p.ranges[0].b.epoch = 3, "range #0"),
        (
            |p| {
                p.odometry.push(Odometry {
                    vehicle: 0,
                    epoch: 2,
                    delta: [0.0; 3],
                    cov: diag(1.0, 1.0, 1.0),
                })
            },
            "odometry #4",
        ),
    ];
    for (edit, name) in cases {
        let mut p = base();
        edit(&mut p);
        for result in [smooth(&p, &[]), filter(&p)] {
            match result {
                Err(e @ EstimateError::BadMeasurement { .. }) => {
                    let EstimateError::BadMeasurement { what, why } = &e else {
                        unreachable!()
                    };
                    assert!(what.starts_with(name), "{name}: got {e}");
                    assert!(!why.is_empty());
                }
                other => panic!("{name}: expected BadMeasurement, got {other:?}"),
            }
        }
    }
    let mut no_start = base();
    no_start.priors.remove(1);
    let mut gap = base();
    gap.odometry.retain(|o| !(o.vehicle == 0 && o.epoch == 1));
    for (p, vehicle, epoch) in [(no_start, 1, 0), (gap, 0, 2)] {
        for result in [smooth(&p, &[]), filter(&p)] {
            match result {
                Err(EstimateError::Unobservable {
                    vehicle: v,
                    epoch: e,
                    why,
                }) => {
                    assert_eq!((v, e), (vehicle, epoch), "{why}");
                }
                other => panic!("expected Unobservable, got {other:?}"),
            }
        }
    }
}
