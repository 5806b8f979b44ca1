//! One lander's control loop, event by event: its sampled thruster errors, sensor biases and
//! law parameters, the latency queue of its commands, the phase it is in, and the thrust it
//! gets until its next event. The kernels' lanes and the scalar reference both run it.

use super::allocation::{Wrench, quantise_carrying};
use super::laws::{
    DescentDraw, LAW_MEMORY, LawCommand, attitude_torque, descent_force, tilted_past,
};
use super::model::ControlModel;
use super::noise::{normal, normal3, small_rotation, truncated};
use super::sensors::{Sensed, Truth};
use super::thrust::Thrust;
use crate::rng::stream;
use crate::scenario::{MAX_THRUSTERS, Sample, Target};
use glam::DVec3;
use rand_xoshiro::Xoshiro256PlusPlus;

/// The phase of a lander's control loop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Phase {
    /// From a descent start until the descent law releases the lander (or contact is
    /// sensed first): braking, and attitude hold if any.
    Descent,
    /// Before contact is sensed: attitude hold, if any.
    Fall,
    /// Hold-down since the instant at `since_s`, at rest (sensed) for `rest_s`.
    HoldDown {
        /// The control instant contact was first sensed (flight computer's clock), s.
        since_s: f64,
        /// How long the sensors have read the lander at rest without a break, s.
        rest_s: f64,
    },
    /// The user's law commands (until it says it is done).
    User,
    /// Nothing more to fire.
    Done,
}

/// A command: every thruster's on-time in its period, and whether it holds down (the
/// built-in hold-down's, or a user's law's push along -Z_B after contact was sensed).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Command {
    on_s: [f64; MAX_THRUSTERS],
    hold_down: bool,
}

const IDLE: Command = Command {
    on_s: [0.0; MAX_THRUSTERS],
    hold_down: false,
};

/// What a lander's control loop did, for its row of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ControlSummary {
    /// Propellant used: the thrust's integral over `isp g0`, kg.
    pub propellant_kg: f64,
    /// Sum of every thruster's time on, s.
    pub on_time_s: f64,
    /// Firings: a thruster on in a control period counts once.
    pub firings: u32,
    /// Integral of the thrust magnitude of the thrusters fired by hold-down commands, N s:
    /// the built-in `hold_down`'s, and a user's law's that ask for a force along -Z_B
    /// once contact has been sensed.
    pub hold_down_impulse_n_s: f64,
    /// The sample's drawn hold-down thrust (NaN without `hold_down`; so are the other
    /// drawn law parameters without their law).
    pub hold_down_thrust_n: f64,
    /// The sample's drawn hold-down duration.
    pub hold_down_duration_s: f64,
    /// The sample's drawn attitude-hold proportional gain.
    pub kp_n_m_per_rad: f64,
    /// The sample's drawn attitude-hold rate gain.
    pub kd_n_m_s_per_rad: f64,
    /// When the descent law released the lander, s (NaN: never released, or no descent;
    /// so are the release's state below).
    pub release_time_s: f64,
    /// Height of the footpads at the release: the true CG altitude above the surface
    /// plane less the footpads' depth below the CG.
    pub release_altitude_m: f64,
    /// True CG velocity in I at the release, m/s.
    pub release_velocity_m_s: [f64; 3],
    /// True body rates in B at the release, rad/s.
    pub release_rate_rad_s: [f64; 3],
    /// True `X_B` and `Z_B` in I at the release.
    pub release_axes: [[f64; 3]; 2],
    /// The sample's drawn descent (none without one).
    pub descent: Option<DescentDraw>,
}

