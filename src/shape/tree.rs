//! The attraction at every facet in `O(F log F)`: the polyhedron's sum of Werner and
//! Scheeres regrouped facet by facet, the facets near a point summed exactly and groups of
//! facets far from it by a multipole expansion (docs/MODEL.md, "The facets' gravity by a
//! tree").
//!
//! By the divergence theorem the attraction of a constant-density body is a sum over its
//! facets, `g(r) = -G rho sum_f n_f phi_f(r)`, with `phi_f(r) = int_f dS' / |r - r'|` the
//! potential of the facet as a sheet of unit density. Werner and Scheeres' edge dyads split
//! between the two facets of each edge give it in closed form:
//!
//! ```text
//! phi_f(r) = sum_{e of f} (n_e^f . r_e) L_e  -  (n_f . r_f) w_f
//! ```
//!
//! (`n_e^f` the outward normal of edge `e` in facet `f`'s plane; `r_e`, `L_e`, `r_f` and
//! `w_f` as in gravity.rs), so the facets' terms summed exactly are that sum, to rounding.
//! Far from a group of facets, `1 / |r - r'|` is expanded about the group's centre `c` in
//! `s = r' - c` to the degree [`ORDER`] (5), and the group's sum is `sum_a c_a(r - c) M_a`
//! with the group's moments `M_a = sum_f n_f int_f s^a dS'` for the 56 monomials `s^a` of
//! that degree or less (each integral exact: Radon's seven-point rule of degree 5 on the
//! triangle; a parent's moments are its children's, shifted exactly) and the Taylor
//! coefficients `c_a` by the recurrence of Duan and Krasny. A group is taken by its
//! moments from a leaf of points when `(D - rho) theta >= R`: `D` the distance between the
//! centres, `rho` the radius of the leaf's points, `R` the radius about the group's centre
//! that holds every vertex of its facets, `theta` the opening angle ([`OPENING`], 0.4). The
//! terms left out are at most `theta^6 / (1 - theta)` of the group's own terms (the first
//! of them `theta^6`); measured against the exact sum, the attraction is within 1.0e-5,
//! 1.3e-5 and 3.1e-5 at every facet of a sphere, an ellipsoid and a waisted body of 5,120
//! facets (tested: below 5e-5) and within 2.7e-5 at
//! 100 facets spread over a 1.3-million-facet ellipsoid (the README).
//!
//! The groups are the nodes of a binary tree of the facets (each node split at the median
//! centroid along its longest side, leaves of at most [`LEAF`] facets); the points are the
//! facets' centroids, taken by leaf, each leaf walking the tree once. Each point's sum is
//! taken in one fixed order: the result does not depend on the number of threads.

use super::mesh::CheckedMesh;
use super::vec3::{add, cross, dot, norm, scale, sub};
use rayon::prelude::*;

/// The most facets in a leaf of the tree.
pub const LEAF: usize = 16;

/// The default opening angle: the attraction's error was at most `3.1e-5` of its magnitude
/// wherever measured (tests/shape/tree.rs asserts below `5e-5`), at about `F log F` cost.
pub const OPENING: f64 = 0.4;

/// The degree of the expansion: the first term left out is of relative size `theta^(ORDER
/// + 1)` of a far group's own terms.
pub const ORDER: usize = 5;

/// The points whose coefficients are computed side by side.
const LANES: usize = 4;

/// The number of monomials `s^a` of degree [`ORDER`] or less.
const MONOMIALS: usize = (ORDER + 1) * (ORDER + 2) * (ORDER + 3) / 6;

/// A facet's share, in tree order: its corners, normal and twice its area, and per edge
/// (`ab`, `bc`, `ca`) the outward normal in its plane and the length.
#[derive(Debug, Clone, Copy)]
struct Facet {
    corners: [[f64; 3]; 3],
    normal: [f64; 3],
    twice_area_m2: f64,
    edge_normals: [[f64; 3]; 3],
    edge_lengths_m: [f64; 3],
}

/// A node of the tree: its facets `start..end` in tree order, its children (none for a
/// leaf), its centre, the radius about it that holds every vertex of its facets, and the
/// radius that holds their centroids.
#[derive(Debug, Clone, Copy)]
struct Node {
    start: u32,
    end: u32,
    children: Option<[u32; 2]>,
    centre: [f64; 3],
    radius_m: f64,
    reach_m: f64,
}

