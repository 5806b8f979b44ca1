//! Rocks and sunk footpads in the pictures of a trace (issue 32): the rocks a scene finds on
//! its ground patch are the sample's (present at its abundance, on the patch, every image
//! of the periodic tile, the one a footpad rests on among them); `animate` draws them and
//! the holes of sunk footpads; `view` puts the rocks and footprints into its page, which
//! opens in headless Chromium without an error and names a rock's radius and a sunk
//! footpad's sinkage under the pointer.

use crate::animate::{chromium, frames};
use crate::common::{SET_DOWN, TempDir, python, touchdown};
use glam::DVec3;
use std::path::Path;
use std::process::Command;
use touchdown::scene::Scene;

/// Rocks on a gentle slope, their abundance drawn (the tiles are built for 0.4 and thinned
/// to each sample's): the lander set down among them. Sample 3 comes to rest with a footpad
/// on a rock's top (found by running samples 0 to 5).
fn rocky(abundance: &str) -> String {
    format!(
        "[surface.rocks]\nabundance = {abundance}\n[inputs]\nslope_deg = 4.0\n\
         downhill_azimuth_deg = 30.0\n{SET_DOWN}[simulation]\nt_max_s = 8.0\n"
    )
}
const ROCKY_SAMPLE: &str = "3";

/// Soil weak enough for the footpads of the default descent to sink about 18 cm.
const SOFT: &str = "[surface]\nkind = \"regolith\"\ndamping_n_s_per_m = 5.0\n\
    [surface.regolith]\nbekker_k_phi = 3000.0\nbekker_k_c = 20.0\ncohesion_pa = 5.0\n\
    [inputs]\nslope_deg = 3.0\n[simulation]\nt_max_s = 6.0\n";

/// The elastic plane, the same lander and inputs as `SOFT`.
const HARD: &str = "[inputs]\nslope_deg = 3.0\n[simulation]\nt_max_s = 6.0\n";

/// Writes `name.toml` and the trace of its `sample` as `name.arrow` in `dir`.
fn trace(dir: &TempDir, name: &str, scenario: &str, sample: &str) {
    dir.write(&format!("{name}.toml"), scenario);
    let (toml, out) = (format!("{name}.toml"), format!("{name}.arrow"));
    let args = [
        "trace",
        "--scenario",
        &toml,
        "--sample",
        sample,
        "--out",
        &out,
    ];
    touchdown(dir.path(), &args).assert_ok();
}

#[test]
fn the_rocks_of_a_patch_are_the_sample_s_every_image_once() {
    let dir = TempDir::new("scene-rocks");
    let abundance = "{ dist = \"uniform\", min = 0.1, max = 0.4 }";
    trace(&dir, "rocky", &rocky(abundance), ROCKY_SAMPLE);
    let scene = Scene::read(&dir.join("rocky.arrow")).expect("read the trace");
    let tiles = scene.model.rocks.as_ref().expect("rocks");
    let k = scene.model.rock_abundance;
    assert!(k > 0.1 && k < 0.4, "abundance {k}");
    let s = &scene.surface;
    // A patch several tiles long (its margin 30 m; a tile is 20 m).
    let ground = scene.ground(30.0, 0.5, 60_000);
    let rocks = scene.rocks(&ground);
    let (u0, v0) = (
        ground.origin.dot(s.tangent_u),
        ground.origin.dot(s.tangent_v),
    );
    let (u1, v1) = (
        u0 + (ground.nu - 1) as f64 * ground.spacing_m,
        v0 + (ground.nv - 1) as f64 * ground.spacing_m,
    );
    let size = tiles.tile_size_m();
    let tile = tiles.rocks(s.rock_tile);
    let present: Vec<_> = tile.iter().filter(|r| r.threshold <= k).collect();
    assert!(present.len() < tile.len(), "the abundance thins the tile");
    // Each rock returned: on the patch, on the plane (no terrain here), and a rock of the
    // tile present at the sample's abundance where its tile coordinates say (1e-9 m: the
    // sums of a few metres' coordinates).
    for r in &rocks {
        let (u, v) = (s.tangent_u.dot(r.centre), s.tangent_v.dot(r.centre));
        assert!(u >= u0 - 1e-9 && u <= u1 + 1e-9 && v >= v0 - 1e-9 && v <= v1 + 1e-9);
        assert!(s.normal.dot(r.centre).abs() < 1e-9, "{r:?} off the plane");
        let wrap = |x: f64| x.rem_euclid(size);
        let (tu, tv) = (wrap(u + s.rock_offset_m[0]), wrap(v + s.rock_offset_m[1]));
        let close = |a: f64, b: f64| (a - b).abs() < 1e-9 || (a - b).abs() > size - 1e-9;
        assert!(
            present
                .iter()
                .any(|t| close(t.u_m, tu) && close(t.v_m, tv) && t.radius_m == r.radius_m),
            "{r:?} is no rock of the tile present at abundance {k}"
        );
    }
    // As many as the present rocks' images on the patch, counted by brute force.
    let mut count = 0;
    for t in &present {
        for m in -20..=20 {
            for n in -20..=20 {
                let u = t.u_m - s.rock_offset_m[0] + f64::from(m) * size;
                let v = t.v_m - s.rock_offset_m[1] + f64::from(n) * size;
                count += usize::from(u >= u0 && u <= u1 && v >= v0 && v <= v1);
            }
        }
    }
    assert_eq!(rocks.len(), count);
    assert!(
        count > present.len(),
        "a patch over several tiles repeats rocks"
    );
    // The footpad that rests on a rock at the end (in contact, 1 cm or more above the
    // plane: only a rock holds it there) touches one of them: the distance from its
    // sphere's centre to the rock's is the radii's sum less the penetration.
    let last = scene.trace.time.len() - 1;
    let rho = scene.model.pad_radius_m();
    let mut rested = 0;
    for leg in 0..scene.trace.legs {
        let c = |a: &str| scene.trace.column(&format!("leg{leg}_{a}"))[last];
        let tip = DVec3::new(c("tip_x_m"), c("tip_y_m"), c("tip_z_m"));
        let depth = c("penetration_m");
        if depth <= 0.0 || s.normal.dot(tip) < 0.01 {
            continue;
        }
        rested += 1;
        let centre = tip + s.normal * rho;
        assert!(
            rocks.iter().any(|r| {
                ((centre - r.centre).length() - (r.radius_m + rho - depth)).abs() < 1e-6
            }),
            "leg {leg} rests on no rock drawn"
        );
    }
    assert!(rested >= 1, "no footpad rests on a rock");
}

