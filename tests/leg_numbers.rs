//! Leg `k` of every output is the user's leg `k` (MODEL.md section 3): the `k`-th of
//! `lander.leg_tips_m` as given, or with the layout keys the `k`-th counter-clockwise from
//! `first_leg_azimuth_deg`; and the support polygon of the outcome rules is the footpads'
//! convex hull, whatever their numbers.

use crate::common::{SET_DOWN, TempDir, arrow_column, arrow_u32s, set_down_lines, touchdown};
use arrow_array::{Array, ArrayRef, RecordBatch, UInt32Array};
use std::path::Path;

/// Runs `touchdown sweep` of `scenario` in `dir` into `out`, and panics, showing the run,
/// unless it exits 0.
fn sweep(dir: &TempDir, scenario: &str, samples: &str, out: &str) {
    let args = [
        "sweep",
        "--scenario",
        scenario,
        "--samples",
        samples,
        "--out",
        out,
    ];
    let run = touchdown(dir.path(), &args);
    assert_eq!(run.code, Some(0), "{run}");
}

/// Every column of the Arrow file at `path`, its batches put together, by name.
fn columns(path: &Path) -> Vec<(String, ArrayRef)> {
    let file = std::fs::File::open(path).expect("open the file");
    let reader = arrow_ipc::reader::FileReader::try_new(file, None).expect("an Arrow file");
    let schema = reader.schema();
    let batches: Vec<RecordBatch> = reader.map(|b| b.expect("a batch")).collect();
    let all = arrow_select::concat::concat_batches(&schema, &batches).expect("one batch");
    schema
        .fields()
        .iter()
        .zip(all.columns())
        .map(|(f, c)| (f.name().clone(), c.clone()))
        .collect()
}

/// `leg_tips_m = [...]` of `tips`.
fn tips_key(tips: &[[f64; 3]]) -> String {
    let each: Vec<String> = tips
        .iter()
        .map(|t| format!("[{:?}, {:?}, {:?}]", t[0], t[1], t[2]))
        .collect();
    format!("leg_tips_m = [{}]", each.join(", "))
}

/// The footpads of a regular gear as `Geometry::Regular` places them (MODEL.md section 3).
fn regular(legs: usize, radius_m: f64, height_m: f64, first_deg: f64) -> Vec<[f64; 3]> {
    (0..legs)
        .map(|i| {
            let az = first_deg.to_radians() + std::f64::consts::TAU * i as f64 / legs as f64;
            [radius_m * az.cos(), radius_m * az.sin(), -height_m]
        })
        .collect()
}

