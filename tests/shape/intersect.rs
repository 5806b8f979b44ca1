//! Meshes whose facets intersect each other (issue 45): two overlapping bodies in one file
//! are refused naming two facets, where before they passed with twice one body's volume;
//! bodies a rounding error apart pass, bodies that touch do not; a large mesh is checked
//! in O(F log F), and a fan of thin facets is refused after a bounded count, never in
//! quadratic time.

use super::{cube, icosphere, twisted_box, uv_sphere};
use std::time::Instant;
use touchdown::shape::{Mesh, PAIRS_AT_LEAST};

/// Two meshes as one, the second's vertices numbered after the first's.
fn both(a: &Mesh, b: &Mesh) -> Mesh {
    let n = a.vertices.len() as u32;
    Mesh {
        vertices: a.vertices.iter().chain(&b.vertices).copied().collect(),
        facets: a
            .facets
            .iter()
            .copied()
            .chain(b.facets.iter().map(|f| f.map(|v| v + n)))
            .collect(),
    }
}

/// An ellipsoid of semi-axes `axes` (m) centred at `centre`, an icosphere of 1,280 facets
/// stretched.
fn ellipsoid(axes: [f64; 3], centre: [f64; 3]) -> Mesh {
    let mut m = icosphere(1.0, 3);
    for v in &mut m.vertices {
        *v = [0, 1, 2].map(|k| centre[k] + axes[k] * v[k]);
    }
    m
}

#[test]
fn two_overlapping_bodies_are_refused_naming_two_facets() {
    let a = ellipsoid([300.0, 200.0, 150.0], [-150.0, 0.0, 0.0]);
    let b = ellipsoid([300.0, 200.0, 150.0], [150.0, 0.0, 0.0]);
    let one = a.clone().check().expect("one ellipsoid").volume_m3();
    let e = both(&a, &b)
        .check()
        .expect_err("overlapping ellipsoids")
        .to_string();
    assert!(
        e.starts_with("shape model refused: it intersects itself: facets ")
            && e.contains(" cross each other"),
        "{e}"
    );
    // The two named are one of each body: the first numbered up to 1,280, the second after.
    let named: Vec<usize> = e
        .split("facets ")
        .nth(1)
        .map(|r| {
            r.split(|c: char| !c.is_ascii_digit())
                .filter(|w| !w.is_empty())
                .map(|w| w.parse().unwrap())
                .collect()
        })
        .unwrap();
    let second = named[4];
    assert!(named[0] <= 1280 && second > 1280, "{e}: {named:?}");
    // Apart (by 1 km), the two pass with twice one body's volume: that is what the
    // overlapping pair claimed too.
    let far = ellipsoid([300.0, 200.0, 150.0], [1000.0, 0.0, 0.0]);
    let two = both(&a, &far)
        .check()
        .expect("two bodies apart")
        .volume_m3();
    assert!((two / one - 2.0).abs() < 1e-12, "{two} against {one}");
}

#[test]
fn bodies_a_rounding_error_apart_pass_and_bodies_that_touch_do_not() {
    // The cube [-1, 1]^3 and another from x = 1 (touching along a whole face), or from the
    // next float past 1: the exact predicates tell the two apart.
    let a = cube(1.0);
    let touching = twisted_box(1.0, 1.0, 1.0, 0.0, 1.0, [2.0, 0.0, 0.0]);
    assert!(both(&a, &touching).check().is_err());
    let mut apart = touching.clone();
    for v in &mut apart.vertices {
        if v[0] == 1.0 {
            v[0] = 1.0f64.next_up();
        }
    }
    assert!(both(&a, &apart).check().is_ok());
    // A vertex of a tetrahedron on a face of the cube: touching at one point.
    let tip = Mesh {
        vertices: vec![
            [1.0, 0.0, 0.0],
            [2.0, -0.5, -0.5],
            [2.0, 0.5, -0.5],
            [2.0, 0.0, 0.5],
        ],
        facets: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    };
    assert!(tip.clone().check().is_ok());
    assert!(both(&a, &tip).check().is_err());
}

#[test]
fn a_large_mesh_is_checked_quickly_and_a_fan_of_thin_facets_is_refused_after_a_count() {
    // 327,680 facets: each facet's box meets about 20 others, neighbours included.
    let started = Instant::now();
    let big = icosphere(1000.0, 7);
    let built = started.elapsed();
    big.check().expect("a sound icosphere");
    let checked = started.elapsed() - built;
    println!("327,680 facets checked in {checked:?}");
    // Every one of 5,000 facets around each pole holds the pole in its box, and every
    // northern box meets every southern one at the equator: 5e7 pairs, past the allowance
    // of 1e7, counted only that far.
    let started = Instant::now();
    let e = uv_sphere(1.0, 2, 5000)
        .check()
        .expect_err("a fan")
        .to_string();
    assert!(
        e.contains(&format!("overlap in more than {PAIRS_AT_LEAST} pairs")),
        "{e}"
    );
    println!("the fan refused in {:?}", started.elapsed());
}
