#!/usr/bin/env python3
"""What hold-down thrust buys: outcome shares, peak loads and propellant per cell of a
hold-down study (scenarios/hold-down-study.toml and hold-down-study-attitude.toml).

usage: python3 hold_down.py SWEEP [SWEEP ...] [--flat-below DEG]

Each SWEEP is the file of `touchdown sweep` on a scenario with [control.hold_down] (Arrow
IPC or Parquet). Prints one Markdown table per file: a row per (hold-down thrust, duration)
cell with its samples, the stable share with its 95 % Wilson interval, the stable share on
slopes below DEG (default 30 deg, under the friction angle atan(0.6) = 31 deg), the tipped,
sliding and bouncing shares, the 99th percentile of the peak leg normal force and of the
peak CG acceleration, and the mean and largest propellant. Then the headline: the smallest
thrust (and its propellant) whose cells reach 99 % stable, on all slopes and below DEG.

Needs: polars. Python 3.11+.
"""

import argparse
import math
import sys

import polars as pl

Z95 = 1.959963984540054


def wilson(k, n):
    """95 % Wilson interval of k successes in n trials, as fractions."""
    if n == 0:
        return (0.0, 1.0)
    p = k / n
    d = 1 + Z95**2 / n
    c = (p + Z95**2 / (2 * n)) / d
    h = Z95 * math.sqrt(p * (1 - p) / n + Z95**2 / (4 * n * n)) / d
    return (max(0.0, c - h), min(1.0, c + h))


def read(path):
    if path.endswith((".parquet", ".pq")):
        return pl.read_parquet(path)
    return pl.read_ipc(path)


def cells(sweep, flat_below):
    legs = [c for c in sweep.columns if c.endswith("_peak_normal_force_n")]
    sweep = sweep.with_columns(
        pl.max_horizontal(legs).alias("peak_leg_force_n"),
        (pl.col("outcome") == "stable").alias("is_stable"),
        (pl.col("slope_deg") < flat_below).alias("below"),
    )
    share = lambda o: (pl.col("outcome") == o).mean().alias(o)
    return (
        sweep.group_by("hold_down_thrust_n", "hold_down_duration_s")
        .agg(
            pl.len().alias("n"),
            pl.col("is_stable").sum().alias("k"),
            pl.col("below").sum().alias("n_below"),
            (pl.col("is_stable") & pl.col("below")).sum().alias("k_below"),
            share("tipped"),
            share("sliding"),
            share("bouncing"),
            pl.col("peak_leg_force_n").quantile(0.99, "higher").alias("force_p99"),
            pl.col("peak_acceleration_m_s2").quantile(0.99, "higher").alias("acc_p99"),
            pl.col("propellant_kg").mean().alias("propellant_mean"),
            pl.col("propellant_kg").max().alias("propellant_max"),
        )
        .sort("hold_down_thrust_n", "hold_down_duration_s")
    )


def table(path, flat_below):
    sweep = read(path)
    if "hold_down_thrust_n" not in sweep.columns:
        sys.exit(f"{path}: no hold_down_thrust_n column (not a sweep with [control.hold_down])")
    rows = cells(sweep, flat_below)
    print(f"## {path}: {sweep.height} samples\n")
    print(
        "| thrust N | duration s | samples | stable % (95 % interval) "
        f"| stable % below {flat_below:g} deg | tipped % | sliding % | bouncing % "
        "| peak leg force p99 N | peak CG accel p99 m/s^2 | propellant mean / max kg |"
    )
    print("|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---|")
    best_all = best_below = None
    for r in rows.iter_rows(named=True):
        lo, hi = wilson(r["k"], r["n"])
        stable = r["k"] / r["n"]
        below = r["k_below"] / r["n_below"] if r["n_below"] else float("nan")
        print(
            f"| {r['hold_down_thrust_n']:g} | {r['hold_down_duration_s']:g} | {r['n']} "
            f"| {100 * stable:.2f} ({100 * lo:.2f}-{100 * hi:.2f}) | {100 * below:.2f} "
            f"| {100 * r['tipped']:.2f} | {100 * r['sliding']:.2f} | {100 * r['bouncing']:.2f} "
            f"| {r['force_p99']:.1f} | {r['acc_p99']:.3f} "
            f"| {r['propellant_mean']:.4f} / {r['propellant_max']:.4f} |"
        )
        key = (r["hold_down_thrust_n"], r["propellant_mean"], r["hold_down_duration_s"])
        if stable >= 0.99 and (best_all is None or key < best_all):
            best_all = key
        if below >= 0.99 and (best_below is None or key < best_below):
            best_below = key
    print()
    for name, best in (("on all slopes", best_all), (f"below {flat_below:g} deg", best_below)):
        if best is None:
            print(f"- {name}: no cell reaches 99 % stable")
        else:
            print(
                f"- {name}: 99 % stable from {best[0]:g} N for {best[2]:g} s "
                f"({best[1]:.4f} kg of propellant on average)"
            )
    print()


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("sweeps", nargs="+")
    p.add_argument("--flat-below", type=float, default=30.0)
    a = p.parse_args()
    for path in a.sweeps:
        table(path, a.flat_below)


if __name__ == "__main__":
    main()
