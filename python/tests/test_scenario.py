"""Scenarios from Python: read, set by dotted keys, refused with the command line's
message."""

import numpy as np
import pytest

import touchdown
from conftest import run


def test_default_is_the_command_lines(cli):
    s = touchdown.Scenario.default()
    # The text is the one `touchdown scenario` prints, comments and all.
    assert s.to_toml() == run(cli, "scenario").stdout
    assert s["surface.friction_coefficient"] == 0.6
    assert "lander.mass_kg" in s.keys()


def test_load_from_toml_and_round_trip(tmp_path, root):
    s = touchdown.Scenario.load(root / "scenarios" / "hold-down.toml")
    assert s["control.rate_hz"] == 10.0
    again = touchdown.Scenario.from_toml(s.to_toml())
    assert again == s


def test_set_a_key_and_a_distribution():
    s = touchdown.Scenario.default()
    s["surface.friction_coefficient"] = 0.4
    assert s["surface.friction_coefficient"] == 0.4
    s["inputs.slope_deg"] = {"dist": "uniform", "min": 0.0, "max": 12.5}
    assert s["inputs.slope_deg"] == {"dist": "uniform", "min": 0.0, "max": 12.5}
    # numpy's scalars are numbers too.
    s["lander.mass_kg"] = np.float64(90.0)
    s["samples"] = np.int64(500)
    assert s["lander.mass_kg"] == 90.0 and s["samples"] == 500
    # The changed scenario reads back as itself.
    assert touchdown.Scenario.from_toml(s.to_toml()) == s


def test_a_thruster_by_its_index(root):
    s = touchdown.Scenario.load(root / "scenarios" / "hold-down.toml")
    s["thrusters.2.min_on_time_s"] = 0.03
    assert s["thrusters.2.min_on_time_s"] == 0.03
    with pytest.raises(touchdown.ScenarioError, match="no index 99"):
        s["thrusters.99.max_thrust_n"] = 1.0


def cli_error(cli, tmp_path, text):
    """What the command line says of a scenario file with `text` (exit 2)."""
    path = tmp_path / "bad.toml"
    path.write_text(text)
    done = run(cli, "sweep", "--scenario", path, "--samples", "1", "--out", tmp_path / "x.arrow", check=False)
    assert done.returncode == 2, done.stderr
    prefix = "touchdown: error: "
    assert done.stderr.startswith(prefix), done.stderr
    return done.stderr[len(prefix):].strip()


def test_a_bad_key_raises_the_command_lines_message(cli, tmp_path):
    s = touchdown.Scenario.default()
    before = s.to_toml()
    with pytest.raises(touchdown.ScenarioError) as raised:
        s["surface.friction_coefficent"] = 0.4
    assert str(raised.value) == cli_error(cli, tmp_path, "[surface]\nfriction_coefficent = 0.4\n")
    assert "did you mean" in str(raised.value)
    # The scenario is as it was.
    assert s.to_toml() == before
    with pytest.raises(touchdown.ScenarioError) as raised:
        touchdown.Scenario.from_toml("[surface]\nfriction_coefficent = 0.4\n")
    assert str(raised.value) == cli_error(cli, tmp_path, "[surface]\nfriction_coefficent = 0.4\n")


def test_a_bad_value_raises_the_command_lines_message(cli, tmp_path):
    s = touchdown.Scenario.default()
    with pytest.raises(touchdown.ScenarioError) as raised:
        s["lander.mass_kg"] = -5.0
    message = str(raised.value)
    assert "lander.mass_kg" in message and "-5" in message
    # The same message as the command line gives for a file with that value.
    assert message == cli_error(cli, tmp_path, "[lander]\nmass_kg = -5.0\n")
    # ScenarioError is a ValueError, for code that catches those.
    assert isinstance(raised.value, ValueError)


def test_other_bad_input(tmp_path):
    s = touchdown.Scenario.default()
    with pytest.raises(TypeError, match="not a value of a scenario"):
        s["lander.mass_kg"] = object()
    with pytest.raises(KeyError):
        touchdown.Scenario.from_toml("")["lander.mass_kg"]
    with pytest.raises(OSError, match="cannot read scenario file"):
        touchdown.Scenario.load(tmp_path / "missing.toml")
    with pytest.raises(touchdown.ScenarioError, match="not valid TOML"):
        touchdown.Scenario.from_toml("[lander\n")


def test_help_and_hints():
    assert touchdown.__version__ == touchdown.ENGINE.split()[-1]
    assert "dotted" in touchdown.Scenario.__doc__
    assert touchdown.sweep.__doc__ and "pyarrow.Table" in touchdown.sweep.__doc__
    assert "pa.Table" in touchdown.sweep.__annotations__["return"]


def test_a_key_removed_takes_its_default_again():
    s = touchdown.Scenario.default()
    s["surface.friction_coefficient"] = 0.3
    del s["surface.friction_coefficient"]
    assert "surface.friction_coefficient" not in s
    with pytest.raises(KeyError):
        del s["surface.friction_coefficient"]
    # The default holds: a sweep runs as the default scenario with the key at 0.6 does.
    again = touchdown.Scenario.default()
    again["surface.friction_coefficient"] = 0.6
    assert touchdown.sweep(s, samples=50, progress=False).equals(touchdown.sweep(again, samples=50, progress=False))