/// The facets of a checked mesh in a tree, each node with its moments: built once, it gives
/// the sum `sum_f n_f phi_f` at every facet's centroid.
#[derive(Debug, Clone)]
pub struct FacetTree {
    facets: Vec<Facet>,
    /// `order[k]`: the mesh's facet at place `k` of the tree order.
    order: Vec<u32>,
    nodes: Vec<Node>,
    /// Each node's moments, [`MONOMIALS`] a node.
    moments: Vec<[f64; 3]>,
    leaves: Vec<u32>,
    opening: f64,
}

impl FacetTree {
    /// The tree of `mesh`'s facets with the opening angle `opening` (in `[0, 1)`; 0 sums
    /// every facet exactly).
    ///
    /// # Panics
    /// If `opening` is not in `[0, 1)` (a caller's mistake).
    #[must_use]
    pub fn new(mesh: &CheckedMesh, opening: f64) -> Self {
        assert!(
            (0.0..1.0).contains(&opening),
            "the opening angle must lie in [0, 1), not {opening}"
        );
        let vertices = &mesh.mesh().vertices;
        let geometry = mesh.facet_geometry();
        let centroids: Vec<[f64; 3]> = geometry.iter().map(|g| g.centroid_m).collect();
        let mut order: Vec<u32> = (0..geometry.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * geometry.len() / LEAF + 2);
        split(&mut order, 0, &centroids, &mut nodes);
        let facets: Vec<Facet> = order
            .iter()
            .map(|&f| {
                let corners = mesh.mesh().facets[f as usize].map(|v| vertices[v as usize]);
                let g = geometry[f as usize];
                let mut edge_normals = [[0.0; 3]; 3];
                let mut edge_lengths_m = [0.0; 3];
                for k in 0..3 {
                    let along = sub(corners[(k + 1) % 3], corners[k]);
                    let length = norm(along);
                    edge_lengths_m[k] = length;
                    edge_normals[k] = cross(scale(along, 1.0 / length), g.normal);
                }
                Facet {
                    corners,
                    normal: g.normal,
                    twice_area_m2: 2.0 * g.area_m2,
                    edge_normals,
                    edge_lengths_m,
                }
            })
            .collect();
        for node in &mut nodes {
            bound(node, &facets[node.start as usize..node.end as usize]);
        }
        let moments = upward(&nodes, &facets);
        let leaves = (0..nodes.len() as u32)
            .filter(|&k| nodes[k as usize].children.is_none())
            .collect();
        FacetTree {
            facets,
            order,
            nodes,
            moments,
            leaves,
            opening,
        }
    }

    /// The number of leaves: the units of work of [`FacetTree::sums`].
    #[must_use]
    pub fn leaves(&self) -> usize {
        self.leaves.len()
    }

    /// The sum `sum_f n_f phi_f` (m) at the centroid of every facet, in the mesh's facet
    /// order, on rayon's threads; `done(k)` is called as each leaf of `k` facets is done.
    /// The attraction is `-G rho` times it. At a facet's own centroid its solid angle's
    /// term is left out (`n_f . r_f = 0` there), as [`super::Polyhedron::field_on_facet`]
    /// leaves it out.
    #[must_use]
    pub fn sums(&self, done: impl Fn(usize) + Sync) -> Vec<[f64; 3]> {
        let by_leaf: Vec<Vec<[f64; 3]>> = self
            .leaves
            .par_iter()
            .enumerate()
            .map(|(k, _)| {
                let sums = self.leaf_sums(k);
                done(sums.len());
                sums
            })
            .collect();
        let mut out = vec![[0.0; 3]; self.facets.len()];
        for (&leaf, sums) in self.leaves.iter().zip(by_leaf) {
            let start = self.nodes[leaf as usize].start as usize;
            for (k, s) in sums.into_iter().enumerate() {
                out[self.order[start + k] as usize] = s;
            }
        }
        out
    }

