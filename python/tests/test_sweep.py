"""Sweeps from Python: the command line's file, column for column and byte for byte;
tables of inputs from polars and pandas; Ctrl-C; the GIL released."""

import _thread
import threading
import time

import numpy as np
import pandas as pd
import polars as pl
import pyarrow as pa
import pyarrow.ipc as ipc
import pyarrow.parquet as pq
import pytest

import touchdown
from conftest import run


def decoded(table):
    """`table` with each coded (dictionary) column as its texts."""
    plain = [f.with_type(f.type.value_type) if pa.types.is_dictionary(f.type) else f for f in table.schema]
    return table.cast(pa.schema(plain, table.schema.metadata))


def read_arrow(path):
    with pa.memory_map(str(path)) as source:
        return ipc.open_file(source).read_all()


def test_equal_to_the_command_lines_file(cli, tmp_path):
    cli_file = tmp_path / "cli.arrow"
    run(cli, "sweep", "--samples", "3000", "--seed", "11", "--quiet", "--out", cli_file)
    py_file = tmp_path / "py.arrow"
    table = touchdown.sweep(samples=3000, seed=11, out=py_file, progress=False)
    expected = read_arrow(cli_file)
    # Column for column, and the schema's metadata (scenario, seed, engine, units) too.
    assert table.schema.equals(expected.schema, check_metadata=True)
    for name in expected.column_names:
        assert table.column(name).equals(expected.column(name)), name
    # The file written beside it is the command line's, byte for byte.
    assert py_file.read_bytes() == cli_file.read_bytes()
    # polars takes it as it is.
    frame = pl.from_arrow(table)
    assert frame.height == 3000 and frame["outcome"].n_unique() >= 2
    # The outcome is coded (a dictionary of every outcome): a Categorical in polars and a
    # category in pandas, both compared with text as a string column is.
    assert pa.types.is_dictionary(table.schema.field("outcome").type)
    stable = table.column("outcome").to_pylist().count("stable")
    assert frame.schema["outcome"] == pl.Categorical
    assert frame.filter(pl.col("outcome") == "stable").height == stable > 0
    df = pd.read_feather(cli_file)
    assert df["outcome"].dtype == "category" and (df["outcome"] == "stable").sum() == stable
    assert pl.read_parquet(_parquet_of(cli, tmp_path)).filter(pl.col("outcome") == "stable").height == stable


def _parquet_of(cli, tmp_path):
    """The sweep of test_equal_to_the_command_lines_file as Parquet."""
    path = tmp_path / "cli.parquet"
    run(cli, "sweep", "--samples", "3000", "--seed", "11", "--quiet", "--out", path)
    return path


def test_parquet_and_a_scenario_object(cli, tmp_path, root):
    path = root / "scenarios" / "flat.toml"
    cli_file = tmp_path / "cli.parquet"
    run(cli, "sweep", "--scenario", path, "--samples", "500", "--quiet", "--out", cli_file)
    table = touchdown.sweep(touchdown.Scenario.load(path), samples=500, out=tmp_path / "py.parquet", progress=False)
    # Parquet keeps the coded outcome's texts and type; its reader makes the dictionary of
    # the texts each row group holds, so the tables are compared as texts.
    assert decoded(table).equals(decoded(pq.read_table(cli_file)).replace_schema_metadata(table.schema.metadata))
    assert (tmp_path / "py.parquet").read_bytes() == cli_file.read_bytes()


def test_a_changed_scenario_runs_as_its_file(cli, tmp_path):
    s = touchdown.Scenario.default()
    s["surface.friction_coefficient"] = 0.3
    s["inputs.slope_deg"] = {"dist": "uniform", "min": 0.0, "max": 10.0}
    scenario_file = tmp_path / "s.toml"
    scenario_file.write_text(s.to_toml())
    cli_file = tmp_path / "cli.arrow"
    run(cli, "sweep", "--scenario", scenario_file, "--samples", "400", "--quiet", "--out", cli_file)
    table = touchdown.sweep(s, samples=400, progress=False)
    assert table.equals(read_arrow(cli_file))
    assert table.schema.metadata[b"touchdown.scenario"].decode().startswith(s.to_toml()[:40])


