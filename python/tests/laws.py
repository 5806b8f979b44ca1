"""Control laws in Python for the tests, the notebook and the README's measure: the same
law as examples/user_law's `DampThenHold` (Rust), written with numpy."""

import numpy as np

import touchdown


class DampThenHold:
    """Damps the body rates through the fall; once a touchdown switch closes, pushes the
    lander onto the surface with 15 N for 8 s; then it is done (examples/user_law)."""

    def command(self, sensed, memory):
        # memory[:, 0]: when contact was first sensed (0 until then).
        first = sensed.contact & (memory[:, 0] == 0.0)
        memory[first, 0] = sensed.t_s[first]
        falling = memory[:, 0] == 0.0
        holding = ~falling & (sensed.t_s - memory[:, 0] < 8.0)
        n = len(sensed)
        torque = np.zeros((n, 3))
        torque[falling] = -30.0 * sensed.rate_rad_s[falling]
        force = np.zeros((n, 3))
        force[holding, 2] = -15.0
        return touchdown.Command(force_b_n=force, torque_b_n_m=torque, done=~falling & ~holding)
