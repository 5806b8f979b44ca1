#!/usr/bin/env python3
"""Checks that the values Python reads from touchdown's files are the ones the CLI printed.

usage: check_printed_values.py trace FILE PRINTOUT
       check_printed_values.py sweep FILE FORMAT SAMPLE PRINTOUT [SAMPLE PRINTOUT ...]

PRINTOUT is a file holding what `touchdown trace` printed on stdout.

trace: FILE is the trace that run wrote. In its schema metadata (pyarrow): the seed, sample,
sample seed, outcome, decision time, `every` and every input as printed. In pyarrow, pandas
(read_feather) and polars (read_ipc): the row count of the `wrote` line; the first row at
t = 0 with the printed body rates (and attitude, for attitude errors against the vertical);
every row before the decision time; and, when every step is a row (`--every 1`), the last
row ending at the decision time and the per-step columns reaching the printed peaks (leg
normal forces, strokes, acceleration along Z_B, penetration).

sweep: FILE (FORMAT `arrow` or `parquet`) is a sweep of the same scenario and seed as each
PRINTOUT, which `touchdown trace --sample SAMPLE` printed. In pyarrow, pandas and polars,
the row of each SAMPLE holds the printed inputs and sample seed.

Printed numbers are compared within half a unit of their last printed digit. Exits 0 when
all holds, 1 with every failure listed otherwise, 2 on bad usage.
"""

import math
import re
import sys

import pandas
import polars
import pyarrow
import pyarrow.ipc
import pyarrow.parquet
import tomllib


class Printed:
    """What `touchdown trace` printed, as text (so that its precision is known)."""

    def __init__(self, text):
        lines = text.splitlines()
        m = re.fullmatch(r"sample (\d+) of seed (\d+) \(sample seed (0x[0-9a-f]+)\)", lines[0])
        if not m:
            raise ValueError(f"cannot read the first line {lines[0]!r}")
        self.sample, self.seed, self.sample_seed = int(m[1]), int(m[2]), int(m[3], 16)
        self.inputs = {}
        for line in block(lines, "inputs"):
            w = line.split()
            if w[0] != "terrain_tile":
                self.inputs[w[0]] = w[1]
        if len(self.inputs) != 12:
            raise ValueError(f"expected 12 inputs, read {sorted(self.inputs)}")
        summary = {}
        for line in block(lines, "summary"):
            key, _, value = line.strip().partition("  ")
            summary[key] = value.strip()
        m = re.fullmatch(r"(\w+) at ([\d.]+) s \((\d+) steps\)", summary["outcome"])
        self.outcome, self.decided_s, self.steps = m[1], m[2], int(m[3])
        m = re.fullmatch(r"[-\d.]+ m/s\^2 \(along Z_B ([-\d.]+) m/s\^2\)", summary["peak acceleration"])
        self.peak_accel_z_body = m[1]
        self.max_penetration_mm = summary["max penetration"].removesuffix(" mm")
        self.legs = [line.split() for line in block(lines, "  leg  peak normal force N   stroke mm   absorbed J")]
        m = re.search(r"^wrote .*: (\d+) rows \(every (\d+) of (\d+) steps, and the state at the decision\)$", text, re.M)
        self.rows, self.every = int(m[1]), int(m[2])
        if int(m[3]) != self.steps:
            raise ValueError(f"the summary says {self.steps} steps, the `wrote` line {m[3]}")


def block(lines, title):
    """The lines after the line `title`, up to the next empty line."""
    if title not in lines:
        raise ValueError(f"no block {title!r}")
    out = []
    for line in lines[lines.index(title) + 1 :]:
        if not line.strip():
            break
        out.append(line)
    return out


def close(value, printed):
    """Whether `value` prints as `printed` (within half a unit of its last digit)."""
    decimals = len(printed.partition(".")[2])
    return math.isfinite(value) and abs(value - float(printed)) <= 0.5 * 10.0**-decimals * (1 + 1e-9) + 1e-12


def angle_close(value, printed):
    """`close` for angles, modulo 360 deg."""
    wrapped = float(printed) + ((value - float(printed) + 180.0) % 360.0 - 180.0)
    return close(wrapped, printed)


def readers(path, fmt):
    """(name, column getter) of pyarrow, pandas and polars on the file."""
    if fmt == "arrow":
        table = pyarrow.ipc.open_file(path).read_all()
        df, pl = pandas.read_feather(path), polars.read_ipc(path)
        names = ("pyarrow", "pandas.read_feather", "polars.read_ipc")
    else:
        table = pyarrow.parquet.read_table(path)
        df, pl = pandas.read_parquet(path), polars.read_parquet(path)
        names = ("pyarrow", "pandas.read_parquet", "polars.read_parquet")
    return [
        (names[0], lambda c: table[c].to_pylist(), table.num_rows),
        (names[1], lambda c: df[c].tolist(), len(df)),
        (names[2], lambda c: pl[c].to_list(), pl.height),
    ]


def schema_metadata(path, fmt):
    schema = pyarrow.ipc.open_file(path).schema if fmt == "arrow" else pyarrow.parquet.read_schema(path)
    return {k.decode(): v.decode() for k, v in (schema.metadata or {}).items()}


