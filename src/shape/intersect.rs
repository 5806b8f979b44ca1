//! Whether a mesh's facets intersect each other: a surface that passes through itself
//! (two overlapping bodies in one file, a fold) encloses no body, and its signed volume
//! counts the overlap twice.
//!
//! The facets' bounding boxes go into a bounding-volume hierarchy (median splits, built in
//! `O(F log F)`); each facet's box is looked up in it, and only the pairs whose boxes
//! overlap are tested, exactly: every orientation is the sign of a determinant computed
//! with Shewchuk's adaptive exact predicates (crate `robust`), so two facets that only
//! touch are found to touch, and two that miss each other by a rounding error are found
//! apart. Facets that share an edge or a vertex are neighbours: they meet there, and
//! intersect only where they meet elsewhere too (a fold onto each other, a surface
//! pinched through a vertex).
//!
//! A shape model's facets are small and each box meets a few others (about 20 on an
//! icosphere, neighbours included), so the pairs are `O(F)`; a mesh whose boxes overlap in
//! more than [`PAIRS_PER_FACET`] pairs a facet (long thin facets fanned about one point) is
//! refused rather than checked in quadratic time.

use super::vec3::{cross, sub};
use rayon::prelude::*;
use robust::{Coord, Coord3D, orient2d, orient3d};
use std::sync::atomic::{AtomicU64, Ordering};

/// The most pairs of overlapping boxes a mesh may have, per facet (with
/// [`PAIRS_AT_LEAST`] allowed to any mesh), before the check refuses it as too costly.
pub const PAIRS_PER_FACET: u64 = 64;

/// Pairs of overlapping boxes any mesh may have, however few its facets.
pub const PAIRS_AT_LEAST: u64 = 10_000_000;

/// Facets in a leaf of the hierarchy.
const LEAF: usize = 4;

/// Why a mesh fails the check.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Intersection {
    /// Facets `0` and `1` (0-based, the first before the second) intersect.
    Facets(usize, usize),
    /// The facets' boxes overlap in more than the allowed pairs (the count reached, the
    /// allowance).
    TooManyPairs(u64, u64),
}

/// An axis-aligned box.
#[derive(Debug, Clone, Copy)]
struct Bounds {
    lo: [f64; 3],
    hi: [f64; 3],
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        lo: [f64::INFINITY; 3],
        hi: [f64::NEG_INFINITY; 3],
    };

    fn of(points: &[[f64; 3]]) -> Bounds {
        points.iter().fold(Bounds::EMPTY, |b, p| b.with(*p))
    }

    fn with(self, p: [f64; 3]) -> Bounds {
        Bounds {
            lo: std::array::from_fn(|k| self.lo[k].min(p[k])),
            hi: std::array::from_fn(|k| self.hi[k].max(p[k])),
        }
    }

    fn join(self, o: Bounds) -> Bounds {
        self.with(o.lo).with(o.hi)
    }

    /// Closed: boxes that touch overlap.
    fn overlaps(&self, o: &Bounds) -> bool {
        (0..3).all(|k| self.lo[k] <= o.hi[k] && o.lo[k] <= self.hi[k])
    }
}

/// A node of the hierarchy: its box, and either two children (`first` the left child's
/// index, the right one next to it) or `count` facets from `first` in the order array.
struct Node {
    bounds: Bounds,
    first: usize,
    count: usize,
}

/// The hierarchy: nodes (the root first) and the facets in leaf order.
struct Tree {
    nodes: Vec<Node>,
    order: Vec<u32>,
}

