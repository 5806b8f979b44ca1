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
        // A duty of 1 burns the thruster's full thrust: propellant is proportional to it.
        let cost: Vec<f64> = thrusters.iter().map(|t| t.max_thrust_n).collect();
        let unit = std::array::from_fn(|k| {
            let mut target = [0.0; 6];
            target[k / 2] = if k % 2 == 0 { 1.0 } else { -1.0 };
            // The duties of least propellant fire only thrusters whose reduced cost is
            // zero (complementary slackness); among them, the one of least `|u|`, the
            // thrust spread most evenly (a symmetric cluster fires symmetrically).
            let cheapest = least_propellant(&columns, &cost, target)?;
            let on_face: Vec<[f64; 6]> = columns
                .iter()
                .zip(&cheapest)
                .map(|(&c, &cheap)| if cheap { c } else { [0.0; 6] })
                .collect();
            let duty = nnls(&on_face, target);
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
    /// then as much of the force along `Z_B` (the main axis: gravity, braking, hold-down)
    /// as the thrusters have left, then as much of the force across it, each scaled as a
    /// whole. Axes the cluster cannot give pure get nothing.
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
        let mut along = [0.0; MAX_THRUSTERS];
        let mut across = [0.0; MAX_THRUSTERS];
        share(3..6, &mut torque[..n]);
        share(2..3, &mut along[..n]);
        share(0..2, &mut across[..n]);
        let most = torque[..n].iter().copied().fold(0.0, f64::max);
        if most > 1.0 {
            torque[..n].iter_mut().for_each(|t| *t /= most);
        }
        duty.copy_from_slice(&torque[..n]);
        for force in [&along[..n], &across[..n]] {
            let mut scale: f64 = 1.0;
            for (d, f) in duty.iter().zip(force) {
                if *f > 0.0 {
                    scale = scale.min((1.0 - d).max(0.0) / f);
                }
            }
            if force.iter().any(|&f| f > 0.0) {
                for (d, f) in duty.iter_mut().zip(force) {
                    *d += scale * f;
                }
            }
        }
    }
}

