//! What the REMUS 100 model can fly, and where flown plans leave their depth and why
//! (docs/simulation.md, "What the vehicle can fly").
//!
//! ```sh
//! cargo run --release --example envelope                   # the trim, envelope and depth steps
//! cargo run --release --example envelope -- out/plan.json  # and where each plan sinks
//! ```
//!
//! For each plan: every AUV's final stages flown at the plan's settings, traced once a second;
//! AUV-epochs (10 s) more than 5 m below the reference, by the reference's horizontal speed;
//! and for those, whether level trim exists at that speed (the vehicle) and what the controller
//! was doing (stern planes at their limit, pitch command at its limit, the integral).

use shoal::sim::control::top_speed;
use shoal::sim::current::{mission_bounds, CurrentField, CURRENT_MARGIN};
use shoal::sim::envelope::{depth_step, flight_path_range, min_level_speed, trace_flight, trim};
use shoal::sim::remus::Remus100;

fn deg(x: f64) -> f64 {
    x.to_degrees()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let model = Remus100::default();
    println!(
        "REMUS 100 (Prestero): fin limit ±{:.1}°, thrust ≤ {:.2} N, top speed {:.2} m/s",
        deg(model.max_fin),
        model.max_thrust,
        top_speed(&model)
    );
    println!("\nlevel trim (still water): speed, angle of attack, pitch, stern plane (share of limit), thrust");
    for v in [0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.25, 1.5, 2.0] {
        match trim(&model, v, 0.0) {
            Some(t) => println!(
                "  {v:4.2} m/s  α {:6.2}°  θ {:6.2}°  δs {:6.2}° ({:4.0} %)  T {:5.2} N  {}",
                deg(t.alpha),
                deg(t.pitch),
                deg(t.stern),
                100.0 * t.fin_share(&model),
                t.thrust,
                if t.flyable(&model) {
                    "flyable"
                } else {
                    "NOT flyable"
                }
            ),
            None => println!("  {v:4.2} m/s  no trim within ±15° of angle of attack"),
        }
    }
    println!("\nslowest speed holding level flight:");
    for share in [1.0, 0.75, 0.5] {
        println!(
            "  with ≤ {:3.0} % of the fin limit: {:.3} m/s",
            100.0 * share,
            min_level_speed(&model, share)
        );
    }
    println!("\nsteady flight-path angles held (steepest climb / steepest dive, of −45° to 45°), fins within 100 % and 75 % of the limit:");
    for v in [
        0.6, 0.8, 1.0, 1.1, 1.15, 1.2, 1.25, 1.3, 1.4, 1.5, 1.75, 2.0,
    ] {
        let show = |x: Option<(f64, f64)>| match x {
            Some((c, d)) => format!("{:+5.1}° / {:+5.1}°", deg(c), deg(d)),
            None => "  none".into(),
        };
        println!(
            "  {v:4.2} m/s   {}    {}",
            show(flight_path_range(&model, v, 1.0)),
            show(flight_path_range(&model, v, 0.75))
        );
    }
    println!("\ndepth steps at a fixed horizontal speed (30 m depth, 60 s level, the change at the rate, 60 s level):");
    println!("  speed  change  rate      below   above   end     stern at limit");
    for v in [0.6, 0.8, 1.0, 1.15, 1.25, 1.5] {
        for (dz, rate) in [(-10.0, 0.1), (10.0, 0.1), (-10.0, 0.3), (10.0, 0.3)] {
            let r = depth_step(&model, v, dz, rate, 60.0);
            println!(
                "  {v:4.2}  {dz:+5.0} m  {rate:.1} m/s  {:6.2}  {:6.2}  {:+6.2}  {:5.1} %",
                r.below,
                r.above,
                r.final_error,
                100.0 * r.saturated
            );
        }
    }

    for path in std::env::args().skip(1) {
        let plan = shoal::output::read_plan(std::path::Path::new(&path))?;
        let floor = shoal::check::load_floor(&plan, None)?;
        let dir = std::path::Path::new(&path)
            .parent()
            .unwrap_or(std::path::Path::new(""));
        let current = CurrentField::load(
            &plan.scenario.current,
            dir,
            mission_bounds(&plan, CURRENT_MARGIN),
        )?;
        println!("\n{path}: AUV-epochs (10 s) more than 5 m below the reference");
        let bins = [0.0, 0.6, 0.8, 1.0, 1.25, 1.5, 10.0];
        let mut total = vec![0usize; bins.len() - 1];
        let mut sunk = vec![0usize; bins.len() - 1];
        let (mut flyable, mut unflyable) = (0usize, 0usize);
        // whether the reference asks for a steady flight the vehicle can hold
        let holdable = |v: f64, climb: f64| {
            trim(&model, v.max(0.05), climb.atan2(v.max(0.05))).is_some_and(|t| t.flyable(&model))
        };
        let (mut now, mut before_only, mut never) = (0usize, 0usize, 0usize);
        let (mut sat, mut pitch_lim, mut int_max, mut worst) = (0usize, 0usize, 0.0_f64, 0.0_f64);
        for auv in 0..plan.scenario.team.auvs {
            let trace = trace_flight(&plan, &floor, &current, &model, auv)
                .map_err(|e| format!("AUV {auv}: {e:?}"))?;
            for p in trace.iter().step_by(10) {
                let b = bins
                    .windows(2)
                    .position(|w| p.planned_speed >= w[0] && p.planned_speed < w[1])
                    .unwrap_or(0);
                total[b] += 1;
                worst = worst.min(p.below);
                if p.below < -5.0 {
                    sunk[b] += 1;
                    // the minute before: the planes at their limit, the pitch command at its
                    let i = p.time as usize;
                    let before = &trace[i.saturating_sub(60)..=i];
                    let share =
                        before.iter().map(|q| q.saturated).sum::<f64>() / before.len() as f64;
                    sat += usize::from(share > 0.25);
                    pitch_lim += usize::from(
                        before
                            .iter()
                            .any(|q| q.trace.pitch_command.abs() >= 29.9f64.to_radians()),
                    );
                    int_max = int_max.max(p.trace.integral.abs());
                    let earlier = &trace[i.saturating_sub(120)..=i];
                    if !holdable(p.planned_speed, p.planned_climb) {
                        now += 1;
                    } else if earlier
                        .iter()
                        .any(|q| !holdable(q.planned_speed, q.planned_climb))
                    {
                        before_only += 1;
                    } else {
                        never += 1;
                        println!(
                            "    AUV {auv} t = {:.0} s: {:.1} m below at {:.2} m/s, climb {:+.3} \
                             m/s; pitch {:.1}° for {:.1}°, stern {:.1}° wanted {:.1}°, integral \
                             {:.3}",
                            p.time,
                            -p.below,
                            p.planned_speed,
                            p.planned_climb,
                            deg(p.trace.pitch),
                            deg(p.trace.pitch_command),
                            deg(p.trace.stern),
                            deg(p.trace.stern_wanted),
                            p.trace.integral
                        );
                    }
                    match trim(&model, p.planned_speed.max(0.05), 0.0) {
                        Some(t) if t.flyable(&model) => flyable += 1,
                        _ => unflyable += 1,
                    }
                }
            }
        }
        println!("  planned horizontal speed   AUV-epochs   > 5 m below");
        for b in 0..total.len() {
            println!(
                "  [{:4.2}, {:5.2}) m/s        {:8}   {:6} ({:4.1} %)",
                bins[b],
                bins[b + 1],
                total[b],
                sunk[b],
                100.0 * sunk[b] as f64 / total[b].max(1) as f64
            );
        }
        let n = sunk.iter().sum::<usize>();
        println!(
            "  {n} sunk AUV-epochs (deepest {:.1} m below): level trim flyable at the planned \
             speed in {flyable}, not in {unflyable}; stern planes at their limit > 25 % of the \
             minute before in {sat}; pitch command at its 30° limit in the minute before in \
             {pitch_lim}; largest depth integral {int_max:.3} rad",
            -worst
        );
        println!(
            "  the reference asks for a steady flight the vehicle cannot hold (level or at the \
             planned climb, through the water): at that epoch in {now}, only in the 120 s \
             before in {before_only}, in neither in {never}"
        );
    }
    Ok(())
}