/// One lander's control loop: its sampled thruster errors, sensor biases and law
/// parameters, its noise generator, and where it stands in its period.
#[derive(Debug, Clone)]
pub struct LaneControl {
    /// Each thruster's force on the lander as built (errors included), B, N.
    force_b_n: Vec<DVec3>,
    /// Its moment about the CG, B, N m.
    moment_b_n_m: Vec<DVec3>,
    noise: Xoshiro256PlusPlus,
    attitude_bias_rad: DVec3,
    rate_bias_rad_s: DVec3,
    velocity_bias_m_s: DVec3,
    altitude_bias_m: f64,
    phase: Phase,
    /// Commands issued and not yet applied, oldest first (`latency_periods` of them).
    queue: Vec<Command>,
    /// The command of the current period.
    current: Command,
    /// Time left in the current period, s.
    period_left_s: f64,
    /// Time each thruster still fires in it, s.
    on_left_s: [f64; MAX_THRUSTERS],
    /// What each thruster's commands asked of it and quantisation left unfired (negative:
    /// fired beyond), carried into its next command, s.
    carry_s: [f64; MAX_THRUSTERS],
    /// The length of the segment under way (from the last event to the next), s.
    segment_s: f64,
    /// Thrust magnitude summed over the thrusters firing in it, N.
    flow_n: f64,
    firing: u32,
    powered: bool,
    /// Thrust integral so far, N s.
    impulse_n_s: f64,
    /// What the sensors read at the last control instant.
    last_sensed: Option<Sensed>,
    /// A touchdown switch closed since the last control instant (latched until read).
    switch_closed: bool,
    /// The sample's release height, m: where the descent law releases the lander.
    release_height_m: f64,
    /// Whether the event under way is a control instant (`begin` to `end`).
    instant_due: bool,
    /// Control instants so far.
    instants: u64,
    /// The user's law's memory for this lander.
    memory: [f64; LAW_MEMORY],
    /// Which thrusters fire in the segment under way.
    firing_now: [bool; MAX_THRUSTERS],
    /// Whether the sensors have read contact at an instant of the user's law's phase.
    touched: bool,
    /// What the loop did so far (`finish` adds the propellant).
    summary: ControlSummary,
}

/// What a lander's control loop is doing during one step, for traces.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ControlReport {
    /// What the sensors read at the last control instant (`None` before the first).
    pub sensed: Option<Sensed>,
    /// The on-time of every thruster in the current period, s.
    pub commanded_on_s: Vec<f64>,
    /// The thrust of every thruster during the step (as built: errors included), N.
    pub thrust_n: Vec<f64>,
    /// The phase of the loop: "descent", "fall", "hold_down", "user" or "done".
    pub phase: &'static str,
}

/// Below this, what is left of a period or an on-time is the rounding of differences of
/// the same times, not time, s.
const TIME_DUST_S: f64 = 1e-12;

impl LaneControl {
    /// The control loop of `sample`: its thruster errors and sensor biases drawn from
    /// streams of its own, its law parameters the sample's (`Sample::law`).
    #[must_use]
    pub fn new(m: &ControlModel, sample: &Sample) -> LaneControl {
        let seed = sample.seed;
        let mut errors = stream(seed, "thrusters");
        let (mut force_b_n, mut moment_b_n_m) = (Vec::new(), Vec::new());
        for t in &m.thrusters {
            let magnitude = t.max_thrust_n * (1.0 + truncated(&mut errors, m.thrust_error_sd));
            let d = DVec3::from_array(t.direction);
            let (a, b) = d.any_orthonormal_pair();
            let tilt = a * truncated(&mut errors, m.misalignment_sd_rad)
                + b * truncated(&mut errors, m.misalignment_sd_rad);
            let f = (small_rotation(tilt) * d) * magnitude;
            force_b_n.push(f);
            moment_b_n_m.push(DVec3::from_array(t.position_m).cross(f));
        }
        let s = &m.config.sensors;
        let mut bias = stream(seed, "sensor_bias");
        let attitude_bias_rad = normal3(&mut bias, s.attitude_bias_deg.to_radians());
        let rate_bias_rad_s = normal3(&mut bias, s.rate_bias_deg_s.to_radians());
        let velocity_bias_m_s = normal3(&mut bias, s.velocity_bias_m_s);
        let altitude_bias_m = normal(&mut bias, s.altitude_bias_m);
        let nan = f64::NAN;
        // The sample's law parameters (`Sample::law`), NaN in its summary where the law is
        // not given.
        let [thrust, duration, kp, kd, ..] = sample.law;
        let (hold_down_thrust_n, hold_down_duration_s) = m
            .config
            .hold_down
            .map_or((nan, nan), |_| (thrust, duration));
        let (kp_n_m_per_rad, kd_n_m_s_per_rad) =
            m.config.attitude_hold.map_or((nan, nan), |_| (kp, kd));
        LaneControl {
            force_b_n,
            moment_b_n_m,
            noise: stream(seed, "sensor_noise"),
            attitude_bias_rad,
            rate_bias_rad_s,
            velocity_bias_m_s,
            altitude_bias_m,
            phase: if m.law.is_some() {
                Phase::User
            } else if m.config.descent.is_some() {
                Phase::Descent
            } else {
                Phase::Fall
            },
            queue: Vec::with_capacity(m.config.latency_periods as usize + 1),
            current: IDLE,
            period_left_s: 0.0,
            on_left_s: [0.0; MAX_THRUSTERS],
            carry_s: [0.0; MAX_THRUSTERS],
            segment_s: 0.0,
            flow_n: 0.0,
            firing: 0,
            powered: true,
            impulse_n_s: 0.0,
            last_sensed: None,
            switch_closed: false,
            release_height_m: sample.inputs.release_height_m,
            instant_due: false,
            instants: 0,
            memory: [0.0; LAW_MEMORY],
            firing_now: [false; MAX_THRUSTERS],
            touched: false,
            summary: ControlSummary {
                hold_down_thrust_n,
                hold_down_duration_s,
                kp_n_m_per_rad,
                kd_n_m_s_per_rad,
                release_time_s: nan,
                release_altitude_m: nan,
                release_velocity_m_s: [nan; 3],
                release_rate_rad_s: [nan; 3],
                release_axes: [[nan; 3]; 2],
                descent: m.descent_draw(sample),
                ..ControlSummary::default()
            },
        }
    }