def check_trace(path, p):
    failures = []

    def expect(ok, message):
        if not ok:
            failures.append(message)

    meta = schema_metadata(path, "arrow")
    for key, want in (
        ("touchdown.seed", str(p.seed)),
        ("touchdown.sample", str(p.sample)),
        ("touchdown.sample_seed", str(p.sample_seed)),
        ("touchdown.outcome", p.outcome),
        ("touchdown.every", str(p.every)),
    ):
        expect(meta.get(key) == want, f"metadata {key} = {meta.get(key)!r}, printed {want!r}")
    decided = float(meta.get("touchdown.decided_s", "nan"))
    expect(close(decided, p.decided_s), f"metadata touchdown.decided_s = {decided}, printed {p.decided_s}")
    for name, printed in p.inputs.items():
        v = float(meta.get(f"touchdown.input.{name}", "nan"))
        expect(close(v, printed), f"metadata touchdown.input.{name} = {v}, printed {printed}")
    vertical = tomllib.loads(meta["touchdown.scenario"]).get("initial", {}).get("attitude_reference", "vertical") == "vertical"

    for reader, col, rows in readers(path, "arrow"):
        expect(rows == p.rows, f"{reader}: {rows} rows, printed {p.rows}")
        if rows < 2:
            expect(False, f"{reader}: {rows} rows: not even one step and the decision")
            continue
        t, dt = col("t_s"), col("dt_s")
        expect(t[0] == 0.0, f"{reader}: the first row is at t = {t[0]} s")
        # The last row is the state at the decision: at its time, no step taken from it.
        expect(
            abs(t[-1] - decided) <= 1e-9 * max(1.0, decided) and dt[-1] == 0.0,
            f"{reader}: the last row is at t = {t[-1]} s (dt {dt[-1]} s), decided at {decided} s",
        )
        expect(t[-2] < decided, f"{reader}: the row before the last is at t = {t[-2]} s, not before the decision at {decided} s")
        # The first row holds the sample's initial body rates (and attitude errors, when they
        # are taken against the vertical, the frame of the trace's Euler angles).
        first = ["rate_x_deg_s", "rate_y_deg_s", "rate_z_deg_s"]
        if vertical:
            first += ["roll_deg", "pitch_deg", "yaw_deg"]
        for name in first:
            v = col(name)[0]
            expect(angle_close(v, p.inputs[name]), f"{reader}: {name} = {v} at t = 0, printed input {p.inputs[name]}")
        if p.every != 1:
            continue
        # Every step is a row: the rows end at the decision and reach the printed peaks.
        expect(
            abs(t[-2] + dt[-2] - decided) <= 1e-9 * max(1.0, decided),
            f"{reader}: the last step ends at {t[-2] + dt[-2]} s, decided at {decided} s",
        )
        for k, leg in enumerate(p.legs):
            expect(int(leg[0]) == k, f"leg line {leg} out of order")
            force = max(col(f"leg{k}_normal_force_n"))
            expect(close(force, leg[1]), f"{reader}: leg {k} peak normal force {force} N, printed {leg[1]}")
            stroke = 1e3 * max(col(f"leg{k}_stroke_m"))
            expect(close(stroke, leg[2]), f"{reader}: leg {k} stroke {stroke} mm, printed {leg[2]}")
        acc = max(col("accel_z_body_m_s2"))
        expect(close(acc, p.peak_accel_z_body), f"{reader}: peak accel_z_body_m_s2 {acc}, printed {p.peak_accel_z_body}")
        pen = 1e3 * max(max(col(f"leg{k}_penetration_m")) for k in range(len(p.legs)))
        expect(close(pen, p.max_penetration_mm), f"{reader}: max penetration {pen} mm, printed {p.max_penetration_mm}")
    return failures


def check_sweep(path, fmt, printouts):
    failures = []

    def expect(ok, message):
        if not ok:
            failures.append(message)

    meta = schema_metadata(path, fmt)
    for reader, col, _ in readers(path, fmt):
        index = {s: i for i, s in enumerate(col("sample"))}
        for sample, p in printouts:
            expect(p.sample == sample, f"the printout of sample {sample} is of sample {p.sample}")
            expect(meta.get("touchdown.seed") == str(p.seed), f"the printout of sample {sample} is of seed {p.seed}")
            i = index.get(sample)
            if i is None:
                failures.append(f"{reader}: no row of sample {sample}")
                continue
            seed = col("sample_seed")[i]
            expect(seed == p.sample_seed, f"{reader}: sample {sample}: sample_seed {seed:#x}, printed {p.sample_seed:#x}")
            for name, printed in p.inputs.items():
                v = col(name)[i]
                expect(close(v, printed), f"{reader}: sample {sample}: {name} = {v}, printed {printed}")
    return failures


def main(argv):
    try:
        if len(argv) == 4 and argv[1] == "trace":
            path = argv[2]
            with open(argv[3]) as f:
                failures = check_trace(path, Printed(f.read()))
        elif len(argv) >= 6 and argv[1] == "sweep" and argv[3] in ("arrow", "parquet") and len(argv) % 2 == 0:
            path, pairs = argv[2], []
            for sample, printout in zip(argv[4::2], argv[5::2]):
                with open(printout) as f:
                    pairs.append((int(sample), Printed(f.read())))
            failures = check_sweep(path, argv[3], pairs)
        else:
            print(__doc__, file=sys.stderr)
            return 2
    except (ValueError, KeyError, TypeError) as e:
        print(f"cannot read the printout: {e!r}", file=sys.stderr)
        return 1
    if failures:
        print(f"{path}: {len(failures)} check(s) failed:", file=sys.stderr)
        for f in failures:
            print(f"  - {f}", file=sys.stderr)
        return 1
    print(f"{path}: ok ({argv[1]}; pandas {pandas.__version__}, polars {polars.__version__}, pyarrow {pyarrow.__version__})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
