#!/usr/bin/env python3
"""Checks that a touchdown sweep file (Arrow IPC or Parquet) reads in the Python tools people use.

usage: check_sweep.py FILE FORMAT ROWS SEED LEGS COUNTS_JSON

FORMAT is `arrow` or `parquet`; COUNTS_JSON is an object of outcome -> count, as the
sweep's closing summary printed them (e.g. '{"stable": 3, "tipped": 97, ...}').

Opens FILE with pyarrow, and with pandas.read_feather and polars.read_ipc (Arrow) or
pandas.read_parquet and polars.read_parquet (Parquet), and checks in each the row count,
that `sample` is exactly 0..ROWS-1 in order, that the outcome counts are COUNTS_JSON; in
the schema, that every field carries a `unit` in its metadata, the provenance in the schema
metadata (engine, seed, scenario, samples), the input columns and the per-leg columns.
Exits 0 when all holds, 1 with every failure listed otherwise, 2 on bad usage.
"""

import json
import math
import sys

import pandas
import polars
import pyarrow
import pyarrow.ipc
import pyarrow.parquet

try:
    import tomllib  # Python 3.11+
except ImportError:  # pragma: no cover
    tomllib = None

REQUIRED_METADATA = (
    "touchdown.engine",
    "touchdown.seed",
    "touchdown.scenario",
    "touchdown.samples",
)
OUTCOMES = ("stable", "tipped", "sliding", "bouncing", "diverged", "held")
INPUTS = (
    "slope_deg",
    "downhill_azimuth_deg",
    "release_height_m",
    "velocity_error_x_m_s",
    "velocity_error_y_m_s",
    "velocity_error_z_m_s",
    "roll_deg",
    "pitch_deg",
    "yaw_deg",
    "rate_x_deg_s",
    "rate_y_deg_s",
    "rate_z_deg_s",
)
LEADING_COLUMNS = ("sample", "sample_seed") + INPUTS + (
    "terrain_tile",
    "terrain_offset_u_m",
    "terrain_offset_v_m",
    "outcome",
    "decided_s",
    "steps",
)
LEG_COLUMNS = ("peak_normal_force_n", "stroke_m", "absorbed_j")


def counts_of(values):
    """Outcome -> count of an iterable of outcome names (only the outcomes that occur)."""
    counts = {}
    for v in values:
        counts[v] = counts.get(v, 0) + 1
    return counts