/// A lander set down level on flat ground with yaw 0: at t = 0 the footpads in I are the
/// CG's position plus their coordinates in B, so each trace column `leg{k}_tip_{x,y}_m`
/// less the CG's `x_m`, `y_m` is the user's leg `k` in B (to rounding: the attitude is the
/// identity quaternion, so the products are exact but for the sums, 1e-12 m).
#[test]
fn a_trace_puts_the_users_legs_in_their_columns() {
    let cases: Vec<(&str, String, Vec<[f64; 3]>)> = vec![
        (
            "the issue's five legs, one inside the others",
            tips_key(&[
                [0.6, 0.0, -0.43],
                [0.0, 0.6, -0.43],
                [-0.6, 0.0, -0.43],
                [0.0, -0.6, -0.43],
                [0.3, 0.3, -0.43],
            ]),
            vec![
                [0.6, 0.0, -0.43],
                [0.0, 0.6, -0.43],
                [-0.6, 0.0, -0.43],
                [0.0, -0.6, -0.43],
                [0.3, 0.3, -0.43],
            ],
        ),
        (
            "four legs listed clockwise from the third quadrant",
            tips_key(&[
                [-0.5, -0.4, -0.43],
                [-0.45, 0.42, -0.43],
                [0.41, 0.44, -0.43],
                [0.43, -0.4, -0.43],
            ]),
            vec![
                [-0.5, -0.4, -0.43],
                [-0.45, 0.42, -0.43],
                [0.41, 0.44, -0.43],
                [0.43, -0.4, -0.43],
            ],
        ),
        (
            "the layout keys of the default lander (first leg at 45 deg)",
            String::new(),
            regular(4, 0.6, 0.428936, 45.0),
        ),
        (
            "three legs, the first at 100 deg",
            "legs = 3\nfootpad_radius_m = 0.7\ncg_height_m = 0.5\nfirst_leg_azimuth_deg = 100.0"
                .into(),
            regular(3, 0.7, 0.5, 100.0),
        ),
        (
            "six legs, the first at -170 deg",
            "legs = 6\nfirst_leg_azimuth_deg = -170.0".into(),
            regular(6, 0.6, 0.428936, -170.0),
        ),
    ];
    for (case, lander, tips) in cases {
        let dir = TempDir::new("leg-numbers-trace");
        let scenario = format!(
            "[lander]\n{lander}\n\n[inputs]\nslope_deg = 0.0\nyaw_deg = 0.0\n{SET_DOWN}\n[simulation]\nt_max_s = 3.0\n"
        );
        dir.write("s.toml", &scenario);
        touchdown(
            dir.path(),
            &["trace", "--scenario", "s.toml", "--out", "t.arrow"],
        )
        .assert_ok();
        let t = dir.join("t.arrow");
        let at0 =
            |name: &str| arrow_column(&t, name).unwrap_or_else(|| panic!("{case}: {name}"))[0];
        let (x, y) = (at0("x_m"), at0("y_m"));
        for (k, tip) in tips.iter().enumerate() {
            let got = [
                at0(&format!("leg{k}_tip_x_m")) - x,
                at0(&format!("leg{k}_tip_y_m")) - y,
            ];
            assert!(
                (got[0] - tip[0]).abs() < 1e-12 && (got[1] - tip[1]).abs() < 1e-12,
                "{case}: leg {k} of the trace is at {got:?} in B, the user's leg {k} at {tip:?}"
            );
        }
        assert!(
            arrow_column(&t, &format!("leg{}_tip_x_m", tips.len())).is_none(),
            "{case}: more leg columns than legs"
        );
    }
}

/// A damper that can crush on the user's leg 1 alone: its strut is vertical, the others'
/// lie 5.7 deg below the horizontal (the steepest the scenario refuses is 2.9 deg), so a
/// level fall on flat ground (vertical normal forces, and with `mu = 0.05` at most 0.05 of
/// them across) loads the other struts along their axes by at most 0.1 + 0.05 of a
/// footpad's force, below the crush force (155 N) for the forces of these falls (below
/// 1000 N). Only `leg1_stroke_m` strokes, in every sample.
#[test]
fn a_damper_on_leg_1_strokes_only_in_leg1_columns() {
    let dir = TempDir::new("leg-numbers-damper");
    let scenario = format!(
        "[surface]\nfriction_coefficient = 0.05\n\n[damper]\nenabled = true\n\
         strut_axis = [[0.7071, -0.7071, -0.1], [0.0, 0.0, -1.0], [-0.7071, 0.7071, -0.1], [0.7071, 0.7071, -0.1]]\n\n\
         [inputs]\nslope_deg = 0.0\nyaw_deg = 0.0\n{}\n[simulation]\nt_max_s = 10.0\n",
        set_down_lines!("{ dist = \"uniform\", min = 5.0, max = 10.0 }", "0.0")
    );
    dir.write("s.toml", &scenario);
    sweep(&dir, "s.toml", "16", "s.arrow");
    let s = dir.join("s.arrow");
    let stroke = |k: usize| arrow_column(&s, &format!("leg{k}_stroke_m")).expect("strokes");
    assert!(
        stroke(1).iter().all(|x| *x > 1e-3),
        "leg 1 crushes in every sample: {:?}",
        stroke(1)
    );
    for k in [0, 2, 3] {
        let peak = arrow_column(&s, &format!("leg{k}_peak_normal_force_n")).expect("peaks");
        assert!(
            peak.iter().all(|f| *f < 1000.0),
            "the forces this test's bound takes: {peak:?}"
        );
        assert!(
            stroke(k).iter().all(|x| *x == 0.0),
            "leg {k} has no damper that can crush: {:?}",
            stroke(k)
        );
    }
}

