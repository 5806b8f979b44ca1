//! A trace's columns as the lines of its pictures: against time, held as staircases, per
//! leg, the tilt from the slope normal, the control loop's phases and firings.

use crate::plot::canvas::{Area, FONT, Line, SERIES_COLOURS, drawing, span};
use crate::scene::Trace;

/// Time axis label of every panel.
pub(super) const TIME: &str = "time (s)";

/// A trace, with the slope's normal its tilt is measured from.
pub(super) struct Series {
    /// The trace as `scene::Trace` reads it (its caption in `about`).
    pub(super) trace: Trace,
    /// Unit normal of the slope plane, in I.
    pub(super) normal: [f64; 3],
}

impl Series {
    /// Reads the trace file at `path` (`Trace::read`).
    pub(super) fn read(path: &std::path::Path) -> anyhow::Result<Series> {
        let trace = Trace::read(path)?;
        let (sa, ca) = trace.slope_deg().to_radians().sin_cos();
        let (sb, cb) = trace.downhill_azimuth_deg().to_radians().sin_cos();
        Ok(Series {
            normal: [sa * cb, sa * sb, ca],
            trace,
        })
    }

    /// What the control loop flew, for the captions of its pictures, in lines of at most
    /// about `width` characters: the drawn law parameters, a descent's release state and
    /// the propellant (none for a trace without them).
    pub(super) fn flown(&self, width: usize) -> Vec<String> {
        let v = |name: &str| self.trace.control_value(name);
        let mut parts = Vec::new();
        if let (Some(f), Some(d)) = (v("hold_down_thrust_n"), v("hold_down_duration_s")) {
            parts.push(format!("hold-down {f:.2} N for {d:.2} s"));
        }
        if let (Some(kp), Some(kd)) = (v("attitude_kp_n_m_per_rad"), v("attitude_kd_n_m_s_per_rad"))
        {
            parts.push(format!(
                "attitude hold kp {kp:.3} N m/rad, kd {kd:.3} N m s/rad"
            ));
        }
        if let Some(h) = v("descent_start_altitude_m") {
            let at = |name| v(name).unwrap_or(f64::NAN);
            parts.push(format!(
                "descent from {h:.2} m at {:.3} m/s, braking {:.4} m/s^2, gain {:.3}/s, release \
                 below {:.4} m/s",
                at("descent_start_speed_m_s"),
                at("descent_braking_m_s2"),
                at("descent_gain_per_s"),
                at("descent_release_speed_m_s"),
            ));
            parts.push(match v("release_time_s") {
                Some(t) if t.is_finite() => format!(
                    "released at {t:.2} s, footpads {:.3} m up, v ({:.4}, {:.4}, {:.4}) m/s",
                    at("release_altitude_m"),
                    at("release_vx_m_s"),
                    at("release_vy_m_s"),
                    at("release_vz_m_s"),
                ),
                _ => "not released: contact came first".to_string(),
            });
        }
        if let Some(p) = v("propellant_kg") {
            parts.push(format!("propellant {:.1} g", p * 1e3));
        }
        let mut lines: Vec<String> = Vec::new();
        for part in parts {
            match lines.last_mut() {
                Some(l) if l.len() + 2 + part.len() <= width => {
                    l.push_str("; ");
                    l.push_str(&part);
                }
                _ => lines.push(part),
            }
        }
        lines
    }