impl Tree {
    /// Built by splitting at the median centre along the widest axis of the centres.
    fn new(boxes: &[Bounds]) -> Tree {
        let centre = |f: u32, k: usize| {
            let b = &boxes[f as usize];
            0.5 * (b.lo[k] + b.hi[k])
        };
        let mut tree = Tree {
            nodes: Vec::with_capacity(2 * boxes.len() / LEAF + 1),
            order: (0..boxes.len() as u32).collect(),
        };
        tree.nodes.push(Node {
            bounds: Bounds::EMPTY,
            first: 0,
            count: boxes.len(),
        });
        // (node, start, end): explicit, so that no input deepens the call stack.
        let mut todo = vec![(0usize, 0usize, boxes.len())];
        while let Some((node, start, end)) = todo.pop() {
            let facets = &mut tree.order[start..end];
            let bounds = facets
                .iter()
                .fold(Bounds::EMPTY, |b, &f| b.join(boxes[f as usize]));
            tree.nodes[node].bounds = bounds;
            if facets.len() <= LEAF {
                continue;
            }
            let spread = facets.iter().fold(Bounds::EMPTY, |b, &f| {
                b.with(std::array::from_fn(|k| centre(f, k)))
            });
            let axis = (0..3)
                .max_by(|&a, &b| {
                    (spread.hi[a] - spread.lo[a]).total_cmp(&(spread.hi[b] - spread.lo[b]))
                })
                .unwrap_or(0);
            let mid = facets.len() / 2;
            facets
                .select_nth_unstable_by(mid, |&a, &b| centre(a, axis).total_cmp(&centre(b, axis)));
            let left = tree.nodes.len();
            for _ in 0..2 {
                tree.nodes.push(Node {
                    bounds: Bounds::EMPTY,
                    first: 0,
                    count: 0,
                });
            }
            tree.nodes[node].first = left;
            tree.nodes[node].count = 0;
            todo.push((left, start, start + mid));
            todo.push((left + 1, start + mid, end));
            tree.nodes[left].first = start;
            tree.nodes[left].count = mid;
            tree.nodes[left + 1].first = start + mid;
            tree.nodes[left + 1].count = end - start - mid;
        }
        tree
    }

    /// Calls `visit` with every facet after `facet` whose box overlaps `query`, until it
    /// returns `false`.
    fn each_overlap(&self, facet: u32, query: &Bounds, mut visit: impl FnMut(u32) -> bool) {
        let mut stack = vec![0usize];
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            if !node.bounds.overlaps(query) {
                continue;
            }
            // Leaves hold facets; a parent holds none (every split leaves two on each side).
            if node.count > 0 {
                for &f in &self.order[node.first..node.first + node.count] {
                    if f > facet && !visit(f) {
                        return;
                    }
                }
            } else {
                stack.push(node.first);
                stack.push(node.first + 1);
            }
        }
    }
}

/// The first pair of facets (in file order: the lowest first facet, then the lowest
/// second) that intersect other than where they are neighbours; or too many overlapping
/// boxes to check. `facets` must name vertices of `vertices` and be non-degenerate (as
/// [`super::Mesh::check`] has checked before it asks).
pub fn first_intersection(vertices: &[[f64; 3]], facets: &[[u32; 3]]) -> Result<(), Intersection> {
    let corners = |f: u32| facets[f as usize].map(|v| vertices[v as usize]);
    let boxes: Vec<Bounds> = (0..facets.len() as u32)
        .map(|f| Bounds::of(&corners(f)))
        .collect();
    let tree = Tree::new(&boxes);
    // First the pairs counted, and no more than allowed: a fan of thin facets stops here
    // after the allowance, not after F^2 pairs.
    let allowed = PAIRS_AT_LEAST.max(PAIRS_PER_FACET.saturating_mul(facets.len() as u64));
    let pairs = AtomicU64::new(0);
    (0..facets.len() as u32).into_par_iter().for_each(|f| {
        let mut mine = 0u64;
        tree.each_overlap(f, &boxes[f as usize], |_| {
            mine += 1;
            // Checked now and then, so that one facet's many pairs stop too.
            !mine.is_multiple_of(4096) || pairs.load(Ordering::Relaxed) + mine <= allowed
        });
        pairs.fetch_add(mine, Ordering::Relaxed);
    });
    let counted = pairs.into_inner();
    if counted > allowed {
        return Err(Intersection::TooManyPairs(counted, allowed));
    }
    let found = (0..facets.len() as u32)
        .into_par_iter()
        .find_map_first(|f| {
            let mut hit = None;
            tree.each_overlap(f, &boxes[f as usize], |g| {
                if g < hit.unwrap_or(u32::MAX)
                    && meet(facets[f as usize], facets[g as usize], vertices)
                {
                    hit = Some(g);
                }
                true
            });
            hit.map(|g| (f as usize, g as usize))
        });
    match found {
        Some((f, g)) => Err(Intersection::Facets(f, g)),
        None => Ok(()),
    }
}

