#!/usr/bin/env python3
"""Stability map of a touchdown sweep: allowable slope per azimuth sector, outcome shares,
and a plot of every sample against the static tipping limit of the lander.

usage: python3 stability.py SWEEP [--png map.png] [--max-points N]

SWEEP is the file of `touchdown sweep` (Arrow IPC or Parquet). Prints Markdown tables; with
--png also draws the map (x: downhill azimuth relative to the lander, y: slope, one point
per sample coloured by outcome, the static tipping limit drawn over it).

The allowable slope follows `touchdown report` (src/report.rs) exactly, so the two agree:
per 45-degree sector of relative azimuth (downhill_azimuth_deg - yaw_deg) mod 360, the
largest slope s such that at least 99 % of the sector's samples with slope <= s are stable,
counting only slopes with at least 100 samples at or below them.

Needs: polars, pyarrow (schema metadata), matplotlib (only for --png). Python 3.11+.
"""

import argparse
import math
import os
import sys
import tomllib

import polars as pl
import pyarrow.ipc
import pyarrow.parquet

# The rule of `touchdown report` (src/report.rs: SECTOR_DEG, ALLOWABLE_STABLE, MIN_SAMPLES).
SECTOR_DEG = 45.0
ALLOWABLE_STABLE = 0.99
MIN_SAMPLES = 100
SECTORS = int(360 / SECTOR_DEG)

# Every outcome a sweep can give, in the order `touchdown report` lists them.
OUTCOMES = ("stable", "tipped", "sliding", "bouncing", "diverged", "held")
COLOURS = {
    "stable": "tab:green",
    "tipped": "tab:red",
    "sliding": "tab:orange",
    "bouncing": "tab:blue",
    "diverged": "black",
    "held": "tab:purple",
}
USED_COLUMNS = ("slope_deg", "downhill_azimuth_deg", "yaw_deg", "outcome")

# The default lander (used for any key the scenario leaves out).
DEFAULT_GEAR = {"legs": 4, "footpad_radius_m": 0.6, "cg_height_m": 0.428936, "first_leg_azimuth_deg": 45.0}


# ---------------------------------------------------------------------------------------
# Reading the file.


def file_format(path):
    """'arrow' or 'parquet', from the magic bytes (as touchdown does), else the extension."""
    with open(path, "rb") as f:
        head = f.read(6)
    if head == b"ARROW1":
        return "arrow"
    if head[:4] == b"PAR1":
        return "parquet"
    if path.endswith((".arrow", ".feather", ".ipc")):
        return "arrow"
    if path.endswith((".parquet", ".pq")):
        return "parquet"
    raise SystemExit(f"{path} is neither an Arrow IPC file nor a Parquet file")


def read_sweep(path):
    """(polars DataFrame of the columns used, pyarrow schema with all the metadata)."""
    fmt = file_format(path)
    if fmt == "arrow":
        # The schema (with field and schema metadata) from pyarrow; the data from polars.
        with pyarrow.ipc.open_file(path) as reader:
            schema = reader.schema
        df = pl.read_ipc(path, columns=list(USED_COLUMNS))
    else:
        schema = pyarrow.parquet.read_schema(path)
        df = pl.read_parquet(path, columns=list(USED_COLUMNS))
    meta = {k.decode(): v.decode() for k, v in (schema.metadata or {}).items()}
    if meta.get("touchdown.kind") != "sweep":
        raise SystemExit(f"{path} is not a sweep file of touchdown")
    return df, schema, meta


def unit(schema, name):
    """The `unit` of a column, from its field metadata."""
    return (schema.field(name).metadata or {}).get(b"unit", b"?").decode()


# ---------------------------------------------------------------------------------------
# The static tipping limit (docs/MODEL.md section 8, thesis 2.2).