    /// `root` titled "`what`, sample N of seed S: OUTCOME at T s", with what the control
    /// loop flew (`flown`) on the lines below; returns the area under them.
    pub(super) fn titled<'a>(&self, root: &Area<'a>, what: &str) -> anyhow::Result<Area<'a>> {
        let mut area = root
            .titled(&format!("{what}, {}", self.about()), (FONT, 22))
            .map_err(drawing)?;
        // 15-point text is about 8 pixels a character.
        for line in self.flown(usize::try_from(root.dim_in_pixel().0 / 8).unwrap_or(100)) {
            area = area.titled(&line, (FONT, 15)).map_err(drawing)?;
        }
        Ok(area)
    }

    /// "sample N of seed S: OUTCOME at T s", for the captions.
    pub(super) fn about(&self) -> &str {
        &self.trace.about
    }

    /// Column `name` against time, as a line labelled `label` in colour `k`, scaled by
    /// `scale`.
    pub(super) fn line(
        &self,
        name: &str,
        label: &str,
        k: usize,
        scale: f64,
    ) -> anyhow::Result<Line> {
        let y = self.trace.column_named(name)?;
        Ok(Line {
            label: label.to_string(),
            colour: SERIES_COLOURS[k % SERIES_COLOURS.len()],
            points: self
                .trace
                .time
                .iter()
                .copied()
                .zip(y.iter().map(|v| v * scale))
                .collect(),
        })
    }

    /// Column `what` of every leg against time, scaled by `scale`.
    pub(super) fn per_leg(&self, what: &str, scale: f64) -> anyhow::Result<Vec<Line>> {
        (0..self.trace.legs)
            .map(|k| self.line(&format!("leg{k}_{what}"), &format!("leg {k}"), k, scale))
            .collect()
    }

    /// The tilt of Z_B from the slope normal against time, deg.
    pub(super) fn tilt(&self) -> anyhow::Result<Line> {
        let q = |n: &str| self.trace.column_named(n);
        let (w, x, y, z) = (q("qw")?, q("qx")?, q("qy")?, q("qz")?);
        let n = self.normal;
        let points = (0..self.trace.time.len())
            .map(|i| {
                // Z_B in I: the third column of the rotation matrix of the quaternion.
                let zb = [
                    2.0 * (x[i] * z[i] + w[i] * y[i]),
                    2.0 * (y[i] * z[i] - w[i] * x[i]),
                    1.0 - 2.0 * (x[i] * x[i] + y[i] * y[i]),
                ];
                let c = zb[0] * n[0] + zb[1] * n[1] + zb[2] * n[2];
                (self.trace.time[i], c.clamp(-1.0, 1.0).acos().to_degrees())
            })
            .collect();
        Ok(Line {
            label: "tilt from the slope normal".to_string(),
            colour: SERIES_COLOURS[3],
            points,
        })
    }

    /// The time axis of every panel.
    pub(super) fn time_range(&self) -> std::ops::Range<f64> {
        span(self.trace.time.iter().copied(), 0.0)
    }

    /// `values` against time as a staircase: each row's value holds until the next row (a
    /// thrust is constant over a step); null rows (NaN) left out.
    pub(super) fn held(&self, label: &str, k: usize, values: &[f64]) -> Line {
        let mut points = Vec::with_capacity(2 * values.len());
        for (i, (&t, &v)) in self.trace.time.iter().zip(values).enumerate() {
            if !v.is_finite() {
                continue;
            }
            points.push((t, v));
            if let Some(&next) = self.trace.time.get(i + 1) {
                points.push((next, v));
            }
        }
        Line {
            label: label.to_string(),
            colour: SERIES_COLOURS[k % SERIES_COLOURS.len()],
            points,
        }
    }

    /// Column `name` against time as a staircase (`held`), scaled by `scale`.
    pub(super) fn held_column(
        &self,
        name: &str,
        label: &str,
        k: usize,
        scale: f64,
    ) -> anyhow::Result<Line> {
        let v: Vec<f64> = self
            .trace
            .column_named(name)?
            .iter()
            .map(|v| v * scale)
            .collect();
        Ok(self.held(label, k, &v))
    }

    /// The control loop's phases and the times they start, in order.
    pub(super) fn phases(&self) -> Vec<(f64, &str)> {
        let Some(phase) = self.trace.phases() else {
            return Vec::new();
        };
        let mut out: Vec<(f64, &str)> = Vec::new();
        for (t, p) in self.trace.time.iter().zip(phase) {
            if out.last().is_none_or(|last| last.1 != p) {
                out.push((*t, p));
            }
        }
        out
    }

    /// The intervals in which thruster `j` fires: from a row with thrust to the next row
    /// without, joined where they touch.
    pub(super) fn firings(&self, j: usize) -> anyhow::Result<Vec<(f64, f64)>> {
        let thrust = self.trace.column_named(&format!("thruster{j}_thrust_n"))?;
        let mut out: Vec<(f64, f64)> = Vec::new();
        for (i, (&t, &f)) in self.trace.time.iter().zip(thrust).enumerate() {
            if f <= 0.0 {
                continue;
            }
            let end = self.trace.time.get(i + 1).copied().unwrap_or(t);
            match out.last_mut() {
                Some(last) if last.1 >= t => last.1 = end,
                _ => out.push((t, end)),
            }
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::Series;
    use crate::run::trace::{TraceSettings, trace};
    use std::path::Path;

    /// The captions of a descent's trace: its law parameters, release state and
    /// propellant as the trace stores them; a passive trace's have none.
    #[test]
    fn captions_carry_what_flew() {
        let dir = std::env::temp_dir().join(format!("touchdown-captions-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let out = dir.join("descent.arrow");
        let scenario = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/descent.toml");
        let settings = TraceSettings {
            sweep: None,
            scenario: Some(scenario),
            scenario_toml: None,
            seed: None,
            inputs: None,
            sample: 0,
            out: Some(out.clone()),
            every: 100,
        };
        let done = trace(&settings).unwrap();
        let c = done.summary.control.unwrap();
        let text = Series::read(&out).unwrap().flown(110).join("\n");
        for part in [
            "attitude hold kp 20.000 N m/rad, kd 40.000 N m s/rad".to_string(),
            "descent from 15.00 m at 0.200 m/s".to_string(),
            format!("released at {:.2} s", c.release_time_s),
            format!("propellant {:.1} g", c.propellant_kg * 1e3),
        ] {
            assert!(text.contains(&part), "{part:?} not in\n{text}");
        }
        let passive = dir.join("passive.arrow");
        let settings = TraceSettings {
            scenario: None,
            out: Some(passive.clone()),
            ..settings
        };
        trace(&settings).unwrap();
        assert!(Series::read(&passive).unwrap().flown(110).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
