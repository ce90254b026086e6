use super::frames::wrap;
use super::*;
use crate::scenario::Auv;
use crate::vehicle::Damping;
use std::f64::consts::{FRAC_PI_2, PI};

/// Integrates `t` seconds at step `h`, calling `each` on every state (the first included).
fn fly(
    model: &Remus100,
    s0: RigidState,
    a: Actuators,
    current: [f64; 3],
    h: f64,
    t: f64,
    mut each: impl FnMut(&RigidState),
) -> RigidState {
    let mut s = s0;
    each(&s);
    for _ in 0..(t / h).round() as usize {
        s = model.step(&s, &a, current, h);
        each(&s);
    }
    s
}

/// Kirchhoff's impulses in NED: linear P = R·(M₁₁v + M₁₂ω), angular about the NED origin
/// L = R·(M₂₁v + M₂₂ω) + x × P.
fn impulses(model: &Remus100, s: &RigidState) -> (Vector3<f64>, Vector3<f64>) {
    let h = model.mass_matrix() * Vector6::from_column_slice(&s.nu);
    let r = body_to_ned(&s.eta);
    let p = r * Vector3::new(h[0], h[1], h[2]);
    let x = Vector3::new(s.eta[0], s.eta[1], s.eta[2]);
    (p, r * Vector3::new(h[3], h[4], h[5]) + x.cross(&p))
}

fn tumbling() -> RigidState {
    RigidState {
        nu: [0.1, 0.4, 0.3, 1.2, -0.2, 0.2],
        eta: [5.0, -3.0, 20.0, 0.1, -0.2, 0.4],
    }
}

#[test]
fn ideal_fluid_conserves_kinetic_energy() {
    // Only M_RB, M_A, C_RB(ν), C_A(ν) act; νᵀC(ν)ν = 0 for the skew-symmetric forms, so
    // ½νᵀMν is constant. RK4 at 5 ms over 60 s: relative drift < 1e-6.
    let model = Remus100::ideal_fluid();
    let s0 = tumbling();
    let e0 = model.kinetic_energy(&s0.nu);
    let (mut worst, mut max_theta) = (0.0_f64, 0.0_f64);
    let mut max_p = 0.0_f64;
    let end = fly(
        &model,
        s0,
        Actuators::default(),
        [0.0; 3],
        0.005,
        60.0,
        |s| {
            worst = worst.max((model.kinetic_energy(&s.nu) - e0).abs() / e0);
            max_theta = max_theta.max(s.eta[4].abs());
            max_p = max_p.max(s.nu[3].abs());
        },
    );
    assert!(worst < 1e-6, "relative energy drift {worst:e}");
    // It does tumble: it rolls through several turns, and the Euler angles stay clear of the
    // θ = ±90° singularity, so the kinematics remain accurate for the momentum test.
    assert!(
        (end.eta[3] - s0.eta[3]).abs() > 4.0 * PI,
        "roll {}",
        end.eta[3]
    );
    assert!(max_theta < 80f64.to_radians(), "θ reached {max_theta}");
    assert!(max_p > 0.5);
}

#[test]
fn ideal_fluid_conserves_kirchhoff_impulses() {
    // Kirchhoff: d/dt(∂T/∂v) + ω × ∂T/∂v = 0 and d/dt(∂T/∂ω) + ω × ∂T/∂ω + v × ∂T/∂v = 0, so the
    // NED linear impulse and the angular impulse about the NED origin are constant.
    let model = Remus100::ideal_fluid();
    let s0 = tumbling();
    let (p0, l0) = impulses(&model, &s0);
    let (mut dp, mut dl) = (0.0_f64, 0.0_f64);
    fly(
        &model,
        s0,
        Actuators::default(),
        [0.0; 3],
        0.005,
        60.0,
        |s| {
            let (p, l) = impulses(&model, s);
            dp = dp.max((p - p0).norm() / p0.norm());
            dl = dl.max((l - l0).norm() / l0.norm());
        },
    );
    assert!(dp < 1e-6, "linear impulse drift {dp:e}");
    assert!(dl < 1e-6, "angular impulse drift {dl:e}");
}

