//! The facets' table of a landing-site map: a row per facet (where it is, its ground,
//! roughness and gravity, its outcome shares with their intervals), as Arrow or Parquet,
//! with the body and the method in the schema's metadata.

use super::estimate::Window;
use super::{SHARE_OUTCOMES, Site, SiteFacet};
use crate::output::format::Format;
use crate::output::{AtomicFile, ENGINE, IpcWriter, cannot_write, field};
use arrow_array::{ArrayRef, Float64Array, RecordBatch, UInt32Array, UInt64Array};
use arrow_schema::{DataType, Field, Schema};
use std::collections::HashMap;
use std::path::Path;
use std::sync::Arc;

/// What the table's metadata records besides the body.
pub struct About<'a> {
    /// The shape file as given.
    pub shape: &'a str,
    /// The window the shares count samples in.
    pub window: Window,
    /// The sweep's file name, in the map's folder.
    pub sweep_file: &'a str,
    /// Its scenario text.
    pub sweep_text: &'a str,
    /// Its samples.
    pub samples: u64,
    /// How the facets' gravity was summed, in words.
    pub gravity: &'a str,
}

/// A column of one `f64` per facet.
fn float(
    fields: &mut Vec<Field>,
    columns: &mut Vec<ArrayRef>,
    (name, unit, description): (&str, &str, &str),
    values: impl Iterator<Item = Option<f64>>,
) {
    // Only the shares may be missing (a facet without samples, or too steep).
    let f = field(name, DataType::Float64, unit, description).with_nullable(name.starts_with("p_"));
    fields.push(f);
    columns.push(Arc::new(values.collect::<Float64Array>()));
}

/// The table's metadata: the body, the method, the sweep.
fn metadata(site: &Site, about: &About<'_>) -> HashMap<String, String> {
    let b = &site.body;
    [
        ("touchdown.kind", "site".to_string()),
        ("touchdown.engine", ENGINE.to_string()),
        ("touchdown.site.shape", about.shape.to_string()),
        ("touchdown.site.body", b.name.clone()),
        (
            "touchdown.site.density_kg_m3",
            super::given_number(b.density_kg_m3),
        ),
        (
            "touchdown.site.spin_period_h",
            super::given_number(b.spin_period_h),
        ),
        (
            "touchdown.site.spin_axis",
            format!("{} {} {}", b.spin_axis[0], b.spin_axis[1], b.spin_axis[2]),
        ),
        ("touchdown.site.mass_kg", b.mass_kg.to_string()),
        ("touchdown.site.volume_m3", b.volume_m3.to_string()),
        ("touchdown.site.area_m2", b.area_m2.to_string()),
        (
            "touchdown.site.centre_of_mass_m",
            format!(
                "{} {} {}",
                b.centre_of_mass_m[0], b.centre_of_mass_m[1], b.centre_of_mass_m[2]
            ),
        ),
        (
            "touchdown.site.window_slope_deg",
            about.window.slope_deg.to_string(),
        ),
        (
            "touchdown.site.window_gravity_fraction",
            about.window.gravity_fraction.to_string(),
        ),
        (
            "touchdown.site.safe_area_fraction",
            site.safe_area_fraction().to_string(),
        ),
        (
            "touchdown.site.safe_area_fraction_point_estimate",
            site.safe_area_fraction_point_estimate().to_string(),
        ),
        ("touchdown.site.gravity", about.gravity.to_string()),
        ("touchdown.site.sweep_file", about.sweep_file.to_string()),
        ("touchdown.samples", about.samples.to_string()),
        ("touchdown.scenario", about.sweep_text.to_string()),
    ]
    .into_iter()
    .map(|(k, v)| (k.to_string(), v))
    .collect()
}