def footpads(scenario_toml):
    """Footpad positions (x, y) in the body frame, m, and the CG height above them, m."""
    lander = tomllib.loads(scenario_toml).get("lander", {})
    if "leg_tips_m" in lander:
        # Explicit footpads [[x, y, z], ...] relative to the CG; z < 0 below it. For
        # footpads not in one plane, take their mean height as the footpad plane.
        tips = lander["leg_tips_m"]
        return [(x, y) for x, y, _ in tips], -sum(z for _, _, z in tips) / len(tips)
    g = {k: lander.get(k, v) for k, v in DEFAULT_GEAR.items()}
    n, r = g["legs"], g["footpad_radius_m"]
    az = [math.radians(g["first_leg_azimuth_deg"]) + 2 * math.pi * k / n for k in range(n)]
    return [(r * math.cos(a), r * math.sin(a)) for a in az], g["cg_height_m"]


def support_polygon(points):
    """Their convex hull, counter-clockwise (Andrew's monotone chain)."""
    pts = sorted(set(points))

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    def chain(seq):  # lower hull (left to right) or upper hull (right to left)
        h = []
        for p in seq:
            while len(h) >= 2 and cross(h[-2], h[-1], p) <= 0:
                h.pop()
            h.append(p)
        return h[:-1]

    return chain(pts) + chain(reversed(pts))


def static_limit_deg(polygon, h, phi_deg):
    """Slope at which the lander standing still tips, downhill at phi_deg from X_B: atan(d/h)
    with d the distance from the CG's foot to the polygon's edge along the downhill ray.
    (For a regular N-gon of radius r: d = r cos(pi/N) / cos(phi - nearest edge normal).)
    (NaN when the CG is not above the inside of the polygon, or not above the footpads.)"""
    if len(polygon) < 3 or not h > 0:
        return math.nan
    u = (math.cos(math.radians(phi_deg)), math.sin(math.radians(phi_deg)))
    d = math.inf
    for (x0, y0), (x1, y1) in zip(polygon, polygon[1:] + polygon[:1]):
        # Outward unit normal n of the edge and its distance c from the CG's foot.
        length = math.hypot(x1 - x0, y1 - y0)
        n = ((y1 - y0) / length, -(x1 - x0) / length)
        c = n[0] * x0 + n[1] * y0
        if c <= 0:
            return math.nan
        along = n[0] * u[0] + n[1] * u[1]
        if along > 0:
            d = min(d, c / along)  # where the ray crosses this edge's line
    return math.degrees(math.atan(d / h))


# ---------------------------------------------------------------------------------------
# The allowable slope, as `touchdown report` finds it.


def with_sector(df):
    """Adds the relative azimuth (downhill_azimuth_deg - yaw_deg) mod 360, deg, its sector
    0..7, and `stable`."""
    # polars' % on floats takes the sign of the divisor: in [0, 360), like Rust's rem_euclid.
    relative = (pl.col("downhill_azimuth_deg") - pl.col("yaw_deg")) % 360.0
    return df.with_columns(
        relative_azimuth_deg=relative,
        sector=(relative / SECTOR_DEG).floor().cast(pl.Int64).clip(0, SECTORS - 1),
        stable=pl.col("outcome") == "stable",
    )


Z95 = 1.959963984540054  # the 97.5 % standard normal quantile


def wilson(k, n):
    """The 95 % Wilson interval of k successes in n trials (polars expressions), computed in
    the order of src/report.rs so that both take the same decisions at 99 %."""
    p = k / n
    centre = (p + Z95 * Z95 / (2.0 * n)) / (1.0 + Z95 * Z95 / n)
    half = Z95 / (1.0 + Z95 * Z95 / n) * (p * (1.0 - p) / n + Z95 * Z95 / (4.0 * n * n)).sqrt()
    lo = pl.when(k == 0).then(0.0).otherwise(pl.max_horizontal(centre - half, 0.0))
    hi = pl.when(k == n).then(1.0).otherwise(pl.min_horizontal(centre + half, 1.0))
    return lo, hi


