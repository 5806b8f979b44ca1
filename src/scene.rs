//! A trace file as something to look at (`touchdown animate`, `touchdown view`): the
//! lander's shape in B, the surface it lands on, and its pose at any time.
//!
//! The trace holds the motion; its metadata holds the scenario and the sample, from which
//! the lander's geometry, the slope and the terrain tile are derived again. The shape drawn
//! is a sketch: the model's lander is a rigid body with point footpads, so the body (an
//! octagonal prism, the thesis's lander), the struts' length and the footpad discs are
//! proportions of the leg geometry, while every footpad is drawn where the trace has it.

use crate::output::columns::Table;
use crate::reference::Model;
use crate::scenario::Scenario;
use crate::slope::Surface;
use anyhow::{anyhow, bail};
use glam::{DQuat, DVec3};
use std::path::Path;

/// One leg of the sketch, in B.
#[derive(Debug, Clone, Copy)]
pub struct LegSketch {
    /// Top of the strut: `strut_length` above the footpad along the strut axis.
    pub hip: DVec3,
    /// The body's bottom corner that the leg's bracing meets.
    pub mount: DVec3,
    /// Footpad at zero stroke.
    pub tip0: DVec3,
    /// Unit strut axis, hip to footpad.
    pub axis: DVec3,
}

/// A thruster of the sketch, in B.
#[derive(Debug, Clone, Copy)]
pub struct ThrusterSketch {
    pub position: DVec3,
    /// Unit direction of its force on the lander (the plume points the other way).
    pub direction: DVec3,
    pub max_thrust_n: f64,
}

/// The lander's shape in B (CG at the origin), m.
#[derive(Debug, Clone)]
pub struct Sketch {
    /// The body's bottom and top octagons, corners in the same order.
    pub bottom: Vec<DVec3>,
    pub top: Vec<DVec3>,
    pub legs: Vec<LegSketch>,
    pub footpad_radius_m: f64,
    pub thrusters: Vec<ThrusterSketch>,
}

impl Sketch {
    /// The sketch of a model's lander. The default lander's CG sits 73.42 mm above its
    /// centre plate, 0.4289 m above the footpads (MODEL.md section 3); the body's bottom
    /// plate keeps that proportion of the CG height for any geometry, and the body's width
    /// and height are proportions of the footpad radius.
    fn of(model: &Model) -> Sketch {
        let n = model.legs.len().max(1) as f64;
        let radius = model
            .legs
            .iter()
            .map(|l| l.tip_m.x.hypot(l.tip_m.y))
            .sum::<f64>()
            / n;
        let cg_height = model.legs.iter().map(|l| -l.tip_m.z).sum::<f64>() / n;
        let (cg_height, radius) = (cg_height.max(0.05), radius.max(0.1));
        let body_radius = 0.62 * radius;
        let z_bottom = -0.171 * cg_height;
        let z_top = z_bottom + 0.75 * radius;
        let corner = |k: usize, z: f64| {
            let a = std::f64::consts::PI / 8.0 * (2 * k + 1) as f64;
            DVec3::new(body_radius * a.cos(), body_radius * a.sin(), z)
        };
        let bottom: Vec<DVec3> = (0..8).map(|k| corner(k, z_bottom)).collect();
        let top = (0..8).map(|k| corner(k, z_top)).collect();
        let strut_length = 0.55 * cg_height;
        let legs = model
            .legs
            .iter()
            .map(|l| {
                let hip = l.tip_m - strut_length * l.strut_axis;
                let mount = *bottom
                    .iter()
                    .min_by(|a, b| {
                        a.truncate()
                            .distance(hip.truncate())
                            .total_cmp(&b.truncate().distance(hip.truncate()))
                    })
                    .unwrap_or(&bottom[0]);
                LegSketch {
                    hip,
                    mount,
                    tip0: l.tip_m,
                    axis: l.strut_axis,
                }
            })
            .collect();
        let thrusters = model
            .control
            .as_ref()
            .map(|c| {
                c.thrusters
                    .iter()
                    .map(|t| ThrusterSketch {
                        position: DVec3::from_array(t.position_m),
                        direction: DVec3::from_array(t.direction).normalize_or_zero(),
                        max_thrust_n: t.max_thrust_n,
                    })
                    .collect()
            })
            .unwrap_or_default();
        Sketch {
            bottom,
            top,
            legs,
            footpad_radius_m: 0.12 * radius,
            thrusters,
        }
    }