    /// The phase the loop is in.
    #[must_use]
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// What the loop is doing in the segment under way, into `out` (for traces).
    pub fn report(&self, m: &ControlModel, out: &mut ControlReport) {
        let n = m.thrusters.len();
        out.sensed = self.last_sensed;
        out.commanded_on_s.clear();
        out.commanded_on_s
            .extend_from_slice(&self.current.on_s[..n]);
        out.thrust_n.clear();
        out.thrust_n.extend((0..n).map(|j| {
            if self.powered && self.firing_now[j] {
                self.force_b_n[j].length()
            } else {
                0.0
            }
        }));
        out.phase = match self.phase {
            Phase::Descent => "descent",
            Phase::Fall => "fall",
            Phase::HoldDown { .. } => "hold_down",
            Phase::User => "user",
            Phase::Done => "done",
        };
    }

    /// Takes in the event that ended the segment under way (or starts the loop: the first
    /// call, at `t = 0`) and returns the thrust until the next event: `begin`, the user's
    /// law for this lander alone where `begin` asks for it, and `end`.
    pub fn event(&mut self, m: &ControlModel, truth: &Truth) -> Thrust {
        let mut command = LawCommand::default();
        let asked = self.begin(m, truth).map(|sensed| {
            if let Some(law) = &m.law {
                law.law.command(
                    std::slice::from_ref(&sensed),
                    std::slice::from_mut(&mut self.memory),
                    std::slice::from_mut(&mut command),
                );
            }
        });
        self.end(m, truth, asked.map(|()| &command))
    }

    /// The first half of `event`: accounts for the segment that ended and, at a control
    /// instant, reads the sensors. Returns the reading where the user's law must command
    /// (`Law::command`, with `memory()`), for `end` to take its command.
    pub fn begin(&mut self, m: &ControlModel, truth: &Truth) -> Option<Sensed> {
        self.instant_due = false;
        if !self.powered {
            return None;
        }
        self.switch_closed |= truth.contact;
        let elapsed = self.segment_s;
        self.spend(elapsed);
        self.period_left_s -= elapsed;
        let n = m.thrusters.len();
        for on in &mut self.on_left_s[..n] {
            *on -= elapsed.min(*on);
            if *on < TIME_DUST_S {
                *on = 0.0;
            }
        }
        if self.period_left_s >= TIME_DUST_S {
            return None;
        }
        self.instant_due = true;
        let sensed = self.sense(m, truth);
        self.switch_closed = false;
        self.last_sensed = Some(sensed);
        (m.law.is_some() && self.phase == Phase::User).then_some(sensed)
    }

    /// This lander's memory for the user's law (zero at the start of its sample).
    pub fn memory(&mut self) -> &mut [f64; LAW_MEMORY] {
        &mut self.memory
    }

    /// The second half of `event`: at a control instant, the command (the user's law's,
    /// `user`, where `begin` asked for one), and the thrust until the next event.
    pub fn end(&mut self, m: &ControlModel, truth: &Truth, user: Option<&LawCommand>) -> Thrust {
        if !self.powered {
            return Thrust::NONE;
        }
        let n = m.thrusters.len();
        if self.instant_due {
            self.instant(m, truth, user);
        }
        let mut segment = self.period_left_s;
        let (mut force, mut moment, mut flow, mut firing) = (DVec3::ZERO, DVec3::ZERO, 0.0, 0);
        for j in 0..n {
            let on = self.on_left_s[j];
            self.firing_now[j] = on > 0.0;
            if on > 0.0 {
                segment = segment.min(on);
                force += self.force_b_n[j];
                moment += self.moment_b_n_m[j];
                flow += self.force_b_n[j].length();
                firing += 1;
            }
        }
        self.flow_n = flow;
        self.firing = firing;
        let idle = firing == 0
            && self.phase == Phase::Done
            && self
                .queue
                .iter()
                .all(|c| c.on_s[..n].iter().all(|&t| t == 0.0));
        if idle {
            self.powered = false;
            self.segment_s = 0.0;
            return Thrust::NONE;
        }
        self.segment_s = segment;
        Thrust {
            force_b_n: force,
            moment_b_n_m: moment,
            event_in_s: segment,
            approach_m_s: (force.length() / m.mass_kg
                + moment.length() / m.inertia_min_kg_m2 * m.leg_reach_m)
                * m.flight_step_max_s,
            powered: true,
            flow_n: flow,
        }
    }