#[test]
fn steady_surge_matches_the_closed_form() {
    // In the full model straight, level flight is an unstable equilibrium (the Munk moments: at
    // 1.54 m/s the heave–pitch pair is at 0.44 ± 0.17i /s and a sway–yaw root at +1.0 /s), and
    // the thrust, acting at the CB above the CG, pitches the nose down. So the settling run
    // uses the symmetric configuration: neutral buoyancy, the CG at the CB, no propeller torque.
    // Every coupling term is then a product with a zero, flight stays exactly straight and
    // level, and (m − X_u̇)u̇ = T + X_u|u|·u|u| settles at U = √(T / −X_u|u|) = √(3.86 / 1.62) =
    // 1.5436 m/s, Prestero's 1.54 m/s.
    let mut c = Coefficients::prestero();
    c.buoyancy = c.weight();
    c.r_g = [0.0; 3];
    c.nominal_prop_torque = 0.0;
    let model = Remus100::new(c).unwrap();
    let thrust = c.nominal_thrust;
    let a = Actuators {
        thrust,
        ..Actuators::default()
    };
    let end = fly(
        &model,
        RigidState::default(),
        a,
        [0.0; 3],
        0.05,
        300.0,
        |_| {},
    );
    let u_closed = (thrust / 1.62).sqrt();
    assert!((end.nu[0] - u_closed).abs() < 1e-9, "u = {}", end.nu[0]);
    assert!(end.nu[1..].iter().all(|x| x.abs() < 1e-12));
    assert!(end.eta[1..].iter().all(|x| x.abs() < 1e-9));
    assert!((model.steady_speed(thrust) - u_closed).abs() < 1e-12);
    assert!((model.steady_thrust(end.nu[0]) - thrust).abs() < 1e-8);
    // In the full model too, steady_thrust(u) zeroes the surge force of level flight.
    let full = Remus100::default();
    for u in [0.5, 1.0, 1.5, 2.0, 2.5] {
        let s = RigidState {
            nu: [u, 0.0, 0.0, 0.0, 0.0, 0.0],
            eta: [0.0, 0.0, 10.0, 0.0, 0.0, 1.0],
        };
        let a = Actuators {
            thrust: full.steady_thrust(u),
            ..Actuators::default()
        };
        assert!(full.forces(&s, &a, [0.0; 3])[0].abs() < 1e-12);
        assert!((full.steady_speed(full.steady_thrust(u)) - u).abs() < 1e-12);
    }
    // The thrust limit is the drag at the top speed of 2.5 m/s.
    assert!((full.max_thrust - 10.125).abs() < 1e-12);
    assert!((full.steady_speed(full.max_thrust) - MAX_SPEED).abs() < 1e-12);
}

/// −∂ν̇_i/∂ν_i at `nu` by central differences, 1/s.
fn rate(model: &Remus100, nu: [f64; 6], i: usize) -> f64 {
    let d = 1e-6;
    let at = |x: f64| {
        let mut s = RigidState {
            nu,
            eta: [0.0, 0.0, 10.0, 0.0, 0.0, 0.0],
        };
        s.nu[i] = x;
        model.derivative(&s, &Actuators::default(), [0.0; 3])[i]
    };
    -(at(nu[i] + d) - at(nu[i] - d)) / (2.0 * d)
}

