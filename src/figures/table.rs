//! The plan's metrics as a table figure: one column per window and one for the mission, the
//! same numbers as the terminal summary of `shoal plan`.

use super::canvas::{Area, DrawResult, Figure, Images};
use super::scene::Scene;
use super::style::{text, Frame, TICK};
use crate::plan::{Metrics, Window};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const ROW_H: u32 = 40;
const LABEL_W: u32 = 520;
const COL_W: u32 = 190;
const MARGIN: u32 = 30;

pub(crate) struct Table {
    frame: Frame,
    header: Vec<String>,
    rows: Vec<(String, Vec<String>)>,
    width: u32,
}

fn short(status: &str) -> &str {
    match status {
        "converged" => "conv",
        "max_iterations" => "max iter",
        "stalled" => "stalled",
        "solver_trouble" => "solver",
        s => s,
    }
}

fn usv_moved(w: &[Window]) -> f64 {
    let a = w.first().and_then(|w| w.final_.usv.position.first());
    let b = w.last().and_then(|w| w.final_.usv.position.last());
    match (a, b) {
        (Some(a), Some(b)) => (b[0] - a[0]).hypot(b[1] - a[1]),
        _ => 0.0,
    }
}

impl Table {
    pub fn new(scene: &Scene) -> Table {
        let plan = scene.plan;
        let ws = &plan.windows;
        let mut header: Vec<String> = ws.iter().map(|w| format!("window {}", w.index)).collect();
        header.push("mission".into());
        // Per window: the window's slice; the mission column uses every window.
        let cols: Vec<(&[Window], &Metrics)> = ws
            .iter()
            .enumerate()
            .map(|(i, w)| (&ws[i..=i], &w.metrics))
            .chain(std::iter::once((&ws[..], &plan.metrics)))
            .collect();
        let last = cols.len() - 1;
        let row = |label: &str, f: &dyn Fn(usize, &[Window], &Metrics) -> String| {
            let cells = cols
                .iter()
                .enumerate()
                .map(|(i, (w, m))| f(i, w, m))
                .collect();
            (label.to_string(), cells)
        };
        let per_window = |f: fn(&Window) -> String| {
            move |i: usize, w: &[Window], _: &Metrics| {
                if i == last {
                    "—".into()
                } else {
                    f(&w[0])
                }
            }
        };
        let lim = 1e3 * plan.scenario.auv.max_heading_rate;
        let rows = vec![
            row(
                "Step 1 (P2): status / SCP iterations",
                &per_window(|w| format!("{} / {}", short(&w.step1.status), w.step1.iterations)),
            ),
            row(
                "Step 3 (P5): status / SCP iterations",
                &per_window(|w| format!("{} / {}", short(&w.final_.status), w.final_.iterations)),
            ),
            row(
                "line-of-sight rounds",
                &per_window(|w| w.links.los_rounds.to_string()),
            ),
            row("input energy Σ‖U‖² ((m/s²)²)", &|_, _, m| {
                format!("{:.3}", m.input_energy)
            }),
            row("mean height above floor (m)", &|_, _, m| {
                format!("{:.2}", m.mean_height)
            }),
            row("min height above floor (m)", &|_, _, m| {
                format!("{:.2}", m.min_height)
            }),
            row("USV moved (m)", &|_, w, _| format!("{:.0}", usv_moved(w))),
            row("explored area (km²)", &|_, _, m| {
                format!("{:.3}", m.explored_area_km2)
            }),
            row("steps connected (%)", &|_, _, m| {
                format!("{:.1}", 100.0 * m.connected_fraction)
            }),
            row("steps with the planned chain usable (%)", &|_, _, m| {
                format!("{:.1}", 100.0 * m.chain_fraction)
            }),
            row("link-steps outside their band", &|_, w, _| {
                w.iter()
                    .map(|w| w.links.out_of_band.len())
                    .sum::<usize>()
                    .to_string()
            }),
            row(
                &format!("max heading rate (mrad/s, limit {lim})"),
                &|_, _, m| format!("{:.3}", 1e3 * m.max_heading_rate),
            ),
            row("Step 1 solve time (s)", &|_, _, m| {
                format!("{:.3}", m.step1_time_s)
            }),
            row("Step 2 solve time (ms)", &|_, _, m| {
                format!("{:.2}", 1e3 * m.step2_time_s)
            }),
            row("Step 3 solve time (s)", &|_, _, m| {
                format!("{:.3}", m.step3_time_s)
            }),
        ];
        let width = 2 * MARGIN + LABEL_W + COL_W * header.len() as u32;
        let frame = Frame::new(scene.title("Metrics"), Vec::new(), width.max(900));
        Table {
            frame,
            header,
            rows,
            width: width.max(900),
        }
    }
}

impl Figure for Table {
    fn name(&self) -> &'static str {
        super::TABLE
    }

    fn size(&self) -> (u32, u32) {
        let h = self.frame.height() + (self.rows.len() as u32 + 1) * ROW_H + MARGIN;
        (self.width, h)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, _: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let x0 = MARGIN as i32;
        let x1 = (MARGIN + LABEL_W + COL_W * self.header.len() as u32) as i32;
        let y = |r: usize| MARGIN as i32 / 2 + (r as u32 * ROW_H) as i32;
        let left = text(TICK).pos(Pos::new(HPos::Left, VPos::Center));
        let right = text(TICK).pos(Pos::new(HPos::Right, VPos::Center));
        body.draw(&Rectangle::new(
            [(x0, y(0)), (x1, y(1))],
            RGBColor(225, 230, 238).filled(),
        ))?;
        for r in 1..=self.rows.len() {
            if r % 2 == 0 {
                body.draw(&Rectangle::new(
                    [(x0, y(r)), (x1, y(r + 1))],
                    RGBColor(245, 246, 248).filled(),
                ))?;
            }
        }
        let col_x = |c: usize| x0 + (LABEL_W + COL_W * (c as u32 + 1)) as i32 - 14;
        let mid = |r: usize| y(r) + ROW_H as i32 / 2;
        body.draw_text("metric", &left, (x0 + 12, mid(0)))?;
        for (c, h) in self.header.iter().enumerate() {
            body.draw_text(h, &right, (col_x(c), mid(0)))?;
        }
        for (r, (label, cells)) in self.rows.iter().enumerate() {
            body.draw_text(label, &left, (x0 + 12, mid(r + 1)))?;
            for (c, v) in cells.iter().enumerate() {
                body.draw_text(v, &right, (col_x(c), mid(r + 1)))?;
            }
        }
        let bottom = y(self.rows.len() + 1);
        let rule = BLACK.stroke_width(1);
        for yy in [y(0), y(1), bottom] {
            body.draw(&PathElement::new(vec![(x0, yy), (x1, yy)], rule))?;
        }
        let mission_x = x0 + (LABEL_W + COL_W * (self.header.len() as u32 - 1)) as i32;
        body.draw(&PathElement::new(
            vec![(mission_x, y(0)), (mission_x, bottom)],
            rule,
        ))?;
        Ok(())
    }
}
