//! The colours of the picture and the one palette every frame maps onto.

use crate::plot::canvas::OUTCOME_COLOURS;
use plotters::style::RGBColor;

/// The palette index that marks a pixel unchanged since the previous frame.
pub(super) const TRANSPARENT: u8 = 255;

// Colours of the picture.
/// The background.
pub(super) const BACKGROUND: RGBColor = RGBColor(250, 250, 252);
/// The ground.
pub(super) const GROUND: RGBColor = RGBColor(158, 146, 132);
/// The body.
pub(super) const BODY: RGBColor = RGBColor(214, 162, 42);
/// The struts.
pub(super) const STRUT: RGBColor = RGBColor(70, 72, 80);
/// The dampers' pistons.
pub(super) const PISTON: RGBColor = RGBColor(175, 178, 186);
/// The footpads.
pub(super) const FOOTPAD: RGBColor = RGBColor(55, 58, 66);
/// The CG's trail.
pub(super) const TRAIL: RGBColor = RGBColor(31, 119, 180);
/// The contact-force arrows.
pub(super) const FORCE: RGBColor = RGBColor(214, 39, 40);
/// The thrust plumes.
pub(super) const PLUME: RGBColor = RGBColor(110, 190, 255);
/// The captions' text.
pub(super) const INK: RGBColor = RGBColor(20, 20, 24);
/// Outcome colours in the order of `Outcome::ALL`, as the sweep plots draw them.
pub(super) const OUTCOME: [RGBColor; 6] = OUTCOME_COLOURS;

/// The outcomes whose colour's shades the palette holds: those of a passive lander (the
/// palette, and so every GIF, stays as it was before `held`); a `held` caption takes the
/// nearest entry, a purple of the colour cube.
const PALETTE_OUTCOMES: usize = 5;
/// X_I, Y_I, Z_I of the axis triad.
pub(super) const AXES: [RGBColor; 3] = [
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(31, 119, 180),
];

/// Brightness levels a shaded material takes (so that its shades are palette entries).
pub(super) const SHADES: usize = 20;

/// A material's colour at brightness `b` (about 0.3 to 1.15), on one of `SHADES` levels.
pub(super) fn shade(c: RGBColor, b: f64) -> RGBColor {
    let level = ((b - 0.3) / 0.85 * (SHADES - 1) as f64)
        .round()
        .clamp(0.0, (SHADES - 1) as f64);
    let b = 0.3 + 0.85 * level / (SHADES - 1) as f64;
    let f = |x: u8| (f64::from(x) * b).round().clamp(0.0, 255.0) as u8;
    RGBColor(f(c.0), f(c.1), f(c.2))
}

/// The fixed palette of every frame: the shades of the materials, blends of the inks into
/// the background (the edges of text), greys, and a coarse colour cube for the rest;
/// `TRANSPARENT` last. Pixels map to their nearest entry through a table of 15-bit colours.
pub(super) struct Palette {
    /// The entries' colours, RGB, 256 of them.
    pub(super) rgb: Vec<u8>,
    /// The nearest entry of every 15-bit colour.
    lookup: Vec<u8>,
}

impl Palette {
    /// The palette and its lookup table.
    pub(super) fn new() -> Palette {
        let mut colours: Vec<RGBColor> = vec![BACKGROUND];
        for m in [GROUND, BODY, PISTON] {
            colours
                .extend((0..SHADES).map(|l| shade(m, 0.3 + 0.85 * l as f64 / (SHADES - 1) as f64)));
        }
        let blend = |c: RGBColor, f: f64| {
            let m = |a: u8, b: u8| (f64::from(a) * f + f64::from(b) * (1.0 - f)).round() as u8;
            RGBColor(
                m(c.0, BACKGROUND.0),
                m(c.1, BACKGROUND.1),
                m(c.2, BACKGROUND.2),
            )
        };
        for ink in [TRAIL, FORCE, PLUME, STRUT, FOOTPAD]
            .into_iter()
            .chain(OUTCOME.into_iter().take(PALETTE_OUTCOMES))
            .chain(AXES)
        {
            colours.extend((1..=6).map(|l| blend(ink, l as f64 / 6.0)));
        }
        colours.extend((0..32).map(|l| {
            let g = (l * 255 / 31) as u8;
            RGBColor(g, g, g)
        }));
        for r in 0..4u8 {
            for g in 0..4u8 {
                for b in 0..4u8 {
                    colours.push(RGBColor(r * 85, g * 85, b * 85));
                }
            }
        }
        colours.dedup();
        colours.truncate(255);
        let mut rgb: Vec<u8> = colours.iter().flat_map(|c| [c.0, c.1, c.2]).collect();
        rgb.resize(256 * 3, 0);
        let lookup = (0..1u32 << 15)
            .map(|c| {
                let (r, g, b) = (
                    ((c >> 10) & 31) * 255 / 31,
                    ((c >> 5) & 31) * 255 / 31,
                    (c & 31) * 255 / 31,
                );
                let d = |p: &RGBColor| {
                    let (dr, dg, db) = (
                        i64::from(p.0) - i64::from(r),
                        i64::from(p.1) - i64::from(g),
                        i64::from(p.2) - i64::from(b),
                    );
                    3 * dr * dr + 4 * dg * dg + 2 * db * db
                };
                (0..colours.len())
                    .min_by_key(|&i| d(&colours[i]))
                    .unwrap_or(0) as u8
            })
            .collect();
        Palette { rgb, lookup }
    }

    /// The palette indices of an RGB picture.
    pub(super) fn index(&self, rgb: &[u8]) -> Vec<u8> {
        rgb.chunks_exact(3)
            .map(|p| {
                let key = (usize::from(p[0] >> 3) << 10)
                    | (usize::from(p[1] >> 3) << 5)
                    | usize::from(p[2] >> 3);
                self.lookup[key]
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_palette_leaves_the_transparent_index_free() {
        let p = Palette::new();
        assert_eq!(p.rgb.len(), 256 * 3);
        assert!(p.lookup.iter().all(|i| *i != TRANSPARENT));
    }
}