#[test]
fn linearisation_recovers_the_planners_damping_rates() {
    // The planner's E' (src/vehicle.rs): e = −γ_v/(m − γ_v̇) per axis, with Prestero's
    // quadratic drag linearised at u0 = 1.5 m/s, w0 = 0.1 m/s, r0 = 0.1 rad/s, each about motion
    // on that axis alone. The 6-DoF rate −∂ν̇_i/∂ν_i at those points is (M⁻¹)_ii·γ_v plus the
    // off-diagonal couplings of M⁻¹ and, in heave, M_w|w| through M⁻¹'s w–q entry. The planner
    // drops them, so the rates agree to 2 % (measured: surge 0.14 %, heave 1.25 %, yaw 0.68 %).
    let model = Remus100::default();
    let planner = Damping::from_params(&Auv::default()).unwrap();
    let surge = rate(&model, [1.5, 0.0, 0.0, 0.0, 0.0, 0.0], 0);
    let heave = rate(&model, [0.0, 0.0, 0.1, 0.0, 0.0, 0.0], 2);
    let yaw = rate(&model, [0.0, 0.0, 0.0, 0.0, 0.0, 0.1], 5);
    for (name, six, two) in [
        ("surge", surge, planner.surge),
        ("heave", heave, planner.heave),
        ("yaw", yaw, planner.yaw),
    ] {
        let rel = (six - two).abs() / two;
        assert!(
            rel < 0.02,
            "{name}: 6-DoF {six:.5} vs planner {two:.5} ({rel:.4})"
        );
    }
    // What the planner's diagonal model leaves out (Prestero's coefficients):
    // - M's off-diagonals: m·z_g = 0.598 kg·m (u–q, v–p); Z_q̇ = M_ẇ = −1.93 kg·m and Y_ṙ = N_v̇ =
    //   1.93 kg·m (w–q, v–r). Against M₃₃ = M₂₂ = 66.0 kg and M₅₅ = M₆₆ = 8.33 kg·m², these
    //   shift the diagonal rates by under 1 % (above).
    // - The terms in u: at u0 = 1.5 m/s, body lift Z_uw·u0 = Y_uv·u0 = −42.9 kg/s, against the
    //   planner's Z_w = −26.2 kg/s. The Munk-dominated moments are M_uw·u0 = +35.9 kg·m/s and
    //   N_uv·u0 = −35.9 kg·m/s (destabilising). The fin/added-mass rate terms are
    //   Y_ur·u0 = −Z_uq·u0 = 7.83 kg·m/s and M_uq·u0 = N_ur·u0 = −3.0 kg·m²/s. At cruise speed,
    //   −∂ẇ/∂w is 1.18 /s, not 0.40 /s: (42.9 + 26.2)/65.6 = 1.05 from lift and drag, plus 0.13
    //   from the Munk moment through M's w–q coupling.
    // - The restoring pitch and roll moment z_g·W = 5.87 N·m/rad, and the buoyancy B − W = 6.7 N.
    let cruise_heave = rate(&model, [1.5, 0.0, 0.1, 0.0, 0.0, 0.0], 2);
    assert!((cruise_heave - 1.18).abs() < 0.01, "{cruise_heave}");
    let m = model.mass_matrix();
    assert!((m[(0, 4)] - 30.51 * 0.0196).abs() < 1e-12);
    assert!((m[(2, 4)] - 1.93).abs() < 1e-12 && (m[(5, 1)] + 1.93).abs() < 1e-12);
}

#[test]
fn at_rest_only_net_buoyancy_acts() {
    let model = Remus100::default();
    let c = *model.coefficients();
    let (w, b) = (c.weight(), c.buoyancy);
    assert!(
        b - w > 6.0 && b - w < 7.0,
        "Prestero's REMUS is 6.7 N buoyant"
    );
    let level = RigidState {
        nu: [0.0; 6],
        eta: [3.0, 4.0, 10.0, 0.0, 0.0, 0.7],
    };
    let f = model.forces(&level, &Actuators::default(), [0.0; 3]);
    let expect = [0.0, 0.0, w - b, 0.0, 0.0, 0.0]; // z down: net buoyancy pushes −z
    for i in 0..6 {
        assert!((f[i] - expect[i]).abs() < 1e-12, "{i}: {f:?}");
    }
    let d = model.derivative(&level, &Actuators::default(), [0.0; 3]);
    assert!(d[2] < 0.0, "ẇ = {} must be upwards", d[2]);
    assert!(d[6..].iter().all(|x| *x == 0.0));
    // ẇ is (M⁻¹)₃₃(W − B); M couples heave to pitch (Z_q̇), so q̇ is not zero, but tiny.
    let expect_nu_dot = model.m_inv * Vector6::from_column_slice(&expect);
    for i in 0..6 {
        assert!((d[i] - expect_nu_dot[i]).abs() < 1e-15);
    }
    // Rolled: the restoring moment −z_g·W·sin φ (CG below CB) brings it back; the buoyancy
    // turns with the body.
    let phi: f64 = 0.3;
    let rolled = RigidState {
        eta: [0.0, 0.0, 10.0, phi, 0.0, 0.0],
        ..level
    };
    let f = model.forces(&rolled, &Actuators::default(), [0.0; 3]);
    assert!((f[3] + c.r_g[2] * w * phi.sin()).abs() < 1e-12);
    assert!((f[1] - (w - b) * phi.sin()).abs() < 1e-12); // up = [0, −sin φ, −cos φ]
                                                         // Left alone for 10 s, it rises: ż < 0 and z decreases.
    let mut zdot_max = f64::NEG_INFINITY;
    let end = fly(
        &model,
        level,
        Actuators::default(),
        [0.0; 3],
        0.05,
        10.0,
        |s| {
            if s.nu[2] != 0.0 {
                zdot_max = zdot_max.max(s.velocity_ned()[2]);
            }
        },
    );
    assert!(
        zdot_max < 0.0 && end.eta[2] < 10.0 - 0.5,
        "z = {}",
        end.eta[2]
    );
}