def sector_table(df):
    """Per sector: samples, stable share, allowable slope (null when no slope is), and the
    ends of its 95 % interval (as `touchdown report`)."""
    ranked = df.sort("sector", "slope_deg").with_columns(
        # Within a sector, by increasing slope: samples and stable samples so far...
        n=pl.int_range(1, pl.len() + 1).over("sector"),
        n_stable=pl.col("stable").cast(pl.Int64).cum_sum().over("sector"),
        # ...counted only at the last of equal slopes (all samples at or below s).
        last_of_slope=(pl.col("slope_deg") != pl.col("slope_deg").shift(-1)).fill_null(True).over("sector"),
    )
    resolved = ranked.filter(pl.col("last_of_slope") & (pl.col("n") >= MIN_SAMPLES))
    lo, hi = wilson(pl.col("n_stable").cast(pl.Float64), pl.col("n").cast(pl.Float64))
    slope_where = lambda cond: pl.col("slope_deg").filter(cond).max()  # noqa: E731
    ends = resolved.group_by("sector").agg(
        first_resolved_deg=pl.col("slope_deg").min(),
        allowable_slope_deg=slope_where(pl.col("n_stable") >= ALLOWABLE_STABLE * pl.col("n")),
        low_deg=slope_where(lo >= ALLOWABLE_STABLE),
        high_deg=slope_where(hi >= ALLOWABLE_STABLE),
    )
    counts = df.group_by("sector").agg(samples=pl.len(), stable_share=pl.col("stable").mean())
    # Every sector, the empty ones too.
    return (
        pl.DataFrame({"sector": range(SECTORS)}, schema={"sector": pl.Int64})
        .join(counts, on="sector", how="left")
        .join(ends, on="sector", how="left")
        .with_columns(pl.col("samples").fill_null(0), pl.col("stable_share").fill_null(0.0))
        .sort("sector")
    )


def allowable_cells(n, allowable, low, high, first_resolved):
    """The report's allowable-slope and interval cells of one sector."""
    if n < MIN_SAMPLES:
        return f"too few samples ({n})", "–"
    if allowable is None:
        below = high if high is not None else first_resolved
        return f"no slope with ≥ {100 * ALLOWABLE_STABLE:.0f} % stable", f"0.0–{below:.1f} deg"
    low = 0.0 if low is None else low
    high = allowable if high is None else high
    return f"{allowable:.1f} deg", f"{low:.1f}–{high:.1f} deg"


# ---------------------------------------------------------------------------------------
# Output.


def print_tables(path, df, schema, meta, sectors, polygon, h):
    print(f"# Stability of {path}\n")
    print(
        f"{df.height} samples, seed {meta.get('touchdown.seed', '?')}, "
        f"{meta.get('touchdown.engine', '?')}.\n"
    )
    print("## Columns used\n\n| column | unit | description |\n|---|---|---|")
    for name in USED_COLUMNS:
        desc = (schema.field(name).metadata or {}).get(b"description", b"").decode()
        print(f"| {name} | {unit(schema, name)} | {desc} |")

    print("\n## Outcomes\n\n| outcome | samples | share |\n|---|---:|---:|")
    counts = dict(df.group_by("outcome").len().iter_rows())
    # held: listed, as the report lists it, for sweeps with a control loop only
    for name in (o for o in OUTCOMES if o != "held" or "propellant_kg" in schema.names):
        k = counts.get(name, 0)
        print(f"| {name} | {k} | {100 * k / df.height:.2f} % |")

    print(
        f"\n## Allowable slope\n\nPer {SECTOR_DEG:.0f}-degree sector of downhill azimuth relative to "
        f"the lander: the largest slope at or below which at least {100 * ALLOWABLE_STABLE:.0f} % "
        f"of the samples are stable (only slopes with at least {MIN_SAMPLES} samples at or below "
        f"them count), its 95 % interval, and the static tipping limit over the sector (CG "
        f"{h:.3f} m above the footpads).\n"
    )
    print(
        "| azimuth sector | samples | stable | allowable slope | 95 % interval | static limit |\n"
        "|---|---:|---:|---:|---:|---:|"
    )
    for k, n, share, allowable, low, high, first in sectors.select(
        "sector", "samples", "stable_share", "allowable_slope_deg", "low_deg", "high_deg",
        "first_resolved_deg",
    ).iter_rows():
        lo, hi = k * SECTOR_DEG, (k + 1) * SECTOR_DEG
        limits = [static_limit_deg(polygon, h, lo + i * SECTOR_DEG / 90) for i in range(91)]
        shown, interval = allowable_cells(n, allowable, low, high, first)
        static = "none" if math.isnan(limits[0]) else f"{min(limits):.1f}–{max(limits):.1f} deg"
        print(f"| {lo:.0f}–{hi:.0f} deg | {n} | {100 * share:.1f} % | {shown} | {interval} | {static} |")


