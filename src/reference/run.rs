//! One whole sample: the initial state at the end of the free fall (MODEL.md section 8),
//! then steps until the outcome is decided.

use super::contact::LegState;
use super::model::Model;
use super::outcome::{Summary, Tracker};
use super::rigid_body::Body;
use super::step::{State, StepReport, step, step_size};
use crate::control::{LaneControl, Truth};
use crate::scenario::Sample;
use crate::scenario::Start;
use crate::slope::Surface;
use glam::{DQuat, DVec3};

/// The state at the last moment of the free fall: attitude and velocity against the
/// attitude reference (local vertical, or the surface normal), the fall speed
/// `sqrt(2 g0 h)` plus the velocity errors, and the CG placed on the slope normal through
/// the origin so that the lowest footpad is `clearance_m` above the terrain beneath it.
/// Or, for a start at the release, the same `h` higher along `Z_I` with only the velocity
/// errors: the stepped fall brings it there. Or, with the touchdown state given
/// (`Start::State`), the velocity `-vn n + vt (cos a u + sin a v)` in the surface's frame.
#[must_use]
pub fn initial_state(model: &Model, surface: &Surface, sample: &Sample) -> State {
    let x = &sample.inputs;
    let reference = if model.attitude_surface {
        surface.alignment()
    } else {
        DQuat::IDENTITY
    };
    let attitude = reference
        * from_euler_zyx(
            x.yaw_deg.to_radians(),
            x.pitch_deg.to_radians(),
            x.roll_deg.to_radians(),
        );
    // From the release the fall is stepped; at touchdown it is over, and its speed known;
    // a descent starts higher, moving down, and the law releases the lander.
    let descent = model.control.as_ref().and_then(|m| m.descent_draw(sample));
    let (fall, above) = match (model.start, descent) {
        (Start::Release, _) => (0.0, x.release_height_m),
        (Start::Descent, Some(d)) => (d.start_speed_m_s, d.start_altitude_m),
        _ => ((2.0 * model.gravity_m_s2 * x.release_height_m).sqrt(), 0.0),
    };
    let velocity = if model.start == Start::State {
        // The touchdown state given: towards the surface at `vn`, along it at `vt` in the
        // direction `a` from downhill `u` towards `v` (MODEL.md section 8).
        let [vn, vt, a] = sample.touchdown;
        let (sa, ca) = libm::sincos(a.to_radians());
        -vn * surface.normal + vt * (ca * surface.tangent_u + sa * surface.tangent_v)
    } else {
        reference
            * DVec3::new(
                x.velocity_error_x_m_s,
                x.velocity_error_y_m_s,
                x.velocity_error_z_m_s - fall,
            )
    };
    let rate = DVec3::new(x.rate_x_deg_s, x.rate_y_deg_s, x.rate_z_deg_s) * (1.0f64).to_radians();
    // Height along the normal that puts the lowest footpad `clearance_m` above the terrain
    // (and the rocks on it); the terrain under a footpad does not change as the CG moves
    // along the normal.
    let rocks = model.rock_field();
    let lift = model
        .legs
        .iter()
        .map(|leg| {
            let arm = attitude * leg.tip_m;
            let (h, _, _) = surface.height(model.terrain.as_ref(), arm);
            let rock = rocks.as_ref().map_or(0.0, |f| surface.rock_height(f, arm));
            h + rock - surface.normal.dot(arm)
        })
        .fold(f64::NEG_INFINITY, f64::max);
    State {
        t_s: 0.0,
        t_error_s: 0.0,
        body: Body {
            position_m: surface.normal * (lift + model.clearance_m) + DVec3::Z * above,
            velocity_m_s: velocity,
            attitude,
            rate_rad_s: rate,
        },
        legs: vec![LegState::default(); model.legs.len()],
        thrust: crate::control::Thrust::NONE,
        contact_step_s: model.step_s,
        force_n: DVec3::ZERO,
        moment_n_m: DVec3::ZERO,
        dt_s: 0.0,
    }
}

