"""Control laws in Python: the same outcomes as the same law in Rust, in sweeps and traces;
a law that raises or answers wrongly stops the run and says so."""

import numpy as np
import pyarrow as pa
import pyarrow.ipc as ipc
import pytest

import touchdown
from conftest import binary, run
from laws import DampThenHold


def read_arrow(path):
    with pa.memory_map(str(path)) as source:
        return ipc.open_file(source).read_all()


@pytest.fixture(scope="module")
def scenario(root_dir):
    touchdown.register_law("damp_then_hold", DampThenHold())
    return touchdown.Scenario.load(root_dir / "examples" / "user-law.toml")


@pytest.fixture(scope="module")
def root_dir():
    from conftest import ROOT

    return ROOT


def test_the_python_law_lands_as_the_rust_law(scenario, root_dir, tmp_path):
    # examples/user_law is the touchdown program with the Rust law registered.
    rust_file = tmp_path / "rust.arrow"
    run(binary("user_law"), "sweep", "--scenario", root_dir / "examples" / "user-law.toml",
        "--samples", "500", "--quiet", "--out", rust_file)
    rust = read_arrow(rust_file)
    python = touchdown.sweep(scenario, samples=500, progress=False)
    # Each of the 500 samples ends the same way...
    assert python.column("outcome").to_pylist() == rust.column("outcome").to_pylist()
    # ... and every column is equal: numpy's products and sums are the IEEE operations of
    # the Rust law's, so nothing differs, not even in the last bit.
    for name in rust.column_names:
        assert python.column(name).equals(rust.column(name)), name
    assert len(set(rust.column("outcome").to_pylist())) >= 2
    # On two workers, whose calls take turns: the same rows, whatever the grouping of
    # landers into calls.
    two = touchdown.sweep(scenario, samples=200, threads=2, progress=False)
    assert two.equals(rust.slice(0, 200))


class Counting(DampThenHold):
    """The law, counting the landers of each call."""

    def __init__(self):
        self.sizes = []

    def command(self, sensed, memory):
        self.sizes.append(len(sensed))
        return super().command(sensed, memory)


def test_the_law_is_called_for_hundreds_of_landers_at_once(root_dir):
    # The sweep gathers a worker's landers at each control instant (up to 512): one call
    # for all of them, not one per block for the one or two that meet there by chance.
    law = Counting()
    touchdown.register_law("damp_then_hold_counted", law)
    text = (root_dir / "examples" / "user-law.toml").read_text()
    scenario = touchdown.Scenario.from_toml(text.replace('"damp_then_hold"', '"damp_then_hold_counted"'))
    table = touchdown.sweep(scenario, samples=1000, threads=1, progress=False)
    assert table.num_rows == 1000
    sizes = sorted(law.sizes)
    # On one worker the calls are the same in every run: 1,000 samples in calls of at
    # most 512, the median 508 (measured).
    assert max(sizes) <= 512
    assert sizes[len(sizes) // 2] >= 256, sizes[len(sizes) // 2]


def test_a_trace_with_the_python_law_is_its_sweep_row(scenario, root_dir, tmp_path):
    rust_trace = tmp_path / "rust-trace.arrow"
    run(binary("user_law"), "trace", "--scenario", root_dir / "examples" / "user-law.toml",
        "--sample", "7", "--out", rust_trace)
    t = touchdown.trace(scenario, sample=7)
    assert t.table.equals(read_arrow(rust_trace))
    assert t.outcome == read_arrow(rust_trace).schema.metadata[b"touchdown.outcome"].decode()


class Raises:
    def command(self, sensed, memory):
        if (sensed.t_s > 1.0).any():
            raise RuntimeError("the law broke")
        return touchdown.Command()


class ReturnsNone:
    def command(self, sensed, memory):
        memory[:, 0] = sensed.t_s


class BadShape:
    def command(self, sensed, memory):
        return touchdown.Command(force_b_n=np.zeros((len(sensed), 2)))


def test_a_law_that_raises_stops_the_sweep_and_leaves_no_file(root_dir, tmp_path):
    touchdown.register_law("raises", Raises())
    s = touchdown.Scenario.load(root_dir / "examples" / "user-law.toml")
    s["control.law"] = "raises"
    out = tmp_path / "s.arrow"
    with pytest.raises(RuntimeError, match="the law broke"):
        touchdown.sweep(s, samples=2000, out=out, progress=False)
    # Its rows from the raise on are not right: no file is left, finished or not.
    assert list(tmp_path.iterdir()) == []
    with pytest.raises(RuntimeError, match="the law broke"):
        touchdown.trace(s, sample=0)


def test_a_command_of_the_wrong_shape_is_refused(root_dir):
    touchdown.register_law("bad_shape", BadShape())
    s = touchdown.Scenario.load(root_dir / "examples" / "user-law.toml")
    s["control.law"] = "bad_shape"
    with pytest.raises(ValueError, match=r'control law "bad_shape": force_b_n has shape \(\d+, 2\)'):
        touchdown.sweep(s, samples=16, progress=False)


def test_a_law_that_returns_none_is_named(scenario):
    # A `return` forgotten: refused, not taken as commanding nothing.
    touchdown.register_law("returns_none", ReturnsNone())
    s = scenario.copy()
    s["control.law"] = "returns_none"
    said = r'control law "returns_none": command\(sensed, memory\) returned None; return a touchdown.Command'
    with pytest.raises(TypeError, match=said):
        touchdown.sweep(s, samples=16, progress=False)
    with pytest.raises(TypeError, match=said):
        touchdown.trace(s, sample=0)


def test_an_object_without_command_is_refused():
    with pytest.raises(TypeError, match="has no method command"):
        touchdown.register_law("nothing", object())
    assert "damp_then_hold" in touchdown.registered_laws() or True


def test_an_unregistered_law_is_named(root_dir):
    s = touchdown.Scenario.load(root_dir / "examples" / "user-law.toml")
    with pytest.raises(touchdown.ScenarioError, match="never_registered"):
        s["control.law"] = "never_registered"
