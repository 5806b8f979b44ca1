//! `touchdown site`: where on a small body the lander can land. Each facet of a shape
//! model has a slope and a gravity (`crate::shape`); one sweep over the range of both that
//! the body spans gives each facet the outcome shares of the samples near its own slope and
//! gravity (`estimate`), with 95 % intervals; the shares of the surface follow by area.
//! docs/MODEL.md, "Landing sites".

pub mod estimate;
pub mod summary;
pub mod table;
pub mod warnings;

use crate::reference::Outcome;

/// The outcomes whose shares each facet gets, in this order.
pub const SHARE_OUTCOMES: [Outcome; 4] = [
    Outcome::Stable,
    Outcome::Tipped,
    Outcome::Sliding,
    Outcome::Bouncing,
];

/// The P(stable) a facet must reach to count as a landing site in `Site::safe_area_fraction`:
/// the low end of its 95 % interval must reach it.
pub const SAFE_P_STABLE: f64 = 0.99;

/// The steepest slope a site's sweep draws, deg: a lander cannot stand on 90 deg, and the
/// scenario refuses it. Facets steeper than it get no shares: "too steep".
pub const SLOPE_LIMIT_DEG: f64 = 89.0;

/// An outcome's share on a facet, with its 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FacetShare {
    /// The share of the samples near the facet's slope and gravity.
    pub p: f64,
    /// The low end of its 95 % interval.
    pub low: f64,
    /// The high end of its 95 % interval.
    pub high: f64,
}

/// One facet of the body: where it is, its ground and gravity, and how landings end there.
#[derive(Debug, Clone, PartialEq)]
pub struct SiteFacet {
    /// The facet's number, 0-based, in the order of the shape model's file.
    pub facet: u32,
    /// Its centroid in the body frame, m.
    pub centroid_m: [f64; 3],
    /// The centroid's latitude and longitude, deg (spherical, about the spin axis: the body
    /// frame's z unless `--spin-axis` says otherwise; longitude 0 along +x, or along the x
    /// made perpendicular to a tilted axis (`shape::spin_frame`), east positive, in
    /// (-180, 180]).
    pub latitude_deg: f64,
    /// See `latitude_deg`.
    pub longitude_deg: f64,
    /// Its outward unit normal.
    pub normal: [f64; 3],
    /// Its area, m^2.
    pub area_m2: f64,
    /// The effective gravity at the centroid (the body's attraction and the spin's
    /// centrifugal acceleration), m/s^2, body frame.
    pub effective_gravity_m_s2: [f64; 3],
    /// Its magnitude, m/s^2: the gravity a lander feels there.
    pub gravity_m_s2: f64,
    /// The local slope: the angle between the outward normal and minus the effective
    /// gravity, deg (above 90 where the effective gravity points off the ground).
    pub slope_deg: f64,
    /// The root mean square of the angles between its outward normal and its three
    /// edge-neighbours' normals, deg (`crate::shape::roughness_deg`): the relief from facet
    /// to facet the shape model resolves. Reported only: the sweep does not use it.
    pub roughness_deg: f64,
    /// The samples of the sweep that the facet's shares count.
    pub samples: u64,
    /// The shares of `SHARE_OUTCOMES`; `None` where the facet is too steep to stand on
    /// (`SLOPE_LIMIT_DEG` or more, or outside the sweep's range) or its window holds no
    /// sample (`samples` 0: "no samples").
    pub shares: Option<[FacetShare; 4]>,
}

impl SiteFacet {
    /// P(stable) and its interval, if the facet has shares.
    #[must_use]
    pub fn p_stable(&self) -> Option<FacetShare> {
        self.shares.map(|s| s[0])
    }

    /// Whether a lander could stand on its slope (below `SLOPE_LIMIT_DEG`): a facet that
    /// could, without shares, had no samples in its window.
    #[must_use]
    pub fn standing(&self) -> bool {
        self.slope_deg < SLOPE_LIMIT_DEG
    }

    /// Whether it is a landing site: the low end of P(stable)'s 95 % interval (Wilson's)
    /// reaches `SAFE_P_STABLE`.
    #[must_use]
    pub fn safe(&self) -> bool {
        self.p_stable().is_some_and(|s| s.low >= SAFE_P_STABLE)
    }