#[test]
fn actuators_are_clamped() {
    let model = Remus100::default();
    let s = RigidState {
        nu: [1.5, 0.05, -0.02, 0.01, 0.02, -0.03],
        eta: [0.0, 0.0, 10.0, 0.05, -0.1, 1.0],
    };
    let wild = Actuators {
        thrust: 500.0,
        rudder: 1.2,
        stern: -3.0,
    };
    let limit = Actuators {
        thrust: model.max_thrust,
        rudder: model.max_fin,
        stern: -model.max_fin,
    };
    assert_eq!(model.clamp(&wild), limit);
    assert_eq!(
        model.derivative(&s, &wild, [0.0; 3]),
        model.derivative(&s, &limit, [0.0; 3])
    );
    let back = Actuators {
        thrust: -500.0,
        ..Actuators::default()
    };
    assert_eq!(model.clamp(&back).thrust, -model.max_thrust);
    assert!((model.max_fin - 13.6f64.to_radians()).abs() < 1e-15);
    // Within the limits nothing changes.
    let fine = Actuators {
        thrust: 3.0,
        rudder: 0.1,
        stern: -0.1,
    };
    assert_eq!(model.clamp(&fine), fine);
}

#[test]
fn frame_helpers_round_trip_and_agree() {
    for p in [[1.0, 2.0, -3.0], [-40.5, 7.25, 0.0], [0.0, -1e3, -55.0]] {
        assert_eq!(shoal_from_ned(ned_from_shoal(p)), p);
        assert_eq!(ned_from_shoal(shoal_from_ned(p)), p);
    }
    for k in -12..=12 {
        let psi = k as f64 * 0.29;
        let back = heading_shoal_from_ned(heading_ned_from_shoal(psi));
        assert!((back - wrap(psi)).abs() < 1e-12, "{psi}: {back}");
    }
    // North in NED (ψ = 0) is +y in shoal (heading π/2); east (ψ = π/2) is +x (heading 0).
    assert!((heading_shoal_from_ned(0.0) - FRAC_PI_2).abs() < 1e-15);
    assert!(heading_shoal_from_ned(FRAC_PI_2).abs() < 1e-15);
    // North-east in NED at 2 m/s and 10 m deep, sinking at 0.1 m/s.
    let s = RigidState {
        nu: [2.0, 0.0, 0.1, 0.0, 0.0, 0.0],
        eta: [100.0, 50.0, 10.0, 0.0, 0.0, PI / 4.0],
    };
    let v = s.velocity_shoal();
    let h = 2.0 / 2f64.sqrt();
    assert!(
        (v[0] - h).abs() < 1e-12 && (v[1] - h).abs() < 1e-12,
        "{v:?}"
    );
    assert!((v[2] + 0.1).abs() < 1e-12);
    assert!((s.heading_shoal() - PI / 4.0).abs() < 1e-12);
    assert_eq!(s.position_shoal(), [50.0, 100.0, -10.0]);
    // A vehicle placed in shoal's frame heads and moves where it was pointed.
    let t = RigidState::from_shoal([10.0, -20.0, -30.0], 2.5, 1.5);
    assert_eq!(t.position_shoal(), [10.0, -20.0, -30.0]);
    assert!((t.heading_shoal() - 2.5).abs() < 1e-12);
    let v = t.velocity_shoal();
    assert!((v[0] - 1.5 * 2.5f64.cos()).abs() < 1e-12 && (v[1] - 1.5 * 2.5f64.sin()).abs() < 1e-12);
}