    /// The sums at the centroids of the facets of the `k`-th leaf (of [`FacetTree::leaves`]),
    /// in tree order: a share of [`FacetTree::sums`]' work, for an estimate of its time.
    ///
    /// # Panics
    /// If `k` is not below [`FacetTree::leaves`] (a caller's mistake).
    #[must_use]
    pub fn leaf_sums(&self, k: usize) -> Vec<[f64; 3]> {
        let target = self.nodes[self.leaves[k] as usize];
        let (far, near) = self.lists(&target);
        let targets: Vec<u32> = (target.start..target.end).collect();
        let mut out = Vec::with_capacity(targets.len());
        // LANES points at a time through the far nodes: their coefficients' recurrences
        // side by side (each point's numbers as it would be alone, in the same order).
        for chunk in targets.chunks(LANES) {
            let point = |l: usize| centroid(&self.facets[chunk[l.min(chunk.len() - 1)] as usize]);
            let r: [[f64; 3]; LANES] = std::array::from_fn(point);
            let mut sums = [[0.0; 3]; LANES];
            for &n in &far {
                let node = &self.nodes[n as usize];
                let c = coefficients(std::array::from_fn(|l| sub(r[l], node.centre)));
                let at = n as usize * MONOMIALS;
                for (c, m) in c.iter().zip(&self.moments[at..at + MONOMIALS]) {
                    for (sum, c) in sums.iter_mut().zip(c) {
                        *sum = add(*sum, scale(*m, *c));
                    }
                }
            }
            for (l, &t) in chunk.iter().enumerate() {
                let mut sum = sums[l];
                for &n in &near {
                    let node = &self.nodes[n as usize];
                    for f in node.start..node.end {
                        let facet = &self.facets[f as usize];
                        let phi = single_layer(facet, r[l], f == t);
                        sum = add(sum, scale(facet.normal, phi));
                    }
                }
                out.push(sum);
            }
        }
        out
    }

    /// The nodes a leaf's points take by their moments (far) and the leaves they sum facet
    /// by facet (near), each in the order of a walk down the tree.
    fn lists(&self, target: &Node) -> (Vec<u32>, Vec<u32>) {
        let mut far = Vec::new();
        let mut near = Vec::new();
        let mut stack = vec![0u32];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n as usize];
            let clear = norm(sub(target.centre, node.centre)) - target.reach_m;
            if clear > 0.0 && clear * self.opening >= node.radius_m {
                far.push(n);
            } else if let Some([a, b]) = node.children {
                stack.push(b);
                stack.push(a);
            } else {
                near.push(n);
            }
        }
        (far, near)
    }
}

/// Splits `order[..]` (the facets at places `offset..offset + order.len()` of the tree
/// order) into a node and its subtree, appended to `nodes` in pre-order; returns the node's
/// index. The median split along the longest side of the centroids' box, ties broken by
/// the facet's number: the same tree on any machine.
fn split(order: &mut [u32], offset: usize, centroids: &[[f64; 3]], nodes: &mut Vec<Node>) -> u32 {
    let index = nodes.len() as u32;
    nodes.push(Node {
        start: offset as u32,
        end: (offset + order.len()) as u32,
        children: None,
        centre: [0.0; 3],
        radius_m: 0.0,
        reach_m: 0.0,
    });
    if order.len() <= LEAF {
        return index;
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &f in order.iter() {
        let c = centroids[f as usize];
        for k in 0..3 {
            lo[k] = lo[k].min(c[k]);
            hi[k] = hi[k].max(c[k]);
        }
    }
    let axis = (0..3)
        .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
        .unwrap_or(0);
    let half = order.len() / 2;
    order.select_nth_unstable_by(half, |&a, &b| {
        centroids[a as usize][axis]
            .total_cmp(&centroids[b as usize][axis])
            .then(a.cmp(&b))
    });
    let (left, right) = order.split_at_mut(half);
    let a = split(left, offset, centroids, nodes);
    let b = split(right, offset + half, centroids, nodes);
    nodes[index as usize].children = Some([a, b]);
    index
}

/// Sets a node's centre (the middle of its facets' vertices' box) and its two radii.
fn bound(node: &mut Node, facets: &[Facet]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for f in facets {
        for v in f.corners {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
    }
    let centre = scale(add(lo, hi), 0.5);
    let mut radius: f64 = 0.0;
    let mut reach: f64 = 0.0;
    for f in facets {
        for v in f.corners {
            radius = radius.max(norm(sub(v, centre)));
        }
        reach = reach.max(norm(sub(centroid(f), centre)));
    }
    node.centre = centre;
    node.radius_m = radius;
    node.reach_m = reach;
}

/// A facet's centroid, as the mesh's geometry takes it.
fn centroid(f: &Facet) -> [f64; 3] {
    let [a, b, c] = f.corners;
    scale(add(add(a, b), c), 1.0 / 3.0)
}

/// The monomials `s^a = x^i y^j z^k` of degree up to [`ORDER`], in graded order (degree
/// by degree, `i` falling, then `j`); for the recurrence of the coefficients, the places of
/// `a - e_m` and `a - 2 e_m` for each axis `m` ([`MONOMIALS`], a coefficient held at 0,
/// where a power would fall below zero) and the factors `(2|a| - 1) / |a|` and `(|a| - 1) /
/// |a|`; for the shift of moments, each `b <= a` with `C(a, b) = prod_m C(a_m, b_m)`.
struct Monomials {
    powers: [[usize; 3]; MONOMIALS],
    less_one: [[usize; 3]; MONOMIALS],
    less_two: [[usize; 3]; MONOMIALS],
    factors: [[f64; 2]; MONOMIALS],
    below: Vec<Vec<(usize, f64)>>,
}

/// The table of [`Monomials`], built once.
fn table() -> &'static Monomials {
    static TABLE: std::sync::OnceLock<Monomials> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut powers = [[0; 3]; MONOMIALS];
        let mut n = 0;
        for degree in 0..=ORDER {
            for i in (0..=degree).rev() {
                for j in (0..=degree - i).rev() {
                    powers[n] = [i, j, degree - i - j];
                    n += 1;
                }
            }
        }
        let place = |p: [usize; 3]| powers.iter().position(|q| *q == p).unwrap_or(MONOMIALS);
        let less = |by: usize| {
            std::array::from_fn(|a| {
                std::array::from_fn(|m| {
                    let mut p = powers[a];
                    if p[m] < by {
                        return MONOMIALS;
                    }
                    p[m] -= by;
                    place(p)
                })
            })
        };
        let factors = std::array::from_fn(|a| {
            let n = powers[a].iter().sum::<usize>().max(1) as f64;
            [(2.0 * n - 1.0) / n, (n - 1.0) / n]
        });
        let choose =
            |n: usize, k: usize| (0..k).fold(1.0, |c, i| c * (n - i) as f64 / (i + 1) as f64);
        let below = powers
            .iter()
            .map(|a| {
                (0..MONOMIALS)
                    .filter(|&b| (0..3).all(|m| powers[b][m] <= a[m]))
                    .map(|b| {
                        let c = (0..3).map(|m| choose(a[m], powers[b][m])).product();
                        (b, c)
                    })
                    .collect()
            })
            .collect();
        Monomials {
            powers,
            less_one: less(1),
            less_two: less(2),
            factors,
            below,
        }
    })
}

