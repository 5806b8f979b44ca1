//! A trace's columns as the lines of its pictures: against time, held as staircases, per
//! leg, the tilt from the slope normal, the control loop's phases and firings.

use crate::plot::canvas::{Line, SERIES_COLOURS, span};
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