/// Whether facets `a` and `b` (vertex indices) meet anywhere but at the vertices or the
/// edge they share.
fn meet(a: [u32; 3], b: [u32; 3], vertices: &[[f64; 3]]) -> bool {
    let at = |v: u32| vertices[v as usize];
    // The corners of `a` that `b` shares (no allocation: this runs for every pair).
    let (mut shared, mut n) = ([0usize; 3], 0);
    for (i, v) in a.iter().enumerate() {
        if b.contains(v) {
            shared[n] = i;
            n += 1;
        }
    }
    match &shared[..n] {
        [] => triangles_meet(a.map(at), b.map(at)),
        // Rotated so that the shared vertex comes first in both: they meet elsewhere exactly
        // when the edge of one opposite it meets the other (MODEL.md 13.1).
        [i] => {
            let v = a[*i];
            let j = b.iter().position(|&x| x == v).unwrap_or(0);
            let ta = [a[*i], a[(*i + 1) % 3], a[(*i + 2) % 3]].map(at);
            let tb = [b[j], b[(j + 1) % 3], b[(j + 2) % 3]].map(at);
            segment_meets_triangle(ta[1], ta[2], tb) || segment_meets_triangle(tb[1], tb[2], ta)
        }
        // Sharing an edge, they meet elsewhere only folded flat onto each other: coplanar,
        // their third vertices on the same side of the edge.
        [i, k] => {
            let (v, w) = (at(a[*i]), at(a[*k]));
            let p = at(a[3 - i - k]);
            let q = at(*b.iter().find(|x| !a.contains(x)).unwrap_or(&b[0]));
            if orient(v, w, p, q) != 0 {
                return false;
            }
            let drop = dominant_axis([v, w, p]);
            let side = |x: [f64; 3]| orient_2d(drop, v, w, x);
            side(p) * side(q) > 0
        }
        // The same three vertices: the edges' check refuses such a mesh before.
        _ => true,
    }
}

