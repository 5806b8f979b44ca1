//! The report as JSON, for programs (Python's `touchdown.report`, a notebook, a pipeline):
//! the same numbers as the Markdown, unrounded, under stable snake_case keys with the unit
//! in the key or beside the value, as the sweep's columns have them. Keys keep the order
//! the Markdown gives them; a number that does not exist is `null`, with its `reason`
//! where the Markdown gives one.

use super::data::{Provenance, Report, Sector, Terrain};
use super::gear::GearSection;
use super::numbers::{Share, Summary, fraction};
use super::release::ReleaseSection;
use super::thrust::ThrustSection;
use crate::exceedance::{DESIGN_LEVELS, DesignRow, DesignValue, DesignValues};
use crate::reference::Outcome;
use crate::stats::{ALLOWABLE_STABLE, Allowable, MIN_SAMPLES};
use std::fmt::Write as _;

/// A JSON value whose objects keep their keys in the order written.
enum Json {
    /// `null`, a boolean, a number or a string, as `serde_json` writes it.
    Leaf(serde_json::Value),
    /// A list.
    Array(Vec<Json>),
    /// Keys and their values, in this order.
    Object(Vec<(&'static str, Json)>),
}

/// What becomes a JSON value: numbers (`null` where not finite), text, flags, `None` as
/// `null`, lists.
trait ToJson {
    /// It as JSON.
    fn json(self) -> Json;
}

impl ToJson for Json {
    fn json(self) -> Json {
        self
    }
}

impl ToJson for f64 {
    fn json(self) -> Json {
        Json::Leaf(serde_json::Number::from_f64(self).map_or(serde_json::Value::Null, Into::into))
    }
}

/// Counts, flags and text, as they are.
macro_rules! leaf {
    ($($t:ty),*) => {
        $(impl ToJson for $t {
            fn json(self) -> Json {
                Json::Leaf(self.into())
            }
        })*
    };
}
leaf!(u64, usize, bool, &str, String);

impl<T: ToJson> ToJson for Option<T> {
    fn json(self) -> Json {
        self.map_or(Json::Leaf(serde_json::Value::Null), ToJson::json)
    }
}

impl<T: ToJson> ToJson for Vec<T> {
    fn json(self) -> Json {
        Json::Array(self.into_iter().map(ToJson::json).collect())
    }
}

/// An object of `"key": value` pairs, in the order written.
macro_rules! object {
    ($($key:literal: $value:expr),* $(,)?) => {
        Json::Object(vec![$(($key, ToJson::json($value))),*])
    };
}

/// An object of `(key, value)` pairs, in their order.
fn keyed(pairs: impl IntoIterator<Item = (&'static str, Json)>) -> Json {
    Json::Object(pairs.into_iter().collect())
}

impl Json {
    /// Writes it at `indent` levels of two spaces, as `serde_json`'s pretty printer does.
    fn write(&self, t: &mut String, indent: usize) {
        let pad = |t: &mut String, n: usize| t.extend(std::iter::repeat_n("  ", n));
        match self {
            Json::Leaf(v) => {
                let _ = write!(t, "{v}");
            }
            Json::Array(a) if a.is_empty() => t.push_str("[]"),
            Json::Object(o) if o.is_empty() => t.push_str("{}"),
            Json::Array(a) => {
                t.push_str("[\n");
                for (i, v) in a.iter().enumerate() {
                    pad(t, indent + 1);
                    v.write(t, indent + 1);
                    t.push_str(if i + 1 < a.len() { ",\n" } else { "\n" });
                }
                pad(t, indent);
                t.push(']');
            }
            Json::Object(o) => {
                t.push_str("{\n");
                for (i, (k, v)) in o.iter().enumerate() {
                    pad(t, indent + 1);
                    let _ = write!(t, "{}: ", serde_json::Value::from(*k));
                    v.write(t, indent + 1);
                    t.push_str(if i + 1 < o.len() { ",\n" } else { "\n" });
                }
                pad(t, indent);
                t.push('}');
            }
        }
    }
}

/// The report `r` as a JSON document (pretty-printed, ending in a newline).
pub(super) fn json(r: &Report) -> String {
    let document = object! {
        "provenance": provenance(&r.provenance),
        "outcomes": keyed(r.outcomes.iter().map(|(o, s)| (o.name(), share(s)))),
        "stable_within_limits": r.stable_within_limits.as_ref().map(share),
        "gear": r.gear.as_ref().map(gear),
        "regolith": r.ground.as_ref().map(|g| keyed(g.quantities.iter().map(|q| (q.key, summary(q))))),
        "terrain": r.terrain.as_ref().map(terrain),
        "allowable_slope_rule": object! {
            "stable_share": ALLOWABLE_STABLE,
            "min_samples": MIN_SAMPLES,
        },
        "allowable_slope": r.allowable.iter().map(sector).collect::<Vec<_>>(),
        "peak_loads": keyed(r.loads.iter().map(|l| (l.key, summary(l)))),
        "exceedance": exceedance(&r.exceedance),
        "thrust": r.thrust.as_ref().map(thrust),
        "release": r.release.as_ref().map(release),
    };
    let mut t = String::new();
    document.write(&mut t, 0);
    t.push('\n');
    t
}

/// Where the sweep came from.
fn provenance(p: &Provenance) -> Json {
    let mut o = object! {
        "sweep": p.sweep.display().to_string(),
        "in_memory": p.in_memory,
        "seed": p.seed.as_deref().and_then(|s| s.parse::<u64>().ok()),
        "samples": p.samples,
        "engine": p.engine.clone(),
        "dampers": p.dampers,
    };
    // Only a file short of its samples says so: an interrupted sweep's.
    if let (Json::Object(keys), Some((asked, note))) = (&mut o, &p.interrupted) {
        keys.push((
            "interrupted",
            object! {
                "samples_asked": *asked,
                "note": note.clone(),
            },
        ));
    }
    o
}

/// A count of samples: `count`, `share`, `low`, `high`.
fn share(s: &Share) -> Json {
    object! {
        "count": s.count,
        "share": s.share,
        "low": s.low,
        "high": s.high,
    }
}

/// A quantity over the samples: its name, unit, mean, smallest, median, 99th percentile and largest value.
fn summary(s: &Summary) -> Json {
    object! {
        "name": s.name,
        "unit": s.unit,
        "mean": s.mean,
        "min": s.min,
        "median": s.median,
        "p99": s.p99,
        "max": s.max,
    }
}

/// The gear section: bottomed dampers and the samples that broke each limit, by its name in `limits_broken`.
fn gear(g: &GearSection) -> Json {
    let broken = g.broken.iter().map(|b| {
        let s = &b.samples;
        let value = object! {
            "limit_key": b.key,
            "limit": b.value,
            "description": b.text.clone(),
            "count": s.count,
            "share": s.share,
            "low": s.low,
            "high": s.high,
        };
        (b.name, value)
    });
    object! {
        "damper_bottomed": g.bottomed.as_ref().map(share),
        "limits_broken": keyed(broken),
    }
}

/// The outcome shares on a terrain, with their standard errors.
fn terrain(t: &Terrain) -> Json {
    let w = &t.weighted;
    let outcomes = Outcome::listed(w.controlled).map(|o| {
        let s = &w.shares[o as usize];
        let value = object! {
            "share": s.p,
            "low": s.low,
            "high": s.high,
            "standard_error": s.se,
        };
        (o.name(), value)
    });
    object! {
        "distribution": t.text.clone(),
        "description": t.description.clone(),
        "samples": w.samples,
        "effective_samples": w.effective_samples,
        "uncovered_share": w.uncovered,
        "sweep_slope_min_deg": w.range.0,
        "sweep_slope_max_deg": w.range.1,
        "outcomes": keyed(outcomes),
    }
}

/// One sector's allowable slope: `slope_deg` and its interval, or `null` and the `reason`.
fn sector(s: &Sector) -> Json {
    let (slope, low, high, reason) = match s.allowable {
        Allowable::TooFewSamples(_) => (None, None, None, Some("too few samples".to_string())),
        Allowable::NoSlope { below_deg } => (
            None,
            Some(0.0),
            Some(below_deg),
            Some(format!(
                "no slope with at least {:.0} % stable",
                100.0 * ALLOWABLE_STABLE
            )),
        ),
        Allowable::Slope {
            slope_deg,
            low_deg,
            high_deg,
        } => (Some(slope_deg), Some(low_deg), Some(high_deg), None),
    };
    object! {
        "azimuth_min_deg": s.azimuth_deg.0,
        "azimuth_max_deg": s.azimuth_deg.1,
        "samples": s.samples,
        "stable": s.stable,
        "stable_share": (s.samples > 0).then(|| fraction(s.stable, s.samples)),
        "slope_deg": slope,
        "low_deg": low,
        "high_deg": high,
        "reason": reason,
    }
}

/// A design value and its interval (`null` ends, with the `reason`), or `null` without samples.
fn design_value(d: Option<DesignValue>) -> Json {
    let reason = |d: &DesignValue| match (d.low, d.high) {
        (_, None) => Some("more samples needed"),
        (None, Some(_)) => Some("too few samples below it"),
        (Some(_), Some(_)) => None,
    };
    d.map(|d| {
        object! {
            "value": d.value,
            "low": d.low,
            "high": d.high,
            "reason": reason(&d),
        }
    })
    .json()
}

/// The design values of one series at 99 % (`p99`) and 99.9 % (`p99_9`), and its largest value.
fn design_row(r: &DesignRow) -> Json {
    object! {
        "p99": design_value(r.levels[0]),
        "p99_9": design_value(r.levels[1]),
        "max": r.largest,
    }
}

/// The exceedance section: per quantity (by key), over all legs and per leg.
fn exceedance(d: &DesignValues) -> Json {
    let quantities = d.quantities.iter().map(|q| {
        let value = object! {
            "name": q.name,
            "unit": q.unit,
            "overall": design_row(&q.overall),
            "legs": q.legs.iter().map(design_row).collect::<Vec<_>>(),
        };
        (q.key, value)
    });
    object! {
        "samples": d.samples,
        "levels": DESIGN_LEVELS.to_vec(),
        "quantities": keyed(quantities),
    }
}

/// The thrust section: the quantities by their column, and the propellant per outcome.
fn thrust(t: &ThrustSection) -> Json {
    let by_outcome = t.by_outcome.iter().map(|&(o, k, kg)| {
        let value = object! {
            "samples": k,
            "mean_propellant_kg": kg,
        };
        (o.name(), value)
    });
    object! {
        "samples": t.samples,
        "fired": t.fired,
        "propellant_total_kg": t.propellant_kg,
        "quantities": keyed(t.quantities.iter().map(|q| (q.key, summary(q)))),
        "by_outcome": keyed(by_outcome),
    }
}

/// The release section: the samples released and the quantities by key.
fn release(r: &ReleaseSection) -> Json {
    object! {
        "samples": r.samples,
        "released": r.released,
        "contact_first": r.samples - r.released,
        "quantities": keyed(r.quantities.iter().map(|q| (q.key, summary(q)))),
    }
}
