//! How a commanded force and torque are shared among the thrusters (MODEL.md section 7):
//! for each signed wrench axis the duties that give it pure, found once by non-negative
//! least squares, and the quantisation of on-times to the minimum on-time.

use crate::scenario::{MAX_THRUSTERS, Thruster};
use glam::DVec3;

/// The wrench a law asks for over one control period: a force and a torque about the CG,
/// both in B, as means over the period.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Wrench {
    /// Force on the lander, in B, N.
    pub force_b_n: DVec3,
    /// Torque about the CG, in B, N m.
    pub torque_b_n_m: DVec3,
}

impl Wrench {
    fn axes(&self) -> [f64; 6] {
        let (f, m) = (self.force_b_n, self.torque_b_n_m);
        [f.x, f.y, f.z, m.x, m.y, m.z]
    }
}

/// How a commanded wrench is shared among the thrusters: for each of the twelve signed
/// wrench axes (force along +-X_B, +-Y_B, +-Z_B, torque about them), the thrusters' duty
/// (fraction of a period at full thrust) that gives one unit of that wrench alone (1 N, or
/// 1 N m) and nothing else, or `None` where the cluster cannot give it pure. Found once,
/// from the nominal thrusters, by non-negative least squares.
#[derive(Debug, Clone, PartialEq)]
pub struct Allocation {
    /// `[axis * 2 + (0 for +, 1 for -)]`.
    pub unit: [Option<Vec<f64>>; 12],
}

/// How far from the asked-for axis an allocation may land, relative to the unit it gives,
/// and still count as pure: the least-squares solution of a cluster that can give the
/// wrench pure misses by the ridge's shrinkage (about 1e-9); one that cannot misses by a
/// sizeable fraction of it.
pub(super) const PURE_TOLERANCE: f64 = 1e-6;

impl Allocation {
    /// The allocation of `thrusters` (nominal force directions and thrusts).
    #[must_use]
    pub fn new(thrusters: &[Thruster]) -> Allocation {
        let columns: Vec<[f64; 6]> = thrusters
            .iter()
            .map(|t| {
                let d = DVec3::from_array(t.direction) * t.max_thrust_n;
                let m = DVec3::from_array(t.position_m).cross(d);
                [d.x, d.y, d.z, m.x, m.y, m.z]
            })
            .collect();
        let unit = std::array::from_fn(|k| {
            let mut target = [0.0; 6];
            target[k / 2] = if k % 2 == 0 { 1.0 } else { -1.0 };
            let duty = nnls(&columns, target);
            let mut miss: f64 = 0.0;
            for (axis, want) in target.iter().enumerate() {
                let got: f64 = columns.iter().zip(&duty).map(|(c, u)| c[axis] * u).sum();
                miss = miss.max((got - want).abs());
            }
            (miss < PURE_TOLERANCE && duty.iter().any(|&u| u > 0.0)).then_some(duty)
        });
        Allocation { unit }
    }

    /// Whether the cluster can give the signed wrench axis `k` (as `unit`) pure.
    #[must_use]
    pub fn can(&self, k: usize) -> bool {
        self.unit[k].is_some()
    }

    /// The duty of every thruster for `wrench` (into `duty`): the torque first, scaled
    /// down as a whole where it alone would need a thruster for longer than the period,
    /// then as much of the force as the thrusters have left, scaled as a whole. Axes the
    /// cluster cannot give pure get nothing.
    pub fn duties(&self, wrench: &Wrench, duty: &mut [f64]) {
        let w = wrench.axes();
        let share = |axes: std::ops::Range<usize>, out: &mut [f64]| {
            out.fill(0.0);
            for axis in axes {
                let k = axis * 2 + usize::from(w[axis] < 0.0);
                if let Some(unit) = &self.unit[k] {
                    for (o, u) in out.iter_mut().zip(unit) {
                        *o += w[axis].abs() * u;
                    }
                }
            }
        };
        let n = duty.len();
        let mut torque = [0.0; MAX_THRUSTERS];
        let mut force = [0.0; MAX_THRUSTERS];
        share(3..6, &mut torque[..n]);
        share(0..3, &mut force[..n]);
        let most = torque[..n].iter().copied().fold(0.0, f64::max);
        if most > 1.0 {
            torque[..n].iter_mut().for_each(|t| *t /= most);
        }
        let mut scale: f64 = 1.0;
        for (t, f) in torque[..n].iter().zip(&force[..n]) {
            if *f > 0.0 {
                scale = scale.min((1.0 - t).max(0.0) / f);
            }
        }
        for ((d, t), f) in duty.iter_mut().zip(&torque[..n]).zip(&force[..n]) {
            *d = t + scale * f;
        }
    }
}