/// Every node's moments: each leaf's from its facets ([`moments`]), on rayon's threads,
/// then each parent's from its children's shifted to its centre (`M_a(c') = sum_(b <= a)
/// C(a, b) (c - c')^(a - b) M_b(c)`, exact: a polynomial's expansion), children before
/// parents.
fn upward(nodes: &[Node], facets: &[Facet]) -> Vec<[f64; 3]> {
    let table = table();
    let mut out = vec![[0.0; 3]; nodes.len() * MONOMIALS];
    out.par_chunks_mut(MONOMIALS)
        .zip(nodes)
        .filter(|(_, n)| n.children.is_none())
        .for_each(|(m, n)| {
            m.copy_from_slice(&moments(
                n.centre,
                &facets[n.start as usize..n.end as usize],
            ));
        });
    // Pre-order: every child comes after its parent.
    for k in (0..nodes.len()).rev() {
        let Some(children) = nodes[k].children else {
            continue;
        };
        let mut m = [[0.0; 3]; MONOMIALS];
        for child in children {
            let child = child as usize;
            let pow = powers(sub(nodes[child].centre, nodes[k].centre));
            let from = &out[child * MONOMIALS..(child + 1) * MONOMIALS];
            for (a, m) in m.iter_mut().enumerate() {
                let p = table.powers[a];
                for &(b, c) in &table.below[a] {
                    let q = table.powers[b];
                    let shift = c * pow[0][p[0] - q[0]] * pow[1][p[1] - q[1]] * pow[2][p[2] - q[2]];
                    *m = add(*m, scale(from[b], shift));
                }
            }
        }
        out[k * MONOMIALS..(k + 1) * MONOMIALS].copy_from_slice(&m);
    }
    out
}

/// The powers `p_m^k`, `k = 0..=ORDER`, of each coordinate of `p`.
fn powers(p: [f64; 3]) -> [[f64; ORDER + 1]; 3] {
    let mut pow = [[1.0; ORDER + 1]; 3];
    for axis in 0..3 {
        for k in 1..=ORDER {
            pow[axis][k] = pow[axis][k - 1] * p[axis];
        }
    }
    pow
}