/// A lander rolled and pitched so that the user's leg 2 (at 225 deg) hangs lowest touches
/// down on it: `touchdown_first_leg` is 2, in the sweep and in the trace's summary.
#[test]
fn the_first_leg_to_touch_is_named_by_the_users_number() {
    let dir = TempDir::new("leg-numbers-first");
    // R = Ry(pitch) Rx(roll): roll > 0 lowers y < 0, pitch < 0 lowers x < 0.
    let scenario = format!(
        "[inputs]\nslope_deg = 0.0\nyaw_deg = 0.0\n{}pitch_deg = -4.0\n[simulation]\nt_max_s = 5.0\n",
        set_down_lines!("1.0", "3.0").replace("pitch_deg = 3.0\n", "")
    );
    dir.write("s.toml", &scenario);
    sweep(&dir, "s.toml", "2", "s.arrow");
    let first = arrow_u32s(&dir.join("s.arrow"), "touchdown_first_leg").expect("first legs");
    assert_eq!(first, vec![2, 2], "the leg at 225 deg touches first");
    let run = touchdown(
        dir.path(),
        &["trace", "--scenario", "s.toml", "--out", "t.arrow"],
    );
    run.assert_ok();
    let t = dir.join("t.arrow");
    let first_contact = arrow_column(&t, "leg2_penetration_m")
        .expect("penetrations")
        .iter()
        .position(|d| *d > 0.0)
        .expect("leg 2 touches");
    for k in [0, 1, 3] {
        let d = arrow_column(&t, &format!("leg{k}_penetration_m")).expect("penetrations");
        assert!(
            d[..=first_contact].iter().all(|d| *d <= 0.0),
            "leg {k} touches no later than leg 2"
        );
    }
}

/// Listing the legs in another order changes only their numbers: a sweep whose
/// `leg_tips_m` (and per-leg strut axes) are a permutation of another's has every column
/// that is not a leg's equal bit for bit, leg `j`'s columns equal to those of the leg it
/// is in the other listing, and the first leg to touch renamed the same way (no two legs
/// tie for it: the attitude errors are drawn).
#[test]
fn listing_the_legs_in_another_order_changes_only_their_numbers() {
    let tips = [
        [0.424265, 0.424265, -0.428936],
        [-0.424265, 0.424265, -0.428936],
        [-0.424265, -0.424265, -0.428936],
        [0.424265, -0.424265, -0.428936],
    ];
    let axes = [
        [0.1, 0.1, -1.0],
        [-0.1, 0.1, -1.0],
        [-0.1, -0.1, -1.0],
        [0.1, -0.1, -1.0],
    ];
    // Leg j of the second listing is leg PERM[j] of the first.
    const PERM: [usize; 4] = [2, 0, 3, 1];
    let dir = TempDir::new("leg-numbers-permuted");
    let write = |name: &str, order: [usize; 4]| {
        let t: Vec<[f64; 3]> = order.iter().map(|&k| tips[k]).collect();
        let a: Vec<String> = order
            .iter()
            .map(|&k| format!("[{:?}, {:?}, {:?}]", axes[k][0], axes[k][1], axes[k][2]))
            .collect();
        dir.write(
            name,
            &format!(
                "[lander]\n{}\n\n[damper]\nenabled = true\nstrut_axis = [{}]\n\n[inputs]\n\
                 slope_deg = {{ dist = \"uniform\", min = 0.0, max = 30.0 }}\n\
                 release_height_m = {{ dist = \"uniform\", min = 0.0, max = 1.0 }}\n\n\
                 [simulation]\nt_max_s = 60.0\n",
                tips_key(&t),
                a.join(", ")
            ),
        );
    };
    write("a.toml", [0, 1, 2, 3]);
    write("b.toml", PERM);
    for name in ["a", "b"] {
        sweep(
            &dir,
            &format!("{name}.toml"),
            "300",
            &format!("{name}.arrow"),
        );
    }
    let (a, b) = (columns(&dir.join("a.arrow")), columns(&dir.join("b.arrow")));
    assert_eq!(a.len(), b.len());
    let of = |cols: &[(String, ArrayRef)], name: &str| {
        cols.iter()
            .find(|(n, _)| n == name)
            .unwrap_or_else(|| panic!("column {name}"))
            .1
            .clone()
    };
    let outcomes = of(&a, "outcome");
    let outcomes = crate::common::texts(outcomes.as_ref());
    assert!(
        outcomes.iter().any(|o| o == "stable") && outcomes.iter().any(|o| o == "tipped"),
        "a sweep with both outcomes"
    );
    let mut leg_columns = 0;
    for (name, column) in &b {
        if let Some((k, rest)) = name
            .strip_prefix("leg")
            .and_then(|r| r.split_once('_'))
            .and_then(|(k, rest)| Some((k.parse::<usize>().ok()?, rest)))
        {
            let other = of(&a, &format!("leg{}_{rest}", PERM[k]));
            assert!(
                column.as_ref() == other.as_ref(),
                "{name} is leg{}_{rest} of the first listing",
                PERM[k]
            );
            leg_columns += 1;
        } else if name == "touchdown_first_leg" {
            let (fa, fb) = (of(&a, name), column.clone());
            let fa = fa.as_any().downcast_ref::<UInt32Array>().expect("UInt32");
            let fb = fb.as_any().downcast_ref::<UInt32Array>().expect("UInt32");
            for i in 0..fa.len() {
                assert_eq!(fa.value(i) as usize, PERM[fb.value(i) as usize], "row {i}");
            }
        } else {
            assert!(
                column.as_ref() == of(&a, name).as_ref(),
                "{name} is the same in both listings"
            );
        }
    }
    assert!(leg_columns >= 4 * 8, "{leg_columns} leg columns compared");
}