#[test]
fn on_regolith_a_footpad_on_a_rock_is_not_sunk_and_one_in_the_soil_is() {
    let dir = TempDir::new("scene-sinkage");
    let abundance = "{ dist = \"uniform\", min = 0.1, max = 0.4 }";
    let scenario = format!("[surface]\nkind = \"regolith\"\n{}", rocky(abundance));
    // Sample 4 ends with footpad 0 on a rock's top (3 cm above the plane) and footpads 2
    // and 3 pressed into the soil (found by running samples 3 and 4).
    trace(&dir, "both", &scenario, "4");
    let scene = Scene::read(&dir.join("both.arrow")).expect("read the trace");
    let t = scene.trace.span_s().1;
    let depth = |leg: usize| scene.trace.value(&format!("leg{leg}_penetration_m"), t);
    let (on_rock, in_soil) = (0..4).partition::<Vec<_>, _>(|k| {
        let tip = ["x", "y", "z"].map(|a| scene.trace.value(&format!("leg{k}_tip_{a}_m"), t));
        scene.surface.normal.dot(DVec3::from_array(tip)) > 0.01
    });
    assert!(
        !on_rock.is_empty() && !in_soil.is_empty(),
        "{on_rock:?} {in_soil:?}"
    );
    for k in on_rock.into_iter().filter(|k| depth(*k) > 0.0) {
        assert_eq!(scene.sinkage_m(k, t), 0.0, "leg {k} on a rock");
    }
    let sunk: Vec<usize> = in_soil.into_iter().filter(|k| depth(*k) > 0.0).collect();
    assert!(!sunk.is_empty());
    for k in sunk {
        assert_eq!(scene.sinkage_m(k, t), depth(k), "leg {k} in the soil");
    }
}

/// The pixels of the last frame of a GIF whose colour is a grey (the rocks' and the
/// captions'), in the picture's part under the captions and above the scale bar.
fn greys(path: &Path) -> usize {
    let (shown, _, (w, h)) = frames(path);
    let last = shown.last().expect("a frame");
    last.chunks_exact(4)
        .enumerate()
        .filter(|(i, p)| {
            let (x, y) = (i % w, i / w);
            let grey = p[0].abs_diff(p[1]) <= 8 && p[1].abs_diff(p[2]) <= 8;
            grey && (60..235).contains(&p[0]) && y > h / 6 && y < h * 5 / 6 && x > w / 8
        })
        .count()
}