def draw_map(png, path, df, schema, meta, sectors, polygon, h, max_points):
    import matplotlib

    matplotlib.use("Agg")  # files only, no window
    import matplotlib.pyplot as plt

    shown = df if df.height <= max_points else df.sample(max_points, seed=0)
    fig, ax = plt.subplots(figsize=(12, 6), dpi=120)
    for name in OUTCOMES:
        pts = shown.filter(pl.col("outcome") == name)
        if pts.height:
            ax.scatter(
                pts["relative_azimuth_deg"], pts["slope_deg"], s=4, c=COLOURS[name],
                alpha=0.6, linewidths=0, rasterized=True, label=f"{name} ({pts.height})",
            )
    phi = [0.5 * i for i in range(721)]
    limit = [static_limit_deg(polygon, h, p) for p in phi]
    ax.plot(phi, limit, color="black", lw=2,
            label="static tipping limit atan(d/h)")
    first = True
    for k, allowable in sectors.select("sector", "allowable_slope_deg").iter_rows():
        if allowable is not None:
            ax.hlines(allowable, k * SECTOR_DEG, (k + 1) * SECTOR_DEG, colors="purple",
                      linestyles="--", lw=1.5,
                      label=f"allowable slope (≥{100 * ALLOWABLE_STABLE:.0f} % stable)" if first else None)
            first = False
    for k in range(1, SECTORS):
        ax.axvline(k * SECTOR_DEG, color="grey", lw=0.5, alpha=0.5)
    az_unit, slope_unit = unit(schema, "downhill_azimuth_deg"), unit(schema, "slope_deg")
    ax.set_xlabel(f"downhill azimuth relative to the lander, downhill_azimuth − yaw [{az_unit}]")
    ax.set_ylabel(f"slope [{slope_unit}]")
    ax.set_xlim(0, 360)
    ax.set_xticks(range(0, 361, 45))
    ax.set_ylim(0, 1.05 * max([df["slope_deg"].max()] + [x for x in limit if not math.isnan(x)]))
    subset = "" if shown.height == df.height else f", {shown.height} shown"
    ax.set_title(f"{os.path.basename(path)}: {df.height} samples{subset}, seed {meta.get('touchdown.seed', '?')}")
    # Outside the axes, so that it hides no sample.
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, markerscale=3)
    fig.tight_layout()
    fig.savefig(png)
    plt.close(fig)
    print(f"\nwrote {png}")


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("sweep", help="sweep file of `touchdown sweep` (Arrow IPC or Parquet)")
    p.add_argument("--png", help="draw the stability map to this PNG file")
    p.add_argument("--max-points", type=int, default=200_000, help="most points to plot (default 200000)")
    a = p.parse_args(argv)
    if a.png:
        # Before any work: say what to install rather than fail with a traceback at the end.
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            print(
                "stability.py: --png draws with matplotlib, which this Python lacks: "
                "pip install matplotlib (or run without --png for the tables alone)",
                file=sys.stderr,
            )
            return 2

    df, schema, meta = read_sweep(a.sweep)
    if df.height == 0:
        raise SystemExit(f"{a.sweep} holds no samples")
    polygon, h = footpads(meta.get("touchdown.scenario", ""))
    polygon = support_polygon(polygon)
    df = with_sector(df)
    sectors = sector_table(df)
    print_tables(a.sweep, df, schema, meta, sectors, polygon, h)
    if a.png:
        draw_map(a.png, a.sweep, df, schema, meta, sectors, polygon, h, a.max_points)
    return 0


if __name__ == "__main__":
    sys.exit(main())