    /// Accounts for `elapsed` of the segment under way.
    fn spend(&mut self, elapsed: f64) {
        let impulse = self.flow_n * elapsed;
        self.impulse_n_s += impulse;
        self.summary.on_time_s += f64::from(self.firing) * elapsed;
        if self.current.hold_down {
            self.summary.hold_down_impulse_n_s += impulse;
        }
    }

    /// Closes the books at the decision, `event_in_s` before the event the segment under
    /// way was heading for; returns the summary, propellant in kg.
    #[must_use]
    pub fn finish(&mut self, m: &ControlModel, event_in_s: f64) -> ControlSummary {
        if self.powered {
            let elapsed = (self.segment_s - event_in_s).clamp(0.0, self.segment_s);
            self.spend(elapsed);
        }
        let mut s = self.summary;
        s.propellant_kg = self.impulse_n_s / m.exhaust_speed_m_s;
        s
    }

    /// A control instant: read the sensors, advance the phase, issue a command, and start
    /// the period of the command whose latency has passed.
    fn instant(&mut self, m: &ControlModel, truth: &Truth, user: Option<&LawCommand>) {
        let c = &m.config;
        let sensed = self.last_sensed.expect("begin read the sensors");
        let t = sensed.t_s;
        if self.phase == Phase::Descent && !sensed.contact {
            let d = self.summary.descent.expect("a descent phase has its law");
            let height = sensed.altitude_m - m.footpad_depth_m;
            let approach = truth.normal.dot(sensed.velocity_m_s);
            if height <= self.release_height_m && approach.abs() < d.release_speed_m_s {
                self.phase = Phase::Fall;
                // The release ends the burn at once: its commands still in the latency
                // queue are dropped, and so is the rounding its thrusters carried (owed
                // to the burn's commands, it would fire after the release), so the free
                // fall starts from the state recorded here.
                self.queue.clear();
                self.carry_s = [0.0; MAX_THRUSTERS];
                let s = &mut self.summary;
                s.release_time_s = truth.t_s;
                s.release_altitude_m = truth.normal.dot(truth.position_m) - m.footpad_depth_m;
                s.release_velocity_m_s = truth.velocity_m_s.to_array();
                s.release_rate_rad_s = truth.rate_rad_s.to_array();
                s.release_axes = [DVec3::X, DVec3::Z].map(|a| (truth.attitude * a).to_array());
            }
        }
        if matches!(self.phase, Phase::Descent | Phase::Fall) && sensed.contact {
            let (thrust, duration) = (
                self.summary.hold_down_thrust_n,
                self.summary.hold_down_duration_s,
            );
            self.phase = if c.hold_down.is_some() && thrust > 0.0 && duration > 0.0 {
                Phase::HoldDown {
                    since_s: t,
                    rest_s: 0.0,
                }
            } else {
                Phase::Done
            };
        }
        if let Phase::HoldDown { since_s, rest_s } = self.phase {
            let at_rest = sensed.velocity_m_s.length() < m.rest_speed_m_s
                && sensed.rate_rad_s.length() < m.rest_rate_rad_s;
            let rest_s = if at_rest { rest_s + m.period_s } else { 0.0 };
            let until_rest = c.hold_down.is_some_and(|h| h.until_rest);
            let tilted = c.hold_down.and_then(|h| h.stop_tilt_deg);
            let tilted = tilted.is_some_and(|limit| tilted_past(&sensed, truth.normal, limit));
            // Periods are counted from the instant contact was sensed: `duration` asks for
            // that many periods' worth (the last one whole).
            let periods = (self.summary.hold_down_duration_s / m.period_s - 1e-9).ceil();
            let done_s = since_s + periods * m.period_s;
            self.phase = if t >= done_s - 0.5 * m.period_s
                || (until_rest && rest_s >= m.hold_time_s - 1e-9)
                || tilted
            {
                Phase::Done
            } else {
                Phase::HoldDown { since_s, rest_s }
            };
        }
        let (wrench, hold_down) = match self.phase {
            Phase::User => {
                let command = user.copied().unwrap_or_default();
                if command.done {
                    self.phase = Phase::Done;
                }
                // A user's law holds down where it asks for a force along -Z_B once contact
                // has been sensed: its impulse counts as the built-in hold_down's.
                self.touched |= sensed.contact;
                (
                    command.wrench,
                    self.touched && command.wrench.force_b_n.z < 0.0,
                )
            }
            Phase::Descent => (self.descent(m, &sensed, truth.normal), false),
            Phase::Fall => (self.attitude_hold(m, &sensed, truth.normal), false),
            Phase::HoldDown { .. } => (
                Wrench {
                    force_b_n: DVec3::new(0.0, 0.0, -self.summary.hold_down_thrust_n),
                    torque_b_n_m: DVec3::ZERO,
                },
                true,
            ),
            Phase::Done => (Wrench::default(), false),
        };
        let mut command = IDLE;
        command.hold_down = hold_down;
        let n = m.thrusters.len();
        if wrench != Wrench::default() {
            m.allocation.duties(&wrench, &mut command.on_s[..n]);
        }
        // Each thruster carries what quantisation left over to its next command, so that
        // over the periods it fires what was asked (a couple's two thrusters, asked alike,
        // fire alike: no net force).
        for ((on, carry), t) in command.on_s[..n]
            .iter_mut()
            .zip(&mut self.carry_s[..n])
            .zip(&m.thrusters)
        {
            (*on, *carry) =
                quantise_carrying(*on * m.period_s, *carry, t.min_on_time_s, m.period_s);
        }
        self.queue.push(command);
        self.current = if self.queue.len() > c.latency_periods as usize {
            self.queue.remove(0)
        } else {
            IDLE
        };
        self.on_left_s[..n].copy_from_slice(&self.current.on_s[..n]);
        self.summary.firings += self.current.on_s[..n].iter().filter(|&&t| t > 0.0).count() as u32;
        self.period_left_s = m.period_s;
    }