    /// The distance from the CG to the farthest point of the sketch, m.
    #[must_use]
    pub fn reach_m(&self) -> f64 {
        self.top
            .iter()
            .chain(&self.bottom)
            .map(|p| p.length())
            .chain(
                self.legs
                    .iter()
                    .map(|l| l.tip0.length() + self.footpad_radius_m),
            )
            .fold(0.0, f64::max)
    }
}

/// The lander at one moment, and what acted on it since the previous one looked at.
#[derive(Debug, Clone)]
pub struct Pose {
    pub t_s: f64,
    pub cg: DVec3,
    /// Body to I.
    pub attitude: DQuat,
    /// Footpads in I, stroke included.
    pub tips: Vec<DVec3>,
    /// Damper stroke per leg, m.
    pub strokes: Vec<f64>,
    /// Largest normal force per leg over the interval, N.
    pub normal_n: Vec<f64>,
    /// Largest thrust per thruster over the interval, N.
    pub thrust_n: Vec<f64>,
    /// Tilt of Z_B from the slope normal, deg.
    pub tilt_deg: f64,
    /// The control loop's phase, if any.
    pub phase: Option<String>,
}

/// A patch of the surface: node `(i, j)` at `origin + i spacing u + j spacing v` plus
/// `heights[j nu + i]` along the normal (no heights: the plane).
#[derive(Debug, Clone)]
pub struct Ground {
    pub origin: DVec3,
    pub u: DVec3,
    pub v: DVec3,
    pub normal: DVec3,
    pub spacing_m: f64,
    pub nu: usize,
    pub nv: usize,
    pub heights: Option<Vec<f64>>,
}

impl Ground {
    /// Node `(i, j)` in I.
    #[must_use]
    pub fn node(&self, i: usize, j: usize) -> DVec3 {
        let h = self.heights.as_ref().map_or(0.0, |h| h[j * self.nu + i]);
        self.origin
            + self.u * (i as f64 * self.spacing_m)
            + self.v * (j as f64 * self.spacing_m)
            + self.normal * h
    }
}

/// Refuses an output `out` that is the trace file `trace` itself (a picture written over
/// the data it shows).
pub fn refuse_overwriting(trace: &Path, out: &Path) -> anyhow::Result<()> {
    if let (Ok(a), Ok(b)) = (std::fs::canonicalize(trace), std::fs::canonicalize(out))
        && a == b
    {
        bail!("--out {}: that is the trace file being read", out.display());
    }
    Ok(())
}

/// What a trace of every N steps leaves out, for a note to its user.
#[must_use]
pub fn sparse_note(trace: &Path, every: u64) -> Option<String> {
    (every > 1).then(|| {
        format!(
            "touchdown: note: {} holds one row every {every} steps (trace --every {every}): \
             the motion between rows is interpolated, and forces and firings between rows do \
             not show",
            trace.display()
        )
    })
}

/// A trace file ready to be drawn.
pub struct Scene {
    /// "sample N of seed S: OUTCOME at T s".
    pub about: String,
    pub outcome: String,
    pub decided_s: f64,
    pub slope_deg: f64,
    pub downhill_azimuth_deg: f64,
    pub surface: Surface,
    pub model: Model,
    pub sketch: Sketch,
    pub time: Vec<f64>,
    pub legs: usize,
    pub thrusters: usize,
    /// The trace's rows are every `every` steps (`touchdown trace --every`).
    pub every: u64,
    table: Table,
}

/// Most nodes of a ground patch along either side.
const MAX_SIDE_NODES: usize = 2000;

/// The columns every trace has that a picture needs.
const BODY_COLUMNS: [&str; 8] = ["t_s", "x_m", "y_m", "z_m", "qw", "qx", "qy", "qz"];