/// Whether two closed triangles meet: exactly when an edge of one meets the other.
fn triangles_meet(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> bool {
    (0..3).any(|k| segment_meets_triangle(a[k], a[(k + 1) % 3], b))
        || (0..3).any(|k| segment_meets_triangle(b[k], b[(k + 1) % 3], a))
}

/// The sign of the orientation of `d` against the plane through `a`, `b`, `c`: exact.
fn orient(a: [f64; 3], b: [f64; 3], c: [f64; 3], d: [f64; 3]) -> i32 {
    let c3 = |p: [f64; 3]| Coord3D {
        x: p[0],
        y: p[1],
        z: p[2],
    };
    sign(orient3d(c3(a), c3(b), c3(c), c3(d)))
}

/// The sign of the orientation of `c` against the line `a b`, all three projected along
/// axis `drop`: exact.
fn orient_2d(drop: usize, a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> i32 {
    let (u, v) = ((drop + 1) % 3, (drop + 2) % 3);
    let c2 = |p: [f64; 3]| Coord { x: p[u], y: p[v] };
    sign(orient2d(c2(a), c2(b), c2(c)))
}

fn sign(x: f64) -> i32 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

/// The axis along which the triangle's normal is largest: projected along it, the
/// triangle keeps its area (and coplanar points their orientations, all flipped alike).
fn dominant_axis(t: [[f64; 3]; 3]) -> usize {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    (0..3)
        .max_by(|&a, &b| n[a].abs().total_cmp(&n[b].abs()))
        .unwrap_or(2)
}

/// Whether the closed segment `p q` meets the closed triangle `t`.
fn segment_meets_triangle(p: [f64; 3], q: [f64; 3], t: [[f64; 3]; 3]) -> bool {
    let (sp, sq) = (orient(t[0], t[1], t[2], p), orient(t[0], t[1], t[2], q));
    if sp * sq > 0 {
        return false;
    }
    if sp == 0 && sq == 0 {
        return coplanar_segment_meets_triangle(p, q, t);
    }
    // The segment reaches the plane; the line through it passes through the closed
    // triangle exactly when it passes no edge on the outer side.
    let s = [
        orient(p, q, t[0], t[1]),
        orient(p, q, t[1], t[2]),
        orient(p, q, t[2], t[0]),
    ];
    !(s.contains(&1) && s.contains(&-1))
}

/// [`segment_meets_triangle`] for a segment in the triangle's plane.
fn coplanar_segment_meets_triangle(p: [f64; 3], q: [f64; 3], t: [[f64; 3]; 3]) -> bool {
    let drop = dominant_axis(t);
    let o = |a: [f64; 3], b: [f64; 3], c: [f64; 3]| orient_2d(drop, a, b, c);
    let inside = |x: [f64; 3]| {
        let s = [o(t[0], t[1], x), o(t[1], t[2], x), o(t[2], t[0], x)];
        !(s.contains(&1) && s.contains(&-1))
    };
    if inside(p) || inside(q) {
        return true;
    }
    (0..3).any(|k| {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        let (d1, d2) = (o(a, b, p), o(a, b, q));
        let (d3, d4) = (o(p, q, a), o(p, q, b));
        // Both ends of each on opposite sides (or on) the other's line; collinear
        // segments need a shared stretch, which an end inside the triangle has shown
        // already or an end of the edge on the segment shows.
        if d1 == 0 && d2 == 0 {
            let (u, v) = ((drop + 1) % 3, (drop + 2) % 3);
            let within = |x: [f64; 3], s: [f64; 3], e: [f64; 3]| {
                (0..2).all(|i| {
                    let k = [u, v][i];
                    s[k].min(e[k]) <= x[k] && x[k] <= s[k].max(e[k])
                })
            };
            return within(a, p, q) || within(b, p, q);
        }
        d1 * d2 <= 0 && d3 * d4 <= 0
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: [[f64; 3]; 3] = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

    #[test]
    fn segments_meet_triangles_where_they_touch_and_not_a_rounding_error_away() {
        // Through the middle, through a vertex, along an edge, ending on the face.
        assert!(segment_meets_triangle([0.2, 0.2, -1.0], [0.2, 0.2, 1.0], T));
        assert!(segment_meets_triangle([1.0, 0.0, -1.0], [1.0, 0.0, 1.0], T));
        assert!(segment_meets_triangle([0.5, 0.5, -1.0], [0.5, 0.5, 1.0], T));
        assert!(segment_meets_triangle([0.1, 0.1, 0.0], [0.1, 0.1, 1.0], T));
        // Past the hypotenuse by the least step a float takes there.
        let past = 0.5f64.next_up();
        assert!(!segment_meets_triangle(
            [past, 0.5, -1.0],
            [past, 0.5, 1.0],
            T
        ));
        // Above the plane, beside it.
        assert!(!segment_meets_triangle(
            [0.2, 0.2, 1e-200],
            [0.2, 0.2, 1.0],
            T
        ));
        assert!(!segment_meets_triangle(
            [2.0, 2.0, -1.0],
            [2.0, 2.0, 1.0],
            T
        ));
        // In the plane: crossing an edge, wholly inside, along an edge's line beyond it.
        assert!(segment_meets_triangle([0.5, -1.0, 0.0], [0.5, 1.0, 0.0], T));
        assert!(segment_meets_triangle([0.1, 0.1, 0.0], [0.2, 0.1, 0.0], T));
        assert!(!segment_meets_triangle([1.5, 0.0, 0.0], [2.0, 0.0, 0.0], T));
        assert!(segment_meets_triangle([1.0, 0.0, 0.0], [2.0, 0.0, 0.0], T));
    }

    #[test]
    fn neighbours_meet_only_beyond_what_they_share() {
        let v = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.3, 0.3, 1.0],
            [0.3, 0.3, -1.0],
            [0.5, 0.1, 0.0],
        ];
        // An edge shared, the other facet below it or flat beside it: neighbours.
        assert!(!meet([0, 1, 2], [1, 0, 3], &v));
        assert!(!meet([0, 1, 2], [0, 1, 4], &v));
        // Folded flat back onto it: they overlap.
        assert!(meet([0, 1, 2], [1, 0, 6], &v));
        // A vertex shared, the other facet rising away from it; through it.
        assert!(!meet([0, 1, 2], [0, 3, 4], &v));
        assert!(meet([0, 1, 2], [0, 4, 5], &v));
    }
}