/// Which thrusters the duties `u >= 0` of least propellant `sum_j cost_j u_j` that give
/// `target` exactly (`A u = target`, `A` given by its columns: a thruster's force and
/// moment at full thrust) may fire, or `None` where no duties give it. A linear programme,
/// by the simplex method in two phases (the first finds duties that give `target`, the
/// second lowers their propellant), with Bland's rule (the lowest index enters and leaves:
/// no cycling). At its optimum every thruster's reduced cost `cost_j - y . A_j` (`y` the
/// duals) is non-negative, and duties give `target` at least propellant exactly when they
/// fire only thrusters whose reduced cost is zero. Small sizes (six rows, at most
/// `MAX_THRUSTERS` columns), once per sweep.
fn least_propellant(columns: &[[f64; 6]], cost: &[f64], target: [f64; 6]) -> Option<Vec<bool>> {
    const ROWS: usize = 6;
    let n = columns.len();
    // The tableau: a row per axis (negated where its target is, so that the right-hand
    // side is non-negative) over the thrusters, an artificial variable per row, and the
    // right-hand side.
    let rhs = n + ROWS;
    let mut t = vec![vec![0.0; rhs + 1]; ROWS];
    let mut basis: [usize; ROWS] = std::array::from_fn(|i| n + i);
    for (i, row) in t.iter_mut().enumerate() {
        let sign = if target[i] < 0.0 { -1.0 } else { 1.0 };
        for (x, c) in row.iter_mut().zip(columns) {
            *x = sign * c[i];
        }
        row[n + i] = 1.0;
        row[rhs] = sign * target[i];
    }
    let largest = columns.iter().flatten().fold(1.0f64, |a, x| a.max(x.abs()));
    let eps = 1e-12 * largest;
    let pivot = |t: &mut Vec<Vec<f64>>, basis: &mut [usize; ROWS], r: usize, j: usize| {
        let p = t[r][j];
        t[r].iter_mut().for_each(|x| *x /= p);
        let pivot_row = t[r].clone();
        for (i, row) in t.iter_mut().enumerate() {
            let f = row[j];
            if i != r && f != 0.0 {
                for (x, y) in row.iter_mut().zip(&pivot_row) {
                    *x -= f * y;
                }
            }
        }
        basis[r] = j;
    };
    // Minimises `sum_j c_j x_j` from the basis at hand; only thrusters enter it.
    let simplex = |t: &mut Vec<Vec<f64>>, basis: &mut [usize; ROWS], c: &[f64]| {
        for _ in 0..1000 {
            let reduced = |j: usize| c[j] - (0..ROWS).map(|i| c[basis[i]] * t[i][j]).sum::<f64>();
            let Some(j) = (0..n).find(|&j| !basis.contains(&j) && reduced(j) < -eps) else {
                return;
            };
            let leave = (0..ROWS).filter(|&i| t[i][j] > eps).min_by(|&a, &b| {
                (t[a][rhs] / t[a][j])
                    .total_cmp(&(t[b][rhs] / t[b][j]))
                    .then(basis[a].cmp(&basis[b]))
            });
            // Unbounded below cannot happen: every cost is positive and every duty
            // non-negative.
            let Some(r) = leave else { return };
            pivot(t, basis, r, j);
        }
    };
    // Phase one: the artificial variables out, if any duties give the target.
    let mut artificial = vec![0.0; n + ROWS];
    artificial[n..].fill(1.0);
    simplex(&mut t, &mut basis, &artificial);
    let left: f64 = (0..ROWS).map(|i| artificial[basis[i]] * t[i][rhs]).sum();
    if left > 1e-9 {
        return None;
    }
    // An artificial variable left in the basis (at zero) is pivoted out on any thruster of
    // its row; a row with none is redundant (an axis no thruster acts on) and stays.
    for r in 0..ROWS {
        if basis[r] >= n
            && let Some(j) = (0..n).find(|&j| !basis.contains(&j) && t[r][j].abs() > eps)
        {
            pivot(&mut t, &mut basis, r, j);
        }
    }
    // Phase two: the least propellant.
    let mut propellant = cost.to_vec();
    propellant.extend([0.0; ROWS]);
    simplex(&mut t, &mut basis, &propellant);
    let dearest = cost.iter().copied().fold(0.0, f64::max);
    Some(
        (0..n)
            .map(|j| {
                let reduced = cost[j]
                    - (0..ROWS)
                        .map(|i| propellant[basis[i]] * t[i][j])
                        .sum::<f64>();
                reduced <= 1e-9 * dearest
            })
            .collect(),
    )
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

/// The on-time (s) of a thruster asked for `want_s` in a period of `period` s, having
/// `carry_s` left unfired (or fired beyond what was asked, negative) from the periods
/// before: `quantise`d together, so that over many periods the thruster fires what was
/// asked of it within half a minimum on-time. Returns the on-time and what it leaves to
/// carry, at most half a minimum on-time either way (more than that is beyond reach: an
/// on-time at its most, or none of a negative ask).
#[must_use]
pub fn quantise_carrying(want_s: f64, carry_s: f64, min_on: f64, period: f64) -> (f64, f64) {
    let total = want_s + carry_s;
    let on = quantise(total, min_on, period);
    (on, (total - on).clamp(-0.5 * min_on, 0.5 * min_on))
}

#[cfg(test)]
mod tests {
    use super::{Allocation, Wrench, quantise};
    use crate::scenario::Thruster;
    use glam::DVec3;

    fn thruster(position_m: [f64; 3], direction: [f64; 3], max_thrust_n: f64) -> Thruster {
        Thruster {
            position_m,
            direction,
            max_thrust_n,
            min_on_time_s: if max_thrust_n > 5.0 { 0.02 } else { 0.01 },
        }
    }

    /// The cluster of `scenarios/hold-down.toml`: four 10 N thrusters along -Z_B 0.35 m out
    /// (0-3), and a +Z_B and a -Z_B 1 N thruster at each of four points 0.45 m out (4-11).
    fn hold_down_cluster() -> Vec<Thruster> {
        let mut c = Vec::new();
        for p in [[0.35, 0.0], [-0.35, 0.0], [0.0, 0.35], [0.0, -0.35]] {
            c.push(thruster([p[0], p[1], 0.3], [0.0, 0.0, -1.0], 10.0));
        }
        for p in [[0.45, 0.0], [-0.45, 0.0], [0.0, 0.45], [0.0, -0.45]] {
            c.push(thruster([p[0], p[1], 0.3], [0.0, 0.0, 1.0], 1.0));
            c.push(thruster([p[0], p[1], 0.3], [0.0, 0.0, -1.0], 1.0));
        }
        c
    }

    fn wrench_of(cluster: &[Thruster], duty: &[f64]) -> (DVec3, DVec3, f64) {
        let (mut f, mut m, mut flow) = (DVec3::ZERO, DVec3::ZERO, 0.0);
        for (t, u) in cluster.iter().zip(duty) {
            let d = DVec3::from_array(t.direction) * t.max_thrust_n * u;
            f += d;
            m += DVec3::from_array(t.position_m).cross(d);
            flow += t.max_thrust_n * u;
        }
        (f, m, flow)
    }

    #[test]
    fn a_torque_comes_from_couples_at_least_propellant() {
        let cluster = hold_down_cluster();
        let a = Allocation::new(&cluster);
        // A pure torque of 1 N m about X_B or Y_B: a couple of the 1 N thrusters 0.9 m
        // apart, 1 / 0.9 N each, 2.22 N of thrust in all; the 10 N thrusters, 0.35 m out,
        // would need their force cancelled by others and cost more.
        for k in 6..10 {
            let unit = a.unit[k]
                .as_ref()
                .expect("the cluster turns about X_B and Y_B");
            let (f, m, flow) = wrench_of(&cluster, unit);
            let mut want = [0.0; 3];
            want[k / 2 - 3] = if k % 2 == 0 { 1.0 } else { -1.0 };
            assert!(f.length() < 1e-6, "axis {k}: net force {f}");
            assert!(
                (m - DVec3::from_array(want)).length() < 1e-6,
                "axis {k}: {m}"
            );
            assert!((flow - 2.0 / 0.9).abs() < 1e-6, "axis {k}: thrust {flow}");
            assert!(unit[..4].iter().all(|&u| u == 0.0), "axis {k}: {unit:?}");
        }
        // About Z_B the cluster has no moment arm at all.
        assert!(!a.can(10) && !a.can(11));
    }

    #[test]
    fn a_force_through_the_cg_is_spread_over_its_thrusters() {
        let cluster = hold_down_cluster();
        let a = Allocation::new(&cluster);
        // 1 N along -Z_B: every -Z_B thruster is on the face of least propellant (1 N of
        // thrust per N); the least |u| on it gives each a duty in proportion to its thrust,
        // `u_j = T_j / sum T^2` = 10 / 404 for the 10 N ones, 1 / 404 for the 1 N ones.
        let unit = a.unit[5].as_ref().expect("the cluster pushes along -Z_B");
        for (t, &u) in cluster.iter().zip(unit) {
            let want = if t.direction[2] < 0.0 {
                t.max_thrust_n / 404.0
            } else {
                0.0
            };
            // Within the shrinkage of the ridge of `nnls`, far below `PURE_TOLERANCE`.
            assert!((u - want).abs() <= 1e-6 * want, "{t:?}: {u} vs {want}");
        }
        // Along X_B it cannot push at all.
        assert!(!a.can(0) && !a.can(1));
    }

    #[test]
    fn a_torque_alone_quantised_with_carry_gives_no_net_impulse() {
        // Duties of a torque about X_B of 0.37 N m for 200 periods of 0.1 s, quantised with
        // each thruster carrying its unfired remainder (as `LaneControl` does): the couple's
        // two thrusters have the same duty and the same remainder, so they fire together
        // and the net force impulse is zero to rounding; the mean torque is the one asked
        // for within one quantum (1 N m s over the run: 0.9 m x 1 N x 10 ms / 20 s).
        let cluster = hold_down_cluster();
        let a = Allocation::new(&cluster);
        let period = 0.1;
        let asked = Wrench {
            force_b_n: DVec3::ZERO,
            torque_b_n_m: DVec3::new(0.37, 0.0, 0.0),
        };
        let mut duty = vec![0.0; cluster.len()];
        let mut carry = vec![0.0; cluster.len()];
        let (mut impulse, mut angular) = (DVec3::ZERO, DVec3::ZERO);
        let periods = 200;
        for _ in 0..periods {
            a.duties(&asked, &mut duty);
            let on: Vec<f64> = cluster
                .iter()
                .zip(&duty)
                .zip(&mut carry)
                .map(|((t, u), c)| {
                    let (on, left) =
                        super::quantise_carrying(u * period, *c, t.min_on_time_s, period);
                    *c = left;
                    on
                })
                .collect();
            let (f, m, _) = wrench_of(&cluster, &on);
            impulse += f;
            angular += m;
        }
        assert!(impulse.length() < 1e-12, "net impulse {impulse}");
        let total = periods as f64 * period;
        assert!((angular.x - 0.37 * total).abs() <= 0.9 * 0.01, "{angular}");
        assert_eq!(quantise(0.014, 0.01, 0.1), 0.01);
    }
}