/// A footpad inside the others' hull is on no edge of the support polygon. Five legs: four
/// at 0.6 m on the axes and one at (0.15, 0.15), stood (attitude to the surface) on a 30 deg
/// slope falling towards 45 deg, the inner leg's side, with `mu = 0.9 > tan 30 deg`. The
/// polygon is the square of the outer four, whose edge lies 0.424 m from the CG's foot
/// towards 45 deg: the static limit there is `atan(0.424 / 0.43)` = 44.6 deg, so the
/// lander stands, and the rest rule (the CG's foot over the polygon) decides `stable` long
/// before `t_max`. With the inner leg taken for a corner, the polygon had a notch 0.21 m
/// from the CG's foot (`atan(0.21 / 0.43)` = 26 deg): no rest there.
#[test]
fn a_leg_inside_the_support_polygon_is_on_no_edge() {
    let dir = TempDir::new("leg-numbers-hull");
    let tips = [
        [0.6, 0.0, -0.43],
        [0.15, 0.15, -0.43],
        [0.0, 0.6, -0.43],
        [-0.6, 0.0, -0.43],
        [0.0, -0.6, -0.43],
    ];
    let scenario = format!(
        "[lander]\n{}\n\n[surface]\nfriction_coefficient = 0.9\n\n[inputs]\nslope_deg = 30.0\n\
         downhill_azimuth_deg = 45.0\nyaw_deg = 0.0\n{SET_DOWN}\n[initial]\nattitude_reference = \"surface\"\n\
         clearance_m = 0.0\n\n[simulation]\nt_max_s = 60.0\n",
        tips_key(&tips)
    );
    dir.write("s.toml", &scenario);
    sweep(&dir, "s.toml", "1", "s.arrow");
    let cols = columns(&dir.join("s.arrow"));
    let outcome = cols
        .iter()
        .find(|(n, _)| n == "outcome")
        .expect("outcome")
        .1
        .clone();
    let outcome = crate::common::texts(outcome.as_ref())[0].clone();
    let decided = arrow_column(&dir.join("s.arrow"), "decided_s").expect("decided_s")[0];
    assert!(
        outcome == "stable" && decided < 30.0,
        "{outcome} at {decided} s: the lander stands within its support polygon"
    );
}