#[test]
fn drifts_with_the_current_when_still_in_the_water() {
    // ν = ν_c (no motion through the water), neutral buoyancy: no force, so ν̇ = 0 and the
    // vehicle moves with the current.
    let mut c = Coefficients::prestero();
    c.buoyancy = c.weight();
    let model = Remus100::new(c).unwrap();
    let current = [0.3, -0.4, 0.0];
    let eta = [0.0, 0.0, 10.0, 0.0, 0.0, 1.1];
    let vc = body_to_ned(&eta).transpose() * Vector3::from(current);
    let s = RigidState {
        nu: [vc[0], vc[1], vc[2], 0.0, 0.0, 0.0],
        eta,
    };
    let end = fly(&model, s, Actuators::default(), current, 0.05, 20.0, |_| {});
    assert!((end.eta[0] - 6.0).abs() < 1e-9 && (end.eta[1] + 8.0).abs() < 1e-9);
    assert!((end.eta[5] - 1.1).abs() < 1e-12);
    // In general (Fossen's Property 8.1, current irrotational and constant in NED): the motion
    // through the water obeys the still-water equations, ν̇ = ν̇_r(still water) + ν̇_c.
    let model = Remus100::default();
    let s = RigidState {
        nu: [1.4, 0.1, -0.05, 0.2, -0.1, 0.15],
        eta: [0.0, 0.0, 10.0, 0.2, -0.15, 2.0],
    };
    let a = Actuators {
        thrust: 5.0,
        rudder: 0.1,
        stern: -0.05,
    };
    let vc = body_to_ned(&s.eta).transpose() * Vector3::from(current);
    let omega = Vector3::new(s.nu[3], s.nu[4], s.nu[5]);
    let vc_dot = -omega.cross(&vc);
    let mut still = s;
    (0..3).for_each(|i| still.nu[i] -= vc[i]);
    let with = model.derivative(&s, &a, current);
    let without = model.derivative(&still, &a, [0.0; 3]);
    for i in 0..6 {
        let c = if i < 3 { vc_dot[i] } else { 0.0 };
        assert!((with[i] - (without[i] + c)).abs() < 1e-12, "{i}");
    }
}

#[test]
fn rk4_is_stable_at_a_tenth_of_a_second_at_full_speed_and_full_fins() {
    // Full thrust from 2.5 m/s, full rudder and full stern planes (nose up) for 120 s: a climbing
    // helix at 2.2 m/s, pitch up to 46°, turning at 0.4 rad/s. At h = 0.1 s the run stays bounded
    // and ends 0.25 mm from the same run at h = 0.01 s (0.02 mm at 0.05 s, RECOMMENDED_STEP).
    // Measured margin: 0.2 s still ends 0.5 m off, 0.25 s 4 m off, and 0.3 s diverges.
    let model = Remus100::default();
    let a = Actuators {
        thrust: 1e3,
        rudder: 1.0,
        stern: -1.0,
    };
    let s0 = RigidState {
        nu: [2.5, 0.0, 0.0, 0.0, 0.0, 0.0],
        eta: [0.0, 0.0, 30.0, 0.0, 0.0, 0.0],
    };
    let mut worst = 0.0_f64;
    let mut max_theta = 0.0_f64;
    let coarse = fly(&model, s0, a, [0.0; 3], 0.1, 120.0, |s| {
        assert!(s.nu.iter().chain(&s.eta).all(|x| x.is_finite()));
        worst = worst.max(s.nu[..3].iter().map(|x| x * x).sum::<f64>().sqrt());
        max_theta = max_theta.max(s.eta[4].abs());
    });
    let fine = fly(&model, s0, a, [0.0; 3], 0.01, 120.0, |_| {});
    assert!(worst < 2.6, "speed reached {worst}");
    assert!(max_theta < 60f64.to_radians(), "θ reached {max_theta}");
    let gap: f64 = (0..3)
        .map(|i| (coarse.eta[i] - fine.eta[i]).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(
        gap < 0.1,
        "positions at h = 0.1 and 0.01 s differ by {gap} m"
    );
    let dnu: f64 = (0..6)
        .map(|i| (coarse.nu[i] - fine.nu[i]).abs())
        .fold(0.0, f64::max);
    assert!(dnu < 1e-3, "{dnu}");
}
