//! The `[simulation]` table: time stepping and the lanes' precision.

use super::reader::table;
use kernels::isa::Precision;

table! {
    /// Time stepping.
    #[derive(Debug, Clone, PartialEq)]
    pub struct Simulation;
    fn read_simulation(r) with key {
        /// Step whenever a leg may touch the surface.
        step_s: f64 = r.f64_where(
            key,
            "a step greater than 0 and at most 0.01 s (the contact springs need small steps)",
            |x| x > 0.0 && x <= 0.01,
        )?,
        /// Longest step in free flight, taken only where no leg can reach the surface in it
        /// (by default at least `step_s`).
        flight_step_max_s: f64 = r.f64_where(
            key,
            &format!("a step of at least step_s = {step_s} s and at most 1 s"),
            |x| x >= step_s && x <= 1.0,
        )?
        .max(step_s),
        /// The error a contact step may add to a footpad's velocity, m/s (MODEL.md section
        /// 2.1): given, each lander's step in contact follows its own local error estimate,
        /// between `step_min_s` and `step_max_s`; absent, every contact step is `step_s`.
        tolerance_m_s: Option<f64> = r.given(key, |r| {
            r.f64_where(
                key,
                "a velocity error greater than 0 and at most 1 m/s",
                |x| x > 0.0 && x <= 1.0,
            )
        })?,
        /// The shortest contact step the error control may take (by default `step_s / 8`).
        step_min_s: f64 = r.or(key, step_s / 8.0).f64_where(
            key,
            &format!("a step greater than 0 and at most step_s = {step_s} s"),
            |x| x > 0.0 && x <= step_s,
        )?,
        /// The longest contact step the error control may take (by default `2 step_s`, at
        /// most `flight_step_max_s`): the explicit contact springs and dampers bound it, not
        /// the error estimate (MODEL.md section 2.1).
        step_max_s: f64 = r.or(key, (2.0 * step_s).min(flight_step_max_s)).f64_where(
            key,
            &format!(
                "a step of at least step_s = {step_s} s and at most flight_step_max_s = \
                 {flight_step_max_s} s"
            ),
            |x| x >= step_s && x <= flight_step_max_s,
        )?,
        /// A sample ends when its outcome is decided or at this time.
        t_max_s: f64 = r.f64_where(
            key,
            &format!("a time of at least step_s = {step_s} s and at most 1e6 s"),
            |x| x >= step_s && x <= 1e6,
        )?,
        /// The lanes' precision: f64 or f32 (twice the landers per lane value, faster;
        /// the shares a sweep reports agree with f64's within their sampling error, single
        /// samples near a decision threshold may end otherwise).
        precision: Precision = r.word(key, &Precision::ALL.map(|p| (p.key(), p)))?,
    }
}