    /// Whether its P(stable) itself (the point estimate) reaches `SAFE_P_STABLE`.
    #[must_use]
    pub fn safe_by_point_estimate(&self) -> bool {
        self.p_stable().is_some_and(|s| s.p >= SAFE_P_STABLE)
    }
}

/// A number the user gave (a density, a spin period), as messages and files show it: as
/// Rust writes it where that is short, in exponent form (`1e300`, the same number) where
/// it would run to more than 16 digits or start with more than 4 zeros.
#[must_use]
pub fn given_number(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-4..1e16).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// The body: its shape and the numbers it was given.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Its name (the shape file's stem).
    pub name: String,
    /// The shape model's vertices, m, body frame.
    pub vertices: Vec<[f64; 3]>,
    /// Its triangles (0-based vertex indices, counter-clockwise seen from outside), in the
    /// order of `Site::facets`.
    pub triangles: Vec<[u32; 3]>,
    /// Bulk density, kg/m^3.
    pub density_kg_m3: f64,
    /// Rotation period, h.
    pub spin_period_h: f64,
    /// Spin axis, a unit vector in the body frame.
    pub spin_axis: [f64; 3],
    /// Mass, kg (the polyhedron's volume times the density).
    pub mass_kg: f64,
    /// Volume, m^3.
    pub volume_m3: f64,
    /// Surface area, m^2.
    pub area_m2: f64,
    /// The centre of mass at constant density, m, body frame. The spin is about the
    /// frame's origin (a shape model's convention: its centre of mass), not about this.
    pub centre_of_mass_m: [f64; 3],
}

/// A landing-site map: the body and each facet's numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct Site {
    /// The body.
    pub body: Body,
    /// Every facet, in the shape model's order.
    pub facets: Vec<SiteFacet>,
}

impl Site {
    /// The fraction of the surface (by area) of the landing sites: the facets whose
    /// P(stable) is at least `SAFE_P_STABLE` with 95 % confidence, the low end of its Wilson
    /// interval (`SiteFacet::safe`). Facets without shares count as not safe.
    #[must_use]
    pub fn safe_area_fraction(&self) -> f64 {
        self.area_fraction(SiteFacet::safe)
    }

    /// [`Site::safe_area_fraction`] by the point estimate of P(stable) instead of its low
    /// end: larger, by the facets whose samples are too few to be sure.
    #[must_use]
    pub fn safe_area_fraction_point_estimate(&self) -> f64 {
        self.area_fraction(SiteFacet::safe_by_point_estimate)
    }

    /// The fraction of the surface (by area) of the facets that `keep`.
    fn area_fraction(&self, keep: fn(&SiteFacet) -> bool) -> f64 {
        let total: f64 = self.facets.iter().map(|f| f.area_m2).sum();
        let kept: f64 = self
            .facets
            .iter()
            .filter(|f| keep(f))
            .map(|f| f.area_m2)
            .sum();
        // `+ 0.0`: an empty sum is -0.0.
        if total > 0.0 { kept / total + 0.0 } else { 0.0 }
    }
}

/// What the samples of a map's sweep did beyond the facets' shares: those that diverged,
/// were held by thrust, or never touched the ground (counted in the facets' samples, the
/// first two in none of their shares, the last as bouncing or tipped).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SweepTally {
    /// The samples of the sweep.
    pub samples: u64,
    /// Those that diverged (a non-finite or exploding state).
    pub diverged: u64,
    /// Those held on the ground by a control loop still running at the end.
    pub held: u64,
    /// Those that never touched the ground before `simulation.t_max_s` (and did not
    /// diverge).
    pub untouched: u64,
    /// Those of them that turned over in flight on slopes of `STEEP_START_DEG` or more,
    /// where a lander released upright already leans that far from the ground's normal.
    pub untouched_steep: u64,
    /// The least slope of those, deg.
    pub untouched_steep_slope_deg: f64,
    /// The largest release height of the others that never touched, m.
    pub untouched_release_m: f64,
    /// The largest upward velocity error of the others that never touched, m/s (0 if none
    /// rose).
    pub untouched_rising_m_s: f64,
}

/// The slope from which a lander that turned over before it touched is put down to the
/// slope itself (it starts upright, leaning that far from the ground's normal), deg.
pub const STEEP_START_DEG: f64 = 45.0;