/// The table's columns.
fn columns(facets: &[SiteFacet]) -> (Vec<Field>, Vec<ArrayRef>) {
    let mut fields = vec![field(
        "facet",
        DataType::UInt32,
        "",
        "the facet's number, 0-based, in the shape file's order",
    )];
    let mut columns: Vec<ArrayRef> = vec![Arc::new(UInt32Array::from_iter_values(
        facets.iter().map(|f| f.facet),
    ))];
    let (fs, cs) = (&mut fields, &mut columns);
    let xyz = ["x", "y", "z"];
    for (k, axis) in xyz.iter().enumerate() {
        float(
            fs,
            cs,
            (
                &format!("centroid_{axis}_m"),
                "m",
                "the facet's centroid, body frame",
            ),
            facets.iter().map(|f| Some(f.centroid_m[k])),
        );
    }
    float(
        fs,
        cs,
        (
            "latitude_deg",
            "deg",
            "the centroid's latitude (about the spin axis: the body frame's z unless --spin-axis)",
        ),
        facets.iter().map(|f| Some(f.latitude_deg)),
    );
    float(
        fs,
        cs,
        (
            "longitude_deg",
            "deg",
            "the centroid's longitude, east from +x (made perpendicular to the spin axis), in (-180, 180]",
        ),
        facets.iter().map(|f| Some(f.longitude_deg)),
    );
    for (k, axis) in xyz.iter().enumerate() {
        float(
            fs,
            cs,
            (
                &format!("normal_{axis}"),
                "1",
                "the facet's outward unit normal",
            ),
            facets.iter().map(|f| Some(f.normal[k])),
        );
    }
    float(
        fs,
        cs,
        ("area_m2", "m^2", "the facet's area"),
        facets.iter().map(|f| Some(f.area_m2)),
    );
    for (k, axis) in xyz.iter().enumerate() {
        float(
            fs,
            cs,
            (
                &format!("effective_gravity_{axis}_m_s2"),
                "m/s^2",
                "the effective gravity at the centroid (attraction and centrifugal), body frame",
            ),
            facets.iter().map(|f| Some(f.effective_gravity_m_s2[k])),
        );
    }
    float(
        fs,
        cs,
        ("gravity_m_s2", "m/s^2", "the effective gravity's magnitude"),
        facets.iter().map(|f| Some(f.gravity_m_s2)),
    );
    float(
        fs,
        cs,
        (
            "slope_deg",
            "deg",
            "the angle between the outward normal and minus the effective gravity",
        ),
        facets.iter().map(|f| Some(f.slope_deg)),
    );
    float(
        fs,
        cs,
        (
            "roughness_deg",
            "deg",
            "the RMS angle between the outward normal and its three edge-neighbours' normals \
             (the shape model's facet-to-facet relief; reported, not simulated)",
        ),
        facets.iter().map(|f| Some(f.roughness_deg)),
    );
    fields.push(field(
        "samples",
        DataType::UInt64,
        "",
        "the sweep's samples in the facet's window of slope and gravity",
    ));
    columns.push(Arc::new(UInt64Array::from_iter_values(
        facets.iter().map(|f| f.samples),
    )));
    for (k, o) in SHARE_OUTCOMES.iter().enumerate() {
        let name = o.name();
        for (suffix, what, pick) in [
            ("", "share", 0),
            ("_low", "95 % interval's low end of the share", 1),
            ("_high", "95 % interval's high end of the share", 2),
        ] {
            let description = format!(
                "{what} of {name} landings near the facet's slope and gravity (null: no \
                 sample, or too steep to stand on)"
            );
            float(
                &mut fields,
                &mut columns,
                (&format!("p_{name}{suffix}"), "1", &description),
                facets.iter().map(|f| {
                    f.shares.map(|s| match pick {
                        0 => s[k].p,
                        1 => s[k].low,
                        _ => s[k].high,
                    })
                }),
            );
        }
    }
    (fields, columns)
}

/// Writes `site`'s facets' table to `path` in `format`, whole or not at all.
pub fn write(path: &Path, format: Format, site: &Site, about: &About<'_>) -> anyhow::Result<()> {
    let (fields, columns) = columns(&site.facets);
    let schema = Arc::new(Schema::new(fields).with_metadata(metadata(site, about)));
    let batch = RecordBatch::try_new(schema.clone(), columns)?;
    let failed = |e: anyhow::Error| cannot_write(path, e);
    let (file, out) = AtomicFile::create(path)?;
    let out = match format {
        Format::Arrow => {
            let mut w = IpcWriter::new(&file, out, &schema).map_err(failed)?;
            w.write(&batch).map_err(|e| failed(e.into()))?;
            w.finish().map_err(|e| failed(e.into()))?
        }
        Format::Parquet => {
            let props = crate::output::format::parquet_properties(&schema, None);
            let mut w = parquet::arrow::ArrowWriter::try_new(out, schema.clone(), Some(props))
                .map_err(|e| failed(e.into()))?;
            w.write(&batch).map_err(|e| failed(e.into()))?;
            w.into_inner().map_err(|e| failed(e.into()))?
        }
    };
    let mut out = out;
    std::io::Write::flush(&mut out).map_err(|e| failed(e.into()))?;
    file.commit(out)
}