impl Scene {
    /// Reads the trace file at `path`; refuses, saying why, a file that is missing, cut
    /// off, not a trace of touchdown, or holding no rows.
    pub fn read(path: &Path) -> anyhow::Result<Scene> {
        if !path.is_file() {
            bail!("{}: no such trace file", path.display());
        }
        let table = Table::read(path, |_| true)?;
        match table.meta.get("touchdown.kind").map(String::as_str) {
            Some("trace") => {}
            Some(kind) => bail!(
                "{} is not a trace file of touchdown (it is a {kind} file; `touchdown trace \
                 --sweep {} --sample I` writes the trace of its sample I)",
                path.display(),
                path.display()
            ),
            None => bail!("{} is not a trace file of touchdown", path.display()),
        }
        if table.rows < 2 {
            bail!(
                "{} holds {} rows: nothing moves",
                path.display(),
                table.rows
            );
        }
        for c in BODY_COLUMNS {
            table.column(c, path)?;
        }
        if let Some((name, c)) = table.columns.iter().find(|(_, c)| c.len() != table.rows) {
            bail!(
                "{}: column {name} has {} values in {} rows",
                path.display(),
                c.len(),
                table.rows
            );
        }
        let meta = |k: &str| -> anyhow::Result<&String> {
            table
                .meta
                .get(k)
                .ok_or_else(|| anyhow!("{}: no {k} in its metadata", path.display()))
        };
        let number = |k: &str| -> anyhow::Result<f64> {
            meta(k)?
                .parse()
                .map_err(|_| anyhow!("{}: {k} is not a number", path.display()))
        };
        let mut scenario = Scenario::from_toml(meta("touchdown.scenario")?)
            .map_err(|e| anyhow!("the scenario stored in {}: {e}", path.display()))?;
        scenario.seed = meta("touchdown.seed")?
            .parse()
            .map_err(|_| anyhow!("{}: its seed is not a whole number", path.display()))?;
        let index: u64 = meta("touchdown.sample")?
            .parse()
            .map_err(|_| anyhow!("{}: its sample is not a whole number", path.display()))?;
        // The trace's own values decide (a table's, where its sweep ran one): its inputs
        // and parameters, and its terrain tile and offset where it stores them (an older
        // trace: drawn again, the same for a sweep without a table).
        let mut drawn = crate::sampling::sample(&scenario, index);
        let mut values = drawn.values();
        for (k, v) in values.iter_mut().enumerate() {
            let kind = if k < crate::scenario::INPUT_FIELDS.len() {
                "input"
            } else {
                "parameter"
            };
            let key = format!("touchdown.{kind}.{}", crate::scenario::value_name(k));
            if k < 2 || table.meta.contains_key(&key) {
                *v = number(&key)?;
            }
        }
        drawn.set_values(values);
        if let Ok(tile) = meta("touchdown.terrain_tile") {
            drawn.terrain_tile = tile.parse().map_err(|_| {
                anyhow!("{}: its terrain tile is not a whole number", path.display())
            })?;
            drawn.terrain_offset_m = [
                number("touchdown.terrain_offset_u_m")?,
                number("touchdown.terrain_offset_v_m")?,
            ];
        }
        // A parameter unlike the scenario's (a table's) is taken per sample as a drawn one.
        for p in crate::scenario::Parameter::ALL {
            let x = drawn.parameters[p as usize];
            if scenario.sampled[p as usize].is_none() && !x.is_nan() && x != scenario.parameter(p) {
                scenario.sampled[p as usize] =
                    Some(crate::scenario::Dist::Uniform { min: x, max: x });
            }
        }
        let surface = Surface::of(&drawn);
        // With the sample's own parameters (a drawn CG height moves the footpads).
        let model = Model::new(&scenario).for_sample(&drawn).into_owned();
        let sketch = Sketch::of(&model);
        let legs = (0..)
            .take_while(|k| table.columns.contains_key(&format!("leg{k}_tip_x_m")))
            .count();
        if legs != model.legs.len() {
            bail!(
                "{}: {legs} legs in its columns, {} in its scenario",
                path.display(),
                model.legs.len()
            );
        }
        let thrusters = (0..)
            .take_while(|j| table.columns.contains_key(&format!("thruster{j}_thrust_n")))
            .count();
        let time = table.column("t_s", path)?.to_vec();
        if time.iter().any(|t| !t.is_finite()) || time.windows(2).any(|w| w[1] < w[0]) {
            bail!("{}: its times do not increase", path.display());
        }
        let every = meta("touchdown.every")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(1);
        let outcome = meta("touchdown.outcome")?.clone();
        let decided_s = number("touchdown.decided_s")?;
        Ok(Scene {
            about: format!(
                "sample {index} of seed {}: {outcome} at {decided_s:.3} s",
                scenario.seed
            ),
            outcome,
            decided_s,
            slope_deg: drawn.inputs.slope_deg,
            downhill_azimuth_deg: drawn.inputs.downhill_azimuth_deg,
            surface,
            model,
            sketch,
            time,
            legs,
            thrusters,
            every,
            table,
        })
    }