    /// The sensors' reading of `truth`: bias and a fresh draw of noise on every quantity.
    fn sense(&mut self, m: &ControlModel, truth: &Truth) -> Sensed {
        let s = &m.config.sensors;
        let r = &mut self.noise;
        let attitude_error = self.attitude_bias_rad + normal3(r, s.attitude_noise_deg.to_radians());
        let rate =
            truth.rate_rad_s + self.rate_bias_rad_s + normal3(r, s.rate_noise_deg_s.to_radians());
        let velocity =
            truth.velocity_m_s + self.velocity_bias_m_s + normal3(r, s.velocity_noise_m_s);
        let altitude = truth.normal.dot(truth.position_m)
            + self.altitude_bias_m
            + normal(r, s.altitude_noise_m);
        // The flight computer's clock: instant k is at k periods, the same in every
        // precision (the true time of the step that reached it differs by roundings).
        let t_s = self.instants as f64 * m.period_s;
        self.instants += 1;
        Sensed {
            t_s,
            attitude: truth.attitude * small_rotation(attitude_error),
            rate_rad_s: rate,
            velocity_m_s: velocity,
            altitude_m: altitude,
            contact: self.switch_closed,
            touching: truth.touching,
        }
    }

    /// The descent's wrench: `descent_force`, and `attitude_hold`'s torque if the loop has
    /// it.
    fn descent(&self, m: &ControlModel, sensed: &Sensed, normal: DVec3) -> Wrench {
        let d = self.summary.descent.expect("a descent phase has its law");
        Wrench {
            force_b_n: descent_force(
                &d,
                m.mass_kg,
                m.gravity_m_s2,
                sensed.altitude_m - m.footpad_depth_m,
                self.release_height_m,
                sensed,
                normal,
            ),
            ..self.attitude_hold(m, sensed, normal)
        }
    }

    /// `attitude_hold`'s wrench, with this sample's gains (`attitude_torque`).
    fn attitude_hold(&self, m: &ControlModel, sensed: &Sensed, normal: DVec3) -> Wrench {
        let Some(a) = &m.config.attitude_hold else {
            return Wrench::default();
        };
        let target = match a.target {
            Target::Vertical => DVec3::Z,
            Target::Normal => normal,
        };
        Wrench {
            force_b_n: DVec3::ZERO,
            torque_b_n_m: attitude_torque(
                self.summary.kp_n_m_per_rad,
                self.summary.kd_n_m_s_per_rad,
                a.deadband_deg.to_radians(),
                sensed.attitude,
                sensed.rate_rad_s,
                target,
            ),
        }
    }
}