#[test]
fn animate_draws_rocks_and_sunk_footpads_and_view_holds_them() {
    let dir = TempDir::new("ground-pictures");
    trace(&dir, "rocky", &rocky("0.3"), "0");
    trace(&dir, "bare", &rocky("0.0"), "0");
    trace(&dir, "soft", SOFT, "0");
    trace(&dir, "hard", HARD, "0");
    for name in ["rocky", "bare", "soft", "hard"] {
        let (arrow, gif) = (format!("{name}.arrow"), format!("{name}.gif"));
        let run = touchdown(dir.path(), &["animate", &arrow, "--size", "320x240"]);
        run.assert_ok();
        assert!(dir.join(&gif).is_file(), "{run}");
        touchdown(dir.path(), &["view", &arrow]).assert_ok();
    }
    // Rocks are grey; the bare plane's picture has only the captions' few greys.
    let (rocky, bare) = (greys(&dir.join("rocky.gif")), greys(&dir.join("bare.gif")));
    assert!(rocky > bare + 2000, "rock pixels: {rocky} against {bare}");
    // Sunk footpads: the holes (the ground's darkest shades) show where none is on the
    // plane. Ground shades are browns: red above blue by a fifth or more.
    let dark = |name: &str| {
        let (shown, _, _) = frames(&dir.join(&format!("{name}.gif")));
        let last = shown.last().expect("a frame").clone();
        last.chunks_exact(4)
            .filter(|p| p[0] < 90 && p[0] > 30 && f64::from(p[2]) < 0.85 * f64::from(p[0]))
            .count()
    };
    let (soft, hard) = (dark("soft"), dark("hard"));
    assert!(soft > hard + 100, "hole pixels: {soft} against {hard}");
    // The pages: the rocks' centres and radii, the footprints and the soil's flag, and no
    // trace of either on a page without them.
    let page = |name: &str| std::fs::read_to_string(dir.join(&format!("{name}.html"))).unwrap();
    let data = |page: &str| -> serde_json::Value {
        let start = page
            .find("\"trace-data\" type=\"application/json\">")
            .unwrap();
        let json = &page[start..];
        let json = &json[json.find('>').unwrap() + 1..json.find("</script>").unwrap()];
        serde_json::from_str(&json.replace("<\\/", "</")).expect("the page's JSON")
    };
    let rocks = data(&page("rocky"))["rocks"]
        .as_array()
        .expect("rocks")
        .clone();
    assert!(rocks.len() > 10, "{} rocks", rocks.len());
    for r in &rocks {
        let r: Vec<f64> = r
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!(r.len() == 4 && r[3] > 0.0 && r[3] <= 1.0, "{r:?}");
    }
    let soft = data(&page("soft"));
    assert_eq!(soft["regolith"], serde_json::Value::Bool(true));
    // Each leg's sinkage at every time of the page; the lander ends sunk over 10 cm.
    let times = soft["time"].as_array().unwrap().len();
    let sinkage = soft["sinkage_m"].as_array().expect("sinkage_m");
    assert_eq!(sinkage.len(), 4);
    for leg in sinkage {
        let leg = leg.as_array().unwrap();
        assert_eq!(leg.len(), times);
        assert!(
            leg[times - 1].as_f64().unwrap() > 0.1,
            "{:?}",
            leg[times - 1]
        );
    }
    assert!(soft.get("rocks").is_none());
    for name in ["bare", "hard"] {
        let text = page(name);
        for key in ["\"rocks\"", "\"footprints\"", "\"regolith\"", "groundPrims"] {
            assert!(!text.contains(key), "{name}: {key}");
        }
    }
    for name in ["rocky", "soft"] {
        assert!(page(name).contains("groundPrims(prims"), "{name}");
    }
}

#[test]
fn a_page_with_rocks_and_one_on_regolith_open_in_a_browser() {
    let Some(browser) = chromium("a_page_with_rocks_and_one_on_regolith_open_in_a_browser") else {
        return;
    };
    let dir = TempDir::new("ground-browser");
    trace(&dir, "rocky", &rocky("0.3"), "0");
    trace(&dir, "soft", SOFT, "0");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/python/browser_view.py");
    for name in ["rocky", "soft"] {
        touchdown(dir.path(), &["view", &format!("{name}.arrow")]).assert_ok();
        let o = Command::new(python())
            .arg(&script)
            .arg(&browser)
            .arg(dir.join(&format!("{name}.html")))
            .arg(dir.join(&format!("shots-{name}")))
            .output()
            .expect("run the browser test");
        let stdout = String::from_utf8_lossy(&o.stdout);
        if o.status.code() == Some(3)
            && std::env::var("TOUCHDOWN_REQUIRE_CHROMIUM").as_deref() != Ok("1")
        {
            return;
        }
        assert!(o.status.success(), "{name}: {stdout}");
        let named = if name == "rocky" {
            "ok: hover names rocks"
        } else {
            "ok: hover names a sunk footpad"
        };
        for check in ["ok: no console errors", "ok: 3D canvas drawn", named] {
            assert!(stdout.contains(check), "{name}: no {check:?} in:\n{stdout}");
        }
    }
}
