//! The `[simulation]` table: time stepping and the lanes' precision.

use super::error::ScenarioError;
use super::reader::Reader;
use kernels::isa::Precision;

/// Time stepping.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// Step whenever a leg may touch the surface.
    pub step_s: f64,
    /// Longest step in free flight, taken only where no leg can reach the surface in it.
    pub flight_step_max_s: f64,
    pub t_max_s: f64,
    /// The lanes' precision: f64 (eight landers per lane value) or f32 (sixteen, faster;
    /// the shares a sweep reports agree with f64's within their sampling error, single
    /// samples near a decision threshold may end otherwise).
    pub precision: Precision,
}

pub(super) fn read_simulation(
    top: &mut Reader,
    d: &Simulation,
) -> Result<Simulation, ScenarioError> {
    let Some(mut r) = top.table("simulation")? else {
        return Ok(d.clone());
    };
    let step_s = r.f64_where(
        "step_s",
        d.step_s,
        "a step greater than 0 and at most 0.01 s (the contact springs need small steps)",
        |x| x > 0.0 && x <= 0.01,
    )?;
    let flight_step_max_s = r.f64_where(
        "flight_step_max_s",
        d.flight_step_max_s.max(step_s),
        &format!("a step of at least step_s = {step_s} s and at most 1 s"),
        |x| x >= step_s && x <= 1.0,
    )?;
    let t_max_s = r.f64_where(
        "t_max_s",
        d.t_max_s,
        &format!("a time of at least step_s = {step_s} s and at most 1e6 s"),
        |x| x >= step_s && x <= 1e6,
    )?;
    let keys: Vec<&str> = Precision::ALL.iter().map(|p| p.key()).collect();
    let precision = Precision::from_key(r.word("precision", d.precision.key(), &keys)?)
        .unwrap_or(Precision::F64);
    r.finish()?;
    Ok(Simulation {
        step_s,
        flight_step_max_s,
        t_max_s,
        precision,
    })
}
