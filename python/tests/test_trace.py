"""Traces from Python: the command line's trace file, of a scenario, of a sweep file and of
a sweep table held in memory."""

import pyarrow as pa
import pyarrow.ipc as ipc
import polars as pl
import pytest

import touchdown
from conftest import run


def read_arrow(path):
    with pa.memory_map(str(path)) as source:
        return ipc.open_file(source).read_all()


def test_a_scenarios_sample_is_the_command_lines_trace(cli, tmp_path):
    out = tmp_path / "t.arrow"
    printed = run(cli, "trace", "--sample", "4", "--seed", "9", "--every", "10", "--out", out).stdout
    t = touchdown.trace(touchdown.Scenario.default(), sample=4, seed=9, every=10)
    expected = read_arrow(out)
    assert t.table.schema.equals(expected.schema, check_metadata=True)
    assert t.table.equals(expected)
    # What it prints is the command's printout, less the line naming the file.
    assert printed.startswith(t.text)
    assert t.outcome in {"stable", "tipped", "sliding", "bouncing", "diverged"}


def test_a_sweeps_row_from_its_file_and_from_its_table(cli, tmp_path):
    sweep_file = tmp_path / "s.arrow"
    table = touchdown.sweep(samples=200, seed=2, out=sweep_file, progress=False)
    out = tmp_path / "t.arrow"
    run(cli, "trace", "--sweep", sweep_file, "--sample", "17", "--out", out)
    expected = read_arrow(out)
    assert touchdown.trace(sweep_file, sample=17).table.equals(expected)
    from_table = touchdown.trace(table, sample=17)
    assert from_table.table.equals(expected)
    # The trace ends as its row did.
    assert from_table.outcome == table.column("outcome")[17].as_py()


def test_bad_requests(tmp_path):
    table = touchdown.sweep(samples=20, progress=False)
    with pytest.raises(touchdown.TouchdownError, match="has samples 0 to 19"):
        touchdown.trace(table, sample=20)
    with pytest.raises(touchdown.TouchdownError, match="metadata"):
        touchdown.trace(pl.from_arrow(table), sample=1)
    with pytest.raises(touchdown.TouchdownError, match="seed"):
        touchdown.trace(table, sample=1, seed=3)
    with pytest.raises(ValueError, match="every"):
        touchdown.trace(sample=1, every=0)