/// The moments `M_a = sum_f n_f int_f s^a dS` of `facets` about `centre`, each integral by
/// Radon's seven-point rule, exact for polynomials of the fifth degree (so for every
/// monomial here): the centroid (weight 9/40) and the points `(u, u, 1 - 2u)` in
/// barycentric coordinates, each of their three turns, for `u = (6 -+ sqrt 15) / 21`
/// (weights `(155 -+ sqrt 15) / 1200`), times the area.
fn moments(centre: [f64; 3], facets: &[Facet]) -> [[f64; 3]; MONOMIALS] {
    let table = table();
    let root = 15f64.sqrt();
    let rule = [
        ((6.0 - root) / 21.0, (155.0 - root) / 1200.0),
        ((6.0 + root) / 21.0, (155.0 + root) / 1200.0),
    ];
    let mut m = [[0.0; 3]; MONOMIALS];
    for f in facets {
        let [a, b, c] = f.corners.map(|v| sub(v, centre));
        let at = |[u, v, w]: [f64; 3]| add(add(scale(a, u), scale(b, v)), scale(c, w));
        let turns = |(u, w): (f64, f64)| {
            let far = 1.0 - 2.0 * u;
            [[u, u, far], [u, far, u], [far, u, u]].map(|turn| (at(turn), w))
        };
        let [one, two] = rule.map(turns);
        let centroid = [(at([1.0 / 3.0; 3]), 9.0 / 40.0)];
        let mut integral = [0.0; MONOMIALS];
        for (p, w) in centroid.into_iter().chain(one).chain(two) {
            let pow = powers(p);
            for (i, e) in integral.iter_mut().zip(&table.powers) {
                *i += w * pow[0][e[0]] * pow[1][e[1]] * pow[2][e[2]];
            }
        }
        let area = 0.5 * f.twice_area_m2;
        for (m, i) in m.iter_mut().zip(integral) {
            *m = add(*m, scale(f.normal, area * i));
        }
    }
    m
}

/// The Taylor coefficients `c_a = d^a f(0) / a!` of `f(s) = 1 / |d - s|` about `s = 0`
/// for `LANES` vectors `d` side by side, in the order of [`Monomials`] (the place past them
/// held at 0), by the recurrence `|a| D^2 c_a = (2 |a| - 1) sum_m d_m c_(a - e_m) - (|a| -
/// 1) sum_m c_(a - 2 e_m)` from `c_0 = 1 / D` (Duan and Krasny 2001, J. Comput. Chem. 22,
/// 184-195): `c_(e_x) = x / D^3`, `c_(2 e_x) = (3 x^2 - D^2) / (2 D^5)`.
fn coefficients(d: [[f64; 3]; LANES]) -> [[f64; LANES]; MONOMIALS + 1] {
    let table = table();
    let inv_d2: [f64; LANES] = std::array::from_fn(|l| 1.0 / dot(d[l], d[l]));
    // One more place, held at 0, for the powers that would fall below zero.
    let mut c = [[0.0; LANES]; MONOMIALS + 1];
    c[0] = inv_d2.map(f64::sqrt);
    for a in 1..MONOMIALS {
        let [i, j, k] = table.less_one[a];
        let [p, q, r] = table.less_two[a];
        let [first, second] = table.factors[a];
        for l in 0..LANES {
            let down_one = d[l][0] * c[i][l] + d[l][1] * c[j][l] + d[l][2] * c[k][l];
            let down_two = c[p][l] + c[q][l] + c[r][l];
            c[a][l] = (first * down_one - second * down_two) * inv_d2[l];
        }
    }
    c
}

/// `phi_f(r) = int_f dS' / |r - r'|` in closed form (module documentation); the solid
/// angle's term left out at the facet's own centroid (`own`).
fn single_layer(f: &Facet, r: [f64; 3], own: bool) -> f64 {
    let [a, b, c] = f.corners.map(|v| sub(v, r));
    let (la, lb, lc) = (norm(a), norm(b), norm(c));
    let ends = [(a, la, lb), (b, lb, lc), (c, lc, la)];
    let mut sum = 0.0;
    for (((p, lp, lq), e), n) in ends.into_iter().zip(f.edge_lengths_m).zip(f.edge_normals) {
        // ln((lp + lq + e) / (lp + lq - e)), exact far away (as in gravity.rs).
        let l_e = (2.0 * e / (lp + lq - e)).ln_1p();
        sum += dot(n, p) * l_e;
    }
    if !own {
        let height = dot(f.normal, a);
        let triple = f.twice_area_m2 * height;
        let below = la * lb * lc + la * dot(b, c) + lb * dot(c, a) + lc * dot(a, b);
        sum -= height * 2.0 * triple.atan2(below);
    }
    sum
}