@pytest.mark.parametrize("kind", ["polars", "pandas", "pyarrow", "path"])
def test_inputs_from_any_table(cli, tmp_path, kind):
    slopes = np.linspace(0.0, 30.0, 64)
    azimuths = np.linspace(0.0, 180.0, 64)
    frame = pl.DataFrame({"slope_deg": slopes, "downhill_azimuth_deg": azimuths})
    csv = tmp_path / "inputs.csv"
    frame.write_csv(csv)
    cli_file = tmp_path / "cli.arrow"
    run(cli, "sweep", "--inputs", csv, "--quiet", "--out", cli_file)
    given = {
        "polars": frame,
        "pandas": frame.to_pandas(),
        "pyarrow": frame.to_arrow(),
        "path": csv,
    }[kind]
    table = touchdown.sweep(inputs=given, progress=False)
    expected = read_arrow(cli_file)
    # The values are the table's; the metadata names the table's file and digest, which
    # differ for a table held in memory (written to a temporary Arrow file for the run).
    assert table.num_rows == 64
    assert table.column("slope_deg").to_pylist() == slopes.tolist()
    for name in expected.column_names:
        assert table.column(name).equals(expected.column(name)), name


def test_bad_arguments_raise_with_the_command_lines_message(tmp_path):
    with pytest.raises(ValueError, match="samples=0 is out of range: expected a whole number from 1"):
        touchdown.sweep(samples=0, progress=False)
    with pytest.raises(touchdown.TouchdownError, match="contradicts the extension"):
        touchdown.sweep(samples=10, out=tmp_path / "x.parquet", format="arrow", progress=False)
    with pytest.raises(ValueError, match="design"):
        touchdown.sweep(samples=10, design="grid", progress=False)
    with pytest.raises(touchdown.TouchdownError, match="input table"):
        touchdown.sweep(inputs=tmp_path / "missing.csv", progress=False)
    with pytest.raises(TypeError, match="not a table"):
        touchdown.sweep(inputs=42, progress=False)
    assert not list(tmp_path.iterdir())


def test_ctrl_c_stops_the_sweep_and_leaves_nothing_half_written(cli, tmp_path):
    out = tmp_path / "big.arrow"
    # Ctrl-C as the main thread gets it: KeyboardInterrupt, half a second in.
    timer = threading.Timer(0.5, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt) as stopped:
        touchdown.sweep(samples=2_000_000, seed=5, out=out, progress=False)
    timer.cancel()
    # It says where the rows went, and how to go on.
    said = str(stopped.value)
    assert f"samples done, in {tmp_path / 'big.arrow.interrupted'} (a valid file)" in said, said
    assert "--resume" in said, said
    # No file under the name asked for, no temporary file: the rows done are in a valid
    # file under the interrupted sweep's name, which the command line finishes.
    stopped = tmp_path / "big.arrow.interrupted"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["big.arrow.interrupted"]
    done = read_arrow(stopped)
    assert 0 < done.num_rows < 2_000_000
    assert done.column("sample").to_pylist() == list(range(done.num_rows))


def test_ctrl_c_without_a_file(tmp_path):
    timer = threading.Timer(0.3, _thread.interrupt_main)
    timer.start()
    with pytest.raises(KeyboardInterrupt, match="samples done; nothing was kept"):
        touchdown.sweep(samples=2_000_000, progress=False)
    timer.cancel()


def test_the_gil_is_released_while_the_kernels_run():
    ticks = []
    result = {}

    def sweep():
        result["table"] = touchdown.sweep(samples=40_000, threads=1, progress=False)

    worker = threading.Thread(target=sweep)
    worker.start()
    # Python runs beside the sweep: with the GIL held by it, not one tick would pass.
    while worker.is_alive():
        ticks.append(time.perf_counter())
        time.sleep(0.01)
    worker.join()
    assert result["table"].num_rows == 40_000
    assert len(ticks) > 10


def test_counts_as_the_command_line_takes_them():
    # 1e2 as a float is a whole number, as `--samples 1e2` is.
    assert touchdown.sweep(samples=1e2, seed=2.0, progress=False).num_rows == 100
    with pytest.raises(ValueError, match="not a whole number"):
        touchdown.sweep(samples=10.5, progress=False)
    with pytest.raises(TypeError):
        touchdown.sweep(samples=True, progress=False)


def test_a_file_only_sweep_keeps_no_table(cli, tmp_path):
    out = tmp_path / "only.arrow"
    assert touchdown.sweep(samples=1000, seed=3, out=out, table=False, progress=False) is None
    cli_file = tmp_path / "cli.arrow"
    run(cli, "sweep", "--samples", "1000", "--seed", "3", "--quiet", "--out", cli_file)
    assert out.read_bytes() == cli_file.read_bytes()
    with pytest.raises(ValueError, match="give out="):
        touchdown.sweep(samples=10, table=False, progress=False)