/// `R = Rz(yaw) Ry(pitch) Rx(roll)` as a quaternion: glam's `DQuat::from_euler(EulerRot::ZYX,
/// ..)`, with the sines and cosines of the `libm` crate (pure Rust, the same bits on every
/// machine) instead of the C library's, which picks other code on CPUs with FMA.
#[must_use]
pub fn from_euler_zyx(yaw: f64, pitch: f64, roll: f64) -> DQuat {
    let (sz, cz) = libm::sincos(yaw * 0.5);
    let (sy, cy) = libm::sincos(pitch * 0.5);
    let (sx, cx) = libm::sincos(roll * 0.5);
    DQuat::from_xyzw(0.0, 0.0, sz, cz)
        * DQuat::from_xyzw(0.0, sy, 0.0, cy)
        * DQuat::from_xyzw(sx, 0.0, 0.0, cx)
}

/// Runs one sample to its outcome, handing every step to `observe` (for traces), with the
/// sample's own parameters where the scenario draws them (`Model::for_sample`).
pub fn run(model: &Model, sample: &Sample, observe: impl FnMut(&StepReport)) -> Summary {
    run_to_end(model, sample, observe).0
}

/// `run`, and the report of the state at the decision: the body after the last step, with
/// the contact forces a next step would start from (a trace's last row).
pub fn run_to_end(
    model: &Model,
    sample: &Sample,
    mut observe: impl FnMut(&StepReport),
) -> (Summary, StepReport) {
    let model = &*model.for_sample(sample);
    let surface = Surface::of(sample);
    let mut state = initial_state(model, &surface, sample);
    let mut tracker = Tracker::new(model, &state);
    let mut report = StepReport::new(model.legs.len());
    let mut control = model
        .control
        .as_ref()
        .map(|m| (m, LaneControl::new(m, sample)));
    if let Some((m, c)) = &mut control {
        state.thrust = c.event(m, &truth_of(&state, &surface, false, false));
    }
    // A footpad touched in some step since the last control event (the touchdown switches).
    let mut touched = false;
    loop {
        let dt = step_size(model, &surface, &state);
        step(model, &surface, &mut state, dt, &mut report);
        let touching = report.legs.iter().any(super::step::LegReport::in_contact);
        touched |= touching;
        if let Some((m, c)) = &control {
            c.report(m, report.control.get_or_insert_with(Default::default));
        }
        observe(&report);
        if let Some(outcome) = tracker.observe(model, &surface, &report, &state) {
            let mut summary = tracker.finish(model, &surface, outcome, &state);
            summary.judge(model);
            if let Some((m, c)) = &mut control {
                summary.control = Some(Box::new(c.finish(m, state.thrust.event_in_s)));
            }
            // One more step of a copy, for what it computed at its start (no step taken
            // from there: length 0, and the strokes of the state itself).
            let mut end = state.clone();
            step(model, &surface, &mut end, model.step_s, &mut report);
            report.dt_s = 0.0;
            for (leg, at) in report.legs.iter_mut().zip(&state.legs) {
                leg.stroke_m = at.stroke_m;
            }
            return (summary, report);
        }
        if let Some((m, c)) = &mut control
            && state.thrust.event_in_s <= 0.0
        {
            state.thrust = c.event(m, &truth_of(&state, &surface, touched, touching));
            touched = false;
        }
    }
}

/// The truth a lander's control loop reads from the reference's state (`contact`: a
/// footpad touched in some step since the loop's last event; `touching`: in the last).
#[must_use]
pub fn truth_of(state: &State, surface: &Surface, contact: bool, touching: bool) -> Truth {
    Truth {
        t_s: state.t_s,
        position_m: state.body.position_m,
        velocity_m_s: state.body.velocity_m_s,
        attitude: state.body.attitude,
        rate_rad_s: state.body.rate_rad_s,
        contact,
        touching,
        normal: surface.normal,
    }
}

#[cfg(test)]
mod tests {
    use super::from_euler_zyx;
    use glam::{DQuat, EulerRot};

    #[test]
    fn euler_angles_turn_as_glam_turns_them() {
        // Only the sines and cosines differ (libm against the C library): within a few
        // rounding errors of glam's quaternion.
        for i in 0..200 {
            let t = f64::from(i);
            let (yaw, pitch, roll) = (t * 0.37 - 30.0, t * 0.21 - 20.0, 17.0 - t * 0.29);
            let ours = from_euler_zyx(yaw, pitch, roll);
            let glam = DQuat::from_euler(EulerRot::ZYX, yaw, pitch, roll);
            let diff = (ours - glam).length().min((ours + glam).length());
            assert!(diff < 1e-15, "{yaw} {pitch} {roll}: {ours} vs {glam}");
        }
    }
}
