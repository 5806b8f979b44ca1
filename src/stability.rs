//! The static tipping limit of a gear (MODEL.md section 8, thesis 2.2): a lander standing
//! still on a slope tips when the slope exceeds `atan(r / h)`, `r` the distance from the
//! CG's foot to the support polygon's edge along the downhill direction and `h` the CG
//! height above the footpad plane.

/// The support polygon of footpads `tips_m` (in B, CG at the origin): their convex hull in
/// the `X_B Y_B` plane, counter-clockwise, without collinear points.
#[must_use]
pub fn support_polygon(tips_m: &[[f64; 3]]) -> Vec<[f64; 2]> {
    support_hull(tips_m)
        .into_iter()
        .map(|i| [tips_m[i][0], tips_m[i][1]])
        .collect()
}

/// The footpads of `tips_m` on their support polygon (`support_polygon`), by index, in its
/// order: counter-clockwise from the lowest `x` (then `y`); of footpads at the same place
/// seen along `Z_B`, the first. Footpads inside the polygon, or on an edge between two of
/// its corners, are not in it.
#[must_use]
pub fn support_hull(tips_m: &[[f64; 3]]) -> Vec<usize> {
    let xy = |i: usize| [tips_m[i][0], tips_m[i][1]];
    let mut p: Vec<usize> = (0..tips_m.len()).collect();
    p.sort_by(|&a, &b| {
        let (a, b) = (xy(a), xy(b));
        a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1]))
    });
    p.dedup_by(|b, a| xy(*a) == xy(*b));
    if p.len() < 3 {
        return p;
    }
    let cross = |o: usize, a: usize, b: usize| {
        let (o, a, b) = (xy(o), xy(a), xy(b));
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    // Andrew's monotone chain: lower hull left to right, then upper hull right to left.
    let mut hull: Vec<usize> = Vec::with_capacity(2 * p.len());
    for pass in [p.clone(), p.iter().rev().copied().collect()] {
        let start = hull.len();
        for q in pass {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], q) <= 0.0
            {
                hull.pop();
            }
            hull.push(q);
        }
        hull.pop();
    }
    hull
}

/// The static tipping limit, deg, of a lander with footpads `tips_m` (in B, CG at the
/// origin, footpads at the same height below it) on a slope whose downhill direction lies
/// `downhill_deg` from `X_B`. `None` when the CG is not above the inside of the support
/// polygon or not above the footpads: such a gear stands on no slope.
#[must_use]
pub fn static_limit_deg(tips_m: &[[f64; 3]], downhill_deg: f64) -> Option<f64> {
    let h = -tips_m.iter().map(|t| t[2]).sum::<f64>() / tips_m.len().max(1) as f64;
    let hull = support_polygon(tips_m);
    if hull.len() < 3 || h.is_nan() || h <= 0.0 {
        return None;
    }
    let (uy, ux) = downhill_deg.to_radians().sin_cos();
    // Along u, the CG's foot leaves the polygon through the first edge it meets: the
    // least d / (n . u) over the edges facing u (n the edge's outward unit normal, d its
    // distance from the origin).
    let mut reach = f64::INFINITY;
    for (i, a) in hull.iter().enumerate() {
        let b = hull[(i + 1) % hull.len()];
        let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
        let len = ex.hypot(ey);
        let (nx, ny) = (ey / len, -ex / len);
        let d = nx * a[0] + ny * a[1];
        if d <= 0.0 {
            return None;
        }
        let facing = nx * ux + ny * uy;
        if facing > 0.0 {
            reach = reach.min(d / facing);
        }
    }
    Some((reach / h).atan().to_degrees())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn regular(legs: usize, radius: f64, height: f64, first_deg: f64) -> Vec<[f64; 3]> {
        (0..legs)
            .map(|i| {
                let az = (first_deg + 360.0 * i as f64 / legs as f64).to_radians();
                [radius * az.cos(), radius * az.sin(), -height]
            })
            .collect()
    }

    #[test]
    fn default_gear_matches_model_md() {
        // MODEL.md section 8: 44.7 deg with a side downhill, 54.4 deg with a leg downhill,
        // i.e. atan(0.6 cos 45 / 0.428936) and atan(0.6 / 0.428936).
        let tips = regular(4, 0.6, 0.428936, 45.0);
        let side = static_limit_deg(&tips, 0.0).unwrap();
        let leg = static_limit_deg(&tips, 45.0).unwrap();
        assert!((side - 44.686).abs() < 1e-3, "{side}");
        assert!((leg - 54.439).abs() < 1e-3, "{leg}");
    }

    #[test]
    fn regular_gears_follow_the_closed_form() {
        // For a regular n-gon of circumradius R the boundary lies at
        // R cos(pi/n) / cos(angle from the nearest edge normal) along any direction.
        for legs in [3usize, 4, 5, 6] {
            for (radius, height, first) in [(0.5, 0.4, 0.0), (0.9, 0.3, 17.0), (0.6, 0.43, 45.0)] {
                let tips = regular(legs, radius, height, first);
                let sector = 360.0 / legs as f64;
                for k in 0..72 {
                    let phi = 5.0 * f64::from(k) + 0.3;
                    let from_normal = (phi - first - sector / 2.0).rem_euclid(sector);
                    let off = from_normal.min(sector - from_normal).to_radians();
                    let r = radius * (PI / legs as f64).cos() / off.cos();
                    let expected = (r / height).atan().to_degrees();
                    let got = static_limit_deg(&tips, phi).unwrap();
                    assert!(
                        (got - expected).abs() < 1e-9,
                        "{legs} legs, R {radius}, az {phi}: {got} vs {expected}"
                    );
                }
            }
        }
    }

    #[test]
    fn gears_that_cannot_stand_have_no_limit() {
        // CG outside the polygon, a footpad line, and footpads above the CG.
        let offset: Vec<[f64; 3]> = regular(4, 0.6, 0.4, 45.0)
            .iter()
            .map(|t| [t[0] + 1.0, t[1], t[2]])
            .collect();
        assert_eq!(static_limit_deg(&offset, 0.0), None);
        assert_eq!(
            static_limit_deg(&[[1.0, 0.0, -0.4], [-1.0, 0.0, -0.4]], 90.0),
            None
        );
        assert_eq!(static_limit_deg(&regular(4, 0.6, -0.4, 45.0), 0.0), None);
        // A redundant footpad inside the polygon changes nothing.
        let mut five = regular(4, 0.6, 0.4, 45.0);
        five.push([0.1, 0.0, -0.4]);
        let four = static_limit_deg(&regular(4, 0.6, 0.4, 45.0), 10.0);
        assert_eq!(static_limit_deg(&five, 10.0), four);
    }
}