def check(path, fmt, rows, seed, legs, counts):
    """Returns the list of failures (empty when the file is good)."""
    failures = []

    def expect(ok, message):
        if not ok:
            failures.append(message)

    expected_counts = {k: v for k, v in counts.items() if v != 0}
    unknown = sorted(set(counts) - set(OUTCOMES))
    expect(not unknown, f"the summary printed unknown outcomes {unknown}")
    expect(sum(counts.values()) == rows, f"the summary's counts add up to {sum(counts.values())}, not {rows}")

    # pyarrow: the schema with its field and schema metadata, and the data.
    if fmt == "arrow":
        with pyarrow.ipc.open_file(path) as reader:
            schema = reader.schema
            table = reader.read_all()
    else:
        schema = pyarrow.parquet.read_schema(path)
        table = pyarrow.parquet.read_table(path)
    expect(table.num_rows == rows, f"pyarrow: {table.num_rows} rows, expected {rows}")
    for field in schema:
        meta = field.metadata or {}
        unit = meta.get(b"unit")
        expect(unit is not None, f"field {field.name!r} has no `unit` metadata")
        expect(unit != b"", f"field {field.name!r} has an empty `unit`")
    names = schema.names
    expect(
        tuple(names[: len(LEADING_COLUMNS)]) == LEADING_COLUMNS,
        f"the columns start {names[: len(LEADING_COLUMNS)]}, expected {list(LEADING_COLUMNS)}",
    )
    for k in range(legs):
        missing = [c for c in LEG_COLUMNS if f"leg{k}_{c}" not in names]
        expect(not missing, f"leg {k}: missing columns {missing}")
    extra = sorted(c for c in names if c.startswith(f"leg{legs}_"))
    expect(not extra, f"columns of a leg beyond the {legs} expected: {extra}")
    for name in INPUTS:
        if name in names:
            expect(pyarrow.types.is_float64(schema.field(name).type), f"{name} is {schema.field(name).type}")

    meta = {k.decode(): v.decode() for k, v in (schema.metadata or {}).items()}
    for key in REQUIRED_METADATA:
        expect(key in meta, f"schema metadata has no {key!r} (has {sorted(meta)})")
    if "touchdown.engine" in meta:
        expect(
            meta["touchdown.engine"].startswith("touchdown "),
            f"touchdown.engine = {meta['touchdown.engine']!r}",
        )
    if "touchdown.seed" in meta:
        expect(meta["touchdown.seed"] == str(seed), f"touchdown.seed = {meta['touchdown.seed']!r}, expected {seed}")
    if "touchdown.samples" in meta:
        expect(
            meta["touchdown.samples"] == str(rows),
            f"touchdown.samples = {meta['touchdown.samples']!r}, expected {rows}",
        )
    if meta.get("touchdown.kind", "sweep") != "sweep":
        failures.append(f"touchdown.kind = {meta['touchdown.kind']!r}, expected 'sweep'")
    if "touchdown.scenario" in meta and tomllib is not None:
        try:
            tomllib.loads(meta["touchdown.scenario"])
        except tomllib.TOMLDecodeError as e:
            failures.append(f"touchdown.scenario is not TOML: {e}")

    if "sample" in table.column_names:
        expect(table["sample"].to_pylist() == list(range(rows)), "pyarrow: sample is not 0..N-1 in order")
    if "sample_seed" in table.column_names:
        seeds = table["sample_seed"].to_pylist()
        expect(len(set(seeds)) == len(seeds), "pyarrow: two samples have the same sample_seed")
    if "outcome" in table.column_names:
        got = counts_of(table["outcome"].to_pylist())
        expect(got == expected_counts, f"pyarrow: outcome counts {got}, the summary printed {expected_counts}")

    # pandas.
    df = pandas.read_feather(path) if fmt == "arrow" else pandas.read_parquet(path)
    reader = "pandas.read_feather" if fmt == "arrow" else "pandas.read_parquet"
    expect(len(df) == rows, f"{reader}: {len(df)} rows, expected {rows}")
    expect(list(df.columns) == names, f"{reader}: columns differ from the schema")
    if "sample" in df.columns:
        expect(df["sample"].tolist() == list(range(rows)), f"{reader}: sample is not 0..N-1 in order")
    else:
        failures.append(f"{reader}: no column sample")
    if "outcome" in df.columns:
        # A coded outcome is a category: pandas counts every category, those with no
        # sample too; the summary lists those that occur.
        got = {str(k): int(v) for k, v in df["outcome"].value_counts().items() if v > 0}
        expect(got == expected_counts, f"{reader}: outcome counts {got}, the summary printed {expected_counts}")
    else:
        failures.append(f"{reader}: no column outcome")
    for name in INPUTS:
        if name in df.columns:
            expect(all(map(math.isfinite, df[name])), f"{reader}: {name} not finite")
        else:
            failures.append(f"{reader}: no column {name}")

    # polars.
    pl = polars.read_ipc(path) if fmt == "arrow" else polars.read_parquet(path)
    reader = "polars.read_ipc" if fmt == "arrow" else "polars.read_parquet"
    expect(pl.height == rows, f"{reader}: {pl.height} rows, expected {rows}")
    expect(pl.columns == names, f"{reader}: columns differ from the schema")
    if "sample" in pl.columns:
        expect(pl["sample"].to_list() == list(range(rows)), f"{reader}: sample is not 0..N-1 in order")
    else:
        failures.append(f"{reader}: no column sample")
    if "outcome" in pl.columns:
        vc = pl["outcome"].value_counts()
        got = dict(zip(vc["outcome"].to_list(), vc["count"].to_list()))
        expect(got == expected_counts, f"{reader}: outcome counts {got}, the summary printed {expected_counts}")
    else:
        failures.append(f"{reader}: no column outcome")

    return failures


def main(argv):
    if len(argv) != 7 or argv[2] not in ("arrow", "parquet"):
        print(__doc__, file=sys.stderr)
        return 2
    path, fmt, rows, seed, legs = argv[1], argv[2], int(argv[3]), int(argv[4]), int(argv[5])
    counts = json.loads(argv[6])
    failures = check(path, fmt, rows, seed, legs, counts)
    if failures:
        print(f"{path}: {len(failures)} check(s) failed:", file=sys.stderr)
        for f in failures:
            print(f"  - {f}", file=sys.stderr)
        return 1
    print(
        f"{path}: ok ({fmt}, {rows} rows, {legs} legs; pandas {pandas.__version__}, "
        f"polars {polars.__version__}, pyarrow {pyarrow.__version__})"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