/// Non-negative least squares, `min |A u - target|^2 + ridge |u|^2` over `u >= 0` (`A`
/// given by its columns), by Lawson and Hanson's active-set method (exact, in finitely
/// many steps). The ridge, `1e-9` of the largest column's squared length, makes the
/// minimiser unique and picks, among exact solutions, the one of least `|u|`: the thrust
/// spread most evenly (a symmetric cluster fires symmetrically). It shrinks the solution
/// by about that fraction, far below `PURE_TOLERANCE`. Small sizes (at most
/// `MAX_THRUSTERS` columns, six rows), once per sweep.
fn nnls(columns: &[[f64; 6]], target: [f64; 6]) -> Vec<f64> {
    let n = columns.len();
    let scale = columns
        .iter()
        .map(|c| c.iter().map(|x| x * x).sum::<f64>())
        .fold(0.0, f64::max);
    let ridge = 1e-9 * scale.max(f64::MIN_POSITIVE);
    // Normal equations of the ridge problem: G = A^T A + ridge I, b = A^T target.
    let dot = |a: &[f64; 6], b: &[f64; 6]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let g: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| dot(&columns[i], &columns[j]) + if i == j { ridge } else { 0.0 })
                .collect()
        })
        .collect();
    let b: Vec<f64> = columns.iter().map(|c| dot(c, &target)).collect();
    // The gradient's negative, b - G u.
    let descent = |u: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| b[i] - (0..n).map(|j| g[i][j] * u[j]).sum::<f64>())
            .collect()
    };
    // Unconstrained minimiser over the free set, zero elsewhere.
    let solve = |free: &[bool]| -> Vec<f64> {
        let idx: Vec<usize> = (0..n).filter(|&i| free[i]).collect();
        let k = idx.len();
        let mut m: Vec<Vec<f64>> = idx
            .iter()
            .map(|&i| {
                let mut row: Vec<f64> = idx.iter().map(|&j| g[i][j]).collect();
                row.push(b[i]);
                row
            })
            .collect();
        for col in 0..k {
            let pivot = (col..k)
                .max_by(|&x, &y| m[x][col].abs().total_cmp(&m[y][col].abs()))
                .unwrap_or(col);
            m.swap(col, pivot);
            let (top, rest) = m.split_at_mut(col + 1);
            let pivot_row = &top[col];
            for row in rest.iter_mut() {
                let f = row[col] / pivot_row[col];
                for (x, p) in row[col..].iter_mut().zip(&pivot_row[col..]) {
                    *x -= f * p;
                }
            }
        }
        let mut z = vec![0.0; k];
        for r in (0..k).rev() {
            let sum: f64 = (r + 1..k).map(|c| m[r][c] * z[c]).sum();
            z[r] = (m[r][k] - sum) / m[r][r];
        }
        let mut out = vec![0.0; n];
        for (&i, v) in idx.iter().zip(z) {
            out[i] = v;
        }
        out
    };
    let mut u = vec![0.0; n];
    let mut free = vec![false; n];
    let tolerance = 1e-12 * b.iter().fold(0.0f64, |a, x| a.max(x.abs())).max(1e-300);
    for _ in 0..(3 * n + 10) {
        let w = descent(&u);
        let Some(t) = (0..n)
            .filter(|&j| !free[j] && w[j] > tolerance)
            .max_by(|&x, &y| w[x].total_cmp(&w[y]))
        else {
            break;
        };
        free[t] = true;
        loop {
            let z = solve(&free);
            if (0..n).filter(|&j| free[j]).all(|j| z[j] > 0.0) {
                u = z;
                break;
            }
            let alpha = (0..n)
                .filter(|&j| free[j] && z[j] <= 0.0)
                .map(|j| u[j] / (u[j] - z[j]))
                .fold(f64::INFINITY, f64::min);
            for j in 0..n {
                u[j] += alpha * (z[j] - u[j]);
                if free[j] && u[j] <= 1e-15 {
                    free[j] = false;
                    u[j] = 0.0;
                }
            }
        }
    }
    u
}

/// An on-time `on` (s) as a whole multiple of the minimum on-time `min_on` (nearest), at
/// most a period's worth of them.
#[must_use]
pub fn quantise(on: f64, min_on: f64, period: f64) -> f64 {
    let most = (period / min_on + 1e-9).floor();
    (on / min_on).round().clamp(0.0, most) * min_on
}
