#!/usr/bin/env python3
"""Checks that a touchdown trace (Arrow IPC file) reads in the Python tools people use.

usage: check_trace.py FILE EXPECTED_ROWS EXPECTED_LEGS

Opens FILE with pyarrow, pandas.read_feather and polars.read_ipc and checks the row count,
that t_s increases, that every field carries a `unit` in its metadata, the provenance in
the schema metadata, and the per-leg columns. Exits 0 when all holds, 1 with every failure
listed otherwise, 2 on bad usage.
"""

import math
import sys

import pandas
import polars
import pyarrow
import pyarrow.ipc

try:
    import tomllib  # Python 3.11+
except ImportError:  # pragma: no cover
    tomllib = None

REQUIRED_METADATA = (
    "touchdown.engine",
    "touchdown.seed",
    "touchdown.scenario",
    "touchdown.outcome",
)
OUTCOMES = {"stable", "tipped", "sliding", "bouncing", "diverged", "held"}
LEG_COLUMNS = (
    "tip_x_m",
    "tip_y_m",
    "tip_z_m",
    "penetration_m",
    "normal_force_n",
    "friction_force_n",
    "stroke_m",
)


def check(path, rows, legs):
    """Returns the list of failures (empty when the file is good)."""
    failures = []

    def expect(ok, message):
        if not ok:
            failures.append(message)

    # pyarrow: the schema with its field and schema metadata.
    with pyarrow.ipc.open_file(path) as reader:
        schema = reader.schema
        table = reader.read_all()
    expect(table.num_rows == rows, f"pyarrow: {table.num_rows} rows, expected {rows}")
    for field in schema:
        meta = field.metadata or {}
        unit = meta.get(b"unit")
        expect(unit is not None, f"field {field.name!r} has no `unit` metadata")
        expect(unit != b"", f"field {field.name!r} has an empty `unit`")
        expect(
            pyarrow.types.is_floating(field.type),
            f"field {field.name!r} is {field.type}, expected a float",
        )
    meta = {k.decode(): v.decode() for k, v in (schema.metadata or {}).items()}
    for key in REQUIRED_METADATA:
        expect(key in meta, f"schema metadata has no {key!r} (has {sorted(meta)})")
    if "touchdown.engine" in meta:
        expect(
            meta["touchdown.engine"].startswith("touchdown "),
            f"touchdown.engine = {meta['touchdown.engine']!r}",
        )
    if "touchdown.seed" in meta:
        expect(meta["touchdown.seed"].isdigit(), f"touchdown.seed = {meta['touchdown.seed']!r}")
    if "touchdown.outcome" in meta:
        expect(
            meta["touchdown.outcome"] in OUTCOMES,
            f"touchdown.outcome = {meta['touchdown.outcome']!r}, expected one of {sorted(OUTCOMES)}",
        )
    if "touchdown.scenario" in meta and tomllib is not None:
        try:
            tomllib.loads(meta["touchdown.scenario"])
        except tomllib.TOMLDecodeError as e:
            failures.append(f"touchdown.scenario is not TOML: {e}")

    # pandas.
    df = pandas.read_feather(path)
    expect(len(df) == rows, f"pandas: {len(df)} rows, expected {rows}")
    expect(list(df.columns) == schema.names, "pandas: columns differ from the schema")
    if "t_s" in df.columns:
        t = df["t_s"]
        expect(t.notna().all() and all(map(math.isfinite, t)), "pandas: t_s not finite")
        expect(
            bool((t.diff().iloc[1:] > 0).all()),
            "pandas: t_s does not increase strictly",
        )
    else:
        failures.append("pandas: no column t_s")

    # polars.
    pl = polars.read_ipc(path)
    expect(pl.height == rows, f"polars: {pl.height} rows, expected {rows}")
    expect(pl.columns == schema.names, "polars: columns differ from the schema")
    if "t_s" in pl.columns:
        diffs = pl["t_s"].diff().drop_nulls()
        expect(bool((diffs > 0).all()), "polars: t_s does not increase strictly")
    else:
        failures.append("polars: no column t_s")

    if "dt_s" in pl.columns:
        # Every row a step, but the last: the state at the decision, from which no step runs.
        expect(bool((pl["dt_s"].head(-1) > 0).all()), "polars: dt_s not positive before the last row")
        expect(pl["dt_s"][-1] == 0.0, f"polars: the last row (the decision) has dt_s {pl['dt_s'][-1]}, not 0")
    else:
        failures.append("polars: no column dt_s")

    # Leg columns: every leg has all of them, and there are no more legs than expected.
    columns = set(schema.names)
    for k in range(legs):
        missing = [c for c in LEG_COLUMNS if f"leg{k}_{c}" not in columns]
        expect(not missing, f"leg {k}: missing columns {missing}")
    extra = sorted(c for c in columns if c.startswith(f"leg{legs}_"))
    expect(not extra, f"columns of a leg beyond the {legs} expected: {extra}")

    return failures


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    path, rows, legs = argv[1], int(argv[2]), int(argv[3])
    failures = check(path, rows, legs)
    if failures:
        print(f"{path}: {len(failures)} check(s) failed:", file=sys.stderr)
        for f in failures:
            print(f"  - {f}", file=sys.stderr)
        return 1
    print(
        f"{path}: ok ({rows} rows, {legs} legs; pandas {pandas.__version__}, "
        f"polars {polars.__version__}, pyarrow {pyarrow.__version__})"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