    /// The first and last time of the trace, s.
    #[must_use]
    pub fn span_s(&self) -> (f64, f64) {
        (self.time[0], self.time[self.time.len() - 1])
    }

    /// Column `name` (every trace has those a pose reads: checked by `read`).
    #[must_use]
    pub fn column(&self, name: &str) -> &[f64] {
        self.table.columns.get(name).map_or(&[], Vec::as_slice)
    }

    /// The control loop's phase per row, if the trace has one.
    #[must_use]
    pub fn phases(&self) -> Option<&[String]> {
        self.table
            .texts
            .get(crate::output::trace::PHASE_COLUMN)
            .map(Vec::as_slice)
    }

    /// The row at or before `t` and the fraction of the way to the next.
    fn locate(&self, t: f64) -> (usize, f64) {
        let n = self.time.len();
        let i = self.time.partition_point(|&x| x <= t).clamp(1, n) - 1;
        if i + 1 >= n {
            return (n - 1, 0.0);
        }
        let (a, b) = (self.time[i], self.time[i + 1]);
        let f = if b > a {
            ((t - a) / (b - a)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (i, f)
    }

    /// Column `name` at `t`, between rows linearly.
    fn at(&self, name: &str, (i, f): (usize, f64)) -> f64 {
        let c = self.column(name);
        match (c.get(i), c.get(i + 1)) {
            (Some(a), Some(b)) if f > 0.0 => a + f * (b - a),
            (Some(a), _) => *a,
            _ => f64::NAN,
        }
    }

    /// The largest value of column `name` over the rows that act in `(from, to]` (the row
    /// in force at `from` included), NaN rows left out.
    fn peak(&self, name: &str, rows: std::ops::RangeInclusive<usize>) -> f64 {
        let c = self.column(name);
        c.get(rows)
            .unwrap_or(&[])
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
    }

    /// The pose at `t`, with the peaks of the forces and thrusts since `since` (a frame
    /// shows an impact or a firing shorter than the time between frames).
    #[must_use]
    pub fn pose(&self, since: f64, t: f64) -> Pose {
        let here = self.locate(t);
        let from = self.locate(since.min(t)).0;
        let rows = from..=here.0;
        let v = |x: &str, y: &str, z: &str| {
            DVec3::new(self.at(x, here), self.at(y, here), self.at(z, here))
        };
        let cg = v("x_m", "y_m", "z_m");
        // Between rows: the attitude by normalised linear interpolation (rows of a trace
        // written at every step are at most one flight step apart, over which the lander
        // turns little; a trace of every N steps is smoothed over more).
        let q = |i: usize| {
            let c = |n: &str| self.column(n)[i];
            DQuat::from_xyzw(c("qx"), c("qy"), c("qz"), c("qw"))
        };
        let (i, f) = here;
        let attitude = if i + 1 < self.time.len() && f > 0.0 {
            let (a, mut b) = (q(i), q(i + 1));
            if a.dot(b) < 0.0 {
                b = -b;
            }
            (a * (1.0 - f) + b * f).normalize()
        } else {
            q(i).normalize()
        };
        let tips = (0..self.legs)
            .map(|k| {
                v(
                    &format!("leg{k}_tip_x_m"),
                    &format!("leg{k}_tip_y_m"),
                    &format!("leg{k}_tip_z_m"),
                )
            })
            .collect();
        let strokes = (0..self.legs)
            .map(|k| self.at(&format!("leg{k}_stroke_m"), here))
            .collect();
        let normal_n = (0..self.legs)
            .map(|k| self.peak(&format!("leg{k}_normal_force_n"), rows.clone()))
            .collect();
        let thrust_n = (0..self.thrusters)
            .map(|j| self.peak(&format!("thruster{j}_thrust_n"), rows.clone()))
            .collect();
        let z_b = attitude * DVec3::Z;
        let tilt_deg = z_b
            .dot(self.surface.normal)
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees();
        Pose {
            t_s: t,
            cg,
            attitude,
            tips,
            strokes,
            normal_n,
            thrust_n,
            tilt_deg,
            phase: self.phases().and_then(|p| p.get(i)).cloned(),
        }
    }

    /// Column `name` at time `t`, between rows linearly (NaN for a column the trace lacks).
    #[must_use]
    pub fn value(&self, name: &str, t: f64) -> f64 {
        self.at(name, self.locate(t))
    }

    /// The largest value of column `name` over the rows in force from `since` to `t`.
    #[must_use]
    pub fn peak_between(&self, name: &str, since: f64, t: f64) -> f64 {
        self.peak(name, self.locate(since.min(t)).0..=self.locate(t).0)
    }

    /// The CG at every row.
    #[must_use]
    pub fn cg_path(&self) -> Vec<DVec3> {
        let (x, y, z) = (self.column("x_m"), self.column("y_m"), self.column("z_m"));
        (0..self.time.len())
            .map(|i| DVec3::new(x[i], y[i], z[i]))
            .collect()
    }

    /// The surface under the CG's path and `margin_m` around it, with nodes `spacing_m`
    /// apart (wider where the patch would pass `max_nodes` nodes, or `MAX_SIDE_NODES` along
    /// a side). Rows whose CG is not finite (a diverged sample's last) are left out.
    #[must_use]
    pub fn ground(&self, margin_m: f64, spacing_m: f64, max_nodes: usize) -> Ground {
        let s = &self.surface;
        let (mut lo, mut hi) = ([-margin_m; 2], [margin_m; 2]);
        let mut first = true;
        for p in self.cg_path().into_iter().filter(|p| p.is_finite()) {
            for (k, axis) in [s.tangent_u, s.tangent_v].iter().enumerate() {
                let c = axis.dot(p);
                if first {
                    (lo[k], hi[k]) = (c - margin_m, c + margin_m);
                } else {
                    lo[k] = lo[k].min(c - margin_m);
                    hi[k] = hi[k].max(c + margin_m);
                }
            }
            first = false;
        }
        let side = |k: usize, spacing: f64| (hi[k] - lo[k]) / spacing + 2.0;
        let mut spacing = spacing_m;
        while side(0, spacing) * side(1, spacing) > max_nodes as f64
            || side(0, spacing).max(side(1, spacing)) > MAX_SIDE_NODES as f64
        {
            spacing *= 2.0;
        }
        // Nodes on whole multiples of the spacing, so that grid lines fall on whole metres.
        let snap = |x: f64| (x / spacing).floor() * spacing;
        let (u0, v0) = (snap(lo[0]), snap(lo[1]));
        let nu = ((hi[0] - u0) / spacing).ceil() as usize + 1;
        let nv = ((hi[1] - v0) / spacing).ceil() as usize + 1;
        let origin = s.tangent_u * u0 + s.tangent_v * v0;
        let heights = self.model.terrain.as_ref().map(|terrain| {
            let mut h = Vec::with_capacity(nu * nv);
            for j in 0..nv {
                for i in 0..nu {
                    let p = origin
                        + s.tangent_u * (i as f64 * spacing)
                        + s.tangent_v * (j as f64 * spacing);
                    h.push(s.height(Some(terrain), p).0);
                }
            }
            h
        });
        Ground {
            origin,
            u: s.tangent_u,
            v: s.tangent_v,
            normal: s.normal,
            spacing_m: spacing,
            nu,
            nv,
            heights,
        }
    }
}
