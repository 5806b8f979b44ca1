//! A control law of your own, run on many touchdowns: this program registers it under a
//! name and then is the `touchdown` command itself, so a scenario can name the law:
//! `cargo run --release -p user_law -- sweep --scenario examples/user-law.toml` (from the
//! repository's root; a crate of its own, so that it builds without touchdown's
//! dev-dependencies).
use glam::DVec3;
use touchdown::control::{LAW_MEMORY, Law, LawCommand, Sensed, register_law};

/// Damps the body rates through the fall; once a touchdown switch closes, pushes the
/// lander onto the surface with 15 N for 8 s; then it is done.
pub struct DampThenHold;

impl Law for DampThenHold {
    fn command(&self, sensed: &[Sensed], memory: &mut [[f64; LAW_MEMORY]], out: &mut [LawCommand]) {
        for ((s, m), c) in sensed.iter().zip(memory).zip(out) {
            // m[0]: when contact was first sensed (0 until then).
            if s.contact && m[0] == 0.0 {
                m[0] = s.t_s;
            }
            if m[0] == 0.0 {
                c.wrench.torque_b_n_m = -30.0 * s.rate_rad_s;
            } else if s.t_s - m[0] < 8.0 {
                c.wrench.force_b_n = DVec3::new(0.0, 0.0, -15.0);
            } else {
                c.done = true;
            }
        }
    }
}

fn main() -> std::process::ExitCode {
    register_law("damp_then_hold", DampThenHold);
    touchdown::commands::main()
}
