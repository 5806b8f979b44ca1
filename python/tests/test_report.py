"""Reports from Python: the command line's numbers, as data, of a file or of a table."""

import json

import polars as pl
import pytest

import touchdown
from conftest import run


def test_the_report_is_the_command_lines(cli, tmp_path):
    path = tmp_path / "s.arrow"
    table = touchdown.sweep(samples=2000, seed=4, out=path, progress=False)
    expected = json.loads(run(cli, "report", path, "--json").stdout)
    assert touchdown.report(path) == expected
    from_table = touchdown.report(table)
    # The same numbers; only the provenance says it was held in memory.
    assert from_table.pop("provenance")["in_memory"] is True
    expected.pop("provenance")
    assert from_table == expected
    stable = expected["outcomes"]["stable"]
    assert stable["count"] == table.column("outcome").to_pylist().count("stable")
    assert stable["share"] == stable["count"] / 2000
    assert run(cli, "report", path).stdout == touchdown.report_markdown(path)


def test_weighed_onto_a_terrain(cli, tmp_path):
    path = tmp_path / "s.arrow"
    touchdown.sweep(samples=1000, out=path, progress=False)
    expected = json.loads(run(cli, "report", path, "--json", "--slope-distribution", "rayleigh:12").stdout)
    assert touchdown.report(path, slope_distribution="rayleigh:12") == expected
    assert expected["terrain"] is not None
    with pytest.raises(touchdown.TouchdownError, match="slope"):
        touchdown.report(path, slope_distribution="banana:3")


def test_a_frame_without_the_metadata_is_refused():
    table = touchdown.sweep(samples=50, progress=False)
    with pytest.raises(touchdown.TouchdownError, match="metadata"):
        touchdown.report(pl.from_arrow(table))
