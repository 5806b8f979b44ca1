#!/usr/bin/env bash
# Prove that a refactor keeps every output: run the same commands with two binaries and
# compare every file they write, byte for byte (SHA-256).
#
#   tests/same-bytes/run.sh OLD_BINARY NEW_BINARY WORKDIR
#
# OLD_BINARY  the touchdown binary before the change (e.g. a build of the base commit)
# NEW_BINARY  the touchdown binary after it (e.g. target/release/touchdown)
# WORKDIR     made if missing; its old/, new/, logs/, inputs/ and bin/ are emptied and made
#             anew: old/ and new/ hold what each binary wrote, with cmd/NAME.stdout and
#             cmd/NAME.exit of every command; logs/SET/ each command's stderr and times
#
# Prints one line per file (equal / equal but the version / DIFFERENT / only in old|new),
# then "N files compared, N equal, E the same values encoded otherwise, M different". Exits
# 0 only if every file is equal (or the same values encoded otherwise, where
# SAME_BYTES_ENCODINGS=allow: "Encodings" below), both folders hold the same file names and
# every command exited as it should; 1 otherwise, 2 on bad arguments. Needs only bash and coreutils; a python with pyarrow ($TOUCHDOWN_PYTHON,
# else target/tmp/python-venv/bin/python of this repo if it exists) adds the one allowed
# difference, the engine version (see "Versions" below).
#
# How. Each binary runs the whole set in turn (OLD first), under the name `touchdown` (a
# symlink in WORKDIR/bin/, since clap's usage lines print the name it was called by), every
# command in its own folder with the same relative file names: the inputs (scenarios/*.toml,
# a CSV table, a terrain of slope bins, bad inputs) are copied into inputs/ of each folder,
# so the paths that files and reports record are the same. The copies are compared too.
# Exit codes are compared (cmd/NAME.exit), and any command that fails (or, for the ones
# that must be refused, succeeds or fails otherwise than with 2) is reported and fails the run.
#
# Covered (run_set below): --version and every --help; scenario; sweep of every
# scenarios/*.toml at 2000 samples and its report; the default sweep as Arrow, Parquet,
# --format parquet, --out - (IPC stream), 3 shards merged into Arrow and Parquet, --seed,
# --threads 1, --kernel portable and avx2 (if the CPU has it), the default output name;
# f32 lanes; every drawable parameter with a drawn roughness; a CSV --inputs table with
# --keep-columns (and trace --sweep / --inputs of its rows); --design sobol-indices and
# sobol-sequence; sensitivity (Markdown and --png) of three Saltelli sweeps; compare of
# three pairs; study (3 footpad radii x 1000 samples), and the same study in 2 shards
# merged; boundary (batch 200, 1000 per sector); trace of the default (also --every), of
# hold-down and descent (thrusters), of drawn parameters, of a rough sweep's row; plot of
# sweeps and traces; animate (160x120 GIFs); view; report --slope-distribution (rayleigh,
# normal, exponential, a CSV of bins); a landing-site map of the Didymos model (2,000
# samples: its sweep, facets table, site.md, map.png and site.html); five refusals (exit 2
# and their message).
#
# Masked before comparing, and why (all else is compared as written):
#   sweep's stdout  "wall time", "samples/s", "lander-steps/s": wall-clock measures;
#                   "serial share": a ratio of CPU times, which vary as they do. And,
#                   with 2 threads, "lane occupancy": which samples share a SIMD block
#                   depends on how the threads steal work, so it varies from run to run
#                   of one binary (0.924/0.931/0.934 in three runs of the default); with
#                   --threads 1 it does not, and that sweep keeps it. Mean steps per
#                   sample, outcome counts and "wrote ..." stay.
#   study's stdout  "N samples in T s" per value and "shard K/N ... done in T s": T
#   boundary's      "... candidates drawn) in T s.": T (boundary writes no file)
#     stdout
#   animate's       "wrote F: X MB in T s": T
#     stdout
#   site's stdout   "... in T s" (the facets' gravity, the sweep): T
# Not compared: stderr (logs/), the progress, the sweep's banner and summary with --out -,
# warnings: no result goes there only, and its lines carry timings. Except the commands
# that must be refused: their stderr is the error message alone, compared (cmd/NAME.stderr).
# Checked to hold no wall time, so compared as written: study.md, study.arrow, study.png,
# every sweep, shard, trace, PNG, GIF and HTML, and the stdout of report, sensitivity,
# compare, trace, plot, view and merge.
# Not covered: `sweep --resume` and an interrupted study (the interrupted file depends on
# when the signal lands), and the AVX-512 kernel where the CPU has none (auto runs the widest).
#
# Versions. touchdown.engine ("touchdown X.Y.Z") is in the schema metadata of every Arrow
# and Parquet file (and Parquet's created_by), and in report's third line. Where a file's
# SHA-256 differs: an Arrow file or stream or Parquet file is compared with pyarrow, schema
# with field metadata, every schema metadata key but touchdown.engine, Parquet key-value
# metadata, batches or row groups, and every column bit for bit; equal there, it is "equal
# but the version". A text file is equal but the version if replacing the old engine string
# (from report's line) with the new one makes it equal. Without pyarrow such an Arrow or
# Parquet file is DIFFERENT.
#
# Encodings. An Arrow or Parquet file that is not equal so is "same values, encoded
# otherwise" where its columns are the same bit for bit once each coded (dictionary) column
# is read as its values, the schemas are the same but for those columns' types, and the
# batches or row groups hold the same rows; the line names the columns coded otherwise and
# whether Parquet's encodings or compression changed. A change of encoding is not a move of
# code: such files fail the run unless SAME_BYTES_ENCODINGS=allow (then the summary counts
# them apart). Since the coded outcome (engine 0.6, after f05d3a3): `outcome` and
# `limits_broken` are coded, Parquet is zstd without dictionaries on floating-point and
# 64-bit integer columns.
#
# Run time on 2 cores: 55-95 s per binary (the upper end while a cargo build shared the
# cores), 2-3 min in all with the comparison. No scenario is near 30 s at 2000 samples: the
# slowest commands are boundary (7-11 s) and the two rough sweeps (5.5-11 s each), all
# others under 6 s; logs/SET/times.txt has each command's time. 402 files are compared.
set -euo pipefail
export LC_ALL=C

usage() {
    sed -n '2,18p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
    exit "${1:-2}"
}

[[ $# -ge 1 && ( $1 == -h || $1 == --help ) ]] && usage 0
[[ $# -eq 3 ]] || usage
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
repo=$(cd "$here/../.." && pwd)
for b in "$1" "$2"; do
    [[ -x $b && -f $b ]] || { echo "same-bytes: not an executable file: $b" >&2; exit 2; }
done
old_bin=$(realpath "$1")
new_bin=$(realpath "$2")
mkdir -p "$3"
work=$(realpath "$3")
[[ $work != "$repo" && $work != / ]] || { echo "same-bytes: WORKDIR must be a folder of its own: $3" >&2; exit 2; }

# The python for the Arrow/Parquet fallback: only if it has pyarrow.
py=${TOUCHDOWN_PYTHON:-$repo/target/tmp/python-venv/bin/python}
py=$(command -v "$py" || true)
if [[ -x $py ]] && "$py" -c 'import pyarrow' 2>/dev/null; then
    have_pyarrow=1
else
    have_pyarrow=0
fi

SAMPLES=2000   # per sweep of scenarios/*.toml and of the default scenario
THREADS=2

# ---------------------------------------------------------------------------------------
# Inputs: made once, copied into old/inputs and new/inputs.

make_inputs() {
    local dir=$1
    mkdir -p "$dir/scenarios"
    cp "$repo"/scenarios/*.toml "$dir/scenarios/"
    # The Didymos model, for a landing-site map.
    cp "$repo"/bodies/didymos/didymos.obj "$dir/didymos.obj"
    # A table of our own (README "Your own inputs"): slopes, rolls and sample seeds set, the
    # rest drawn from the default scenario; `case` (text) and `weight` (numbers) pass
    # through with --keep-columns.
    awk 'BEGIN {
        print "slope_deg,roll_deg,sample_seed,case,weight"
        for (i = 0; i < 40; i++)
            printf "%.3f,%.2f,%d,case-%02d,%.4f\n", (i * 7.3) % 45, (i % 7) - 3, 1000003 + 7919 * i, i, 1 + i / 8
    }' >"$dir/table.csv"
    # A table the sweep must refuse: a slope of 95 deg in row 1.
    printf 'slope_deg\n10\n95\n' >"$dir/bad-table.csv"
    # A terrain of slope bins for report --slope-distribution.
    printf 'slope_min_deg,slope_max_deg,probability\n0,10,0.62\n10,20,0.30\n20,40,0.08\n' \
        >"$dir/terrain-bins.csv"
    # The default scenario in f32 lanes (f32x16 kernels: another code path).
    printf '[simulation]\nprecision = "f32"\n' >"$dir/f32.toml"
    # Every drawn lander and surface parameter (README "Uncertain surface and lander
    # parameters"), dampers on and a drawn roughness.
    cat >"$dir/params.toml" <<'TOML'
[lander]
mass_kg = { dist = "uniform", min = 90.0, max = 110.0 }
cg_height_m = { dist = "uniform", min = 0.40, max = 0.46 }
[surface]
stiffness_n_per_m = { dist = "uniform", min = 1.0e4, max = 1.0e5 }
damping_n_s_per_m = { dist = "uniform", min = 200.0, max = 2000.0 }
friction_coefficient = { dist = "uniform", min = 0.3, max = 0.9 }
[surface.roughness]
rms_height_m = { dist = "uniform", min = 0.0, max = 0.02 }
[damper]
enabled = true
crush_strength_psi = { dist = "uniform", min = 50.0, max = 140.0 }
TOML
    # A scenario the reader must refuse: an unknown key.
    printf '[lander]\nfootpad_radius = 0.6\n' >"$dir/bad-key.toml"
}

# ---------------------------------------------------------------------------------------
# Running one command. Every command runs in the binary's folder; its exit code goes to
# cmd/NAME.exit and its stdout (masked where it holds timings) to cmd/NAME.stdout, both
# compared; its stderr to logs/NAME.log (not compared). A non-zero exit is reported at once
# and counted.

bin=        # the binary of the current set
logs=       # logs/old or logs/new
failed=()   # "old: NAME (exit N)" of commands that exited otherwise than they should

# Masks of wall-clock numbers in stdout (see the header); `none` keeps it as it is.
mask() {
    case $1 in
        none) cat ;;
        sweep) sed -E \
            -e 's/^(wall time +)[0-9.]+ s$/\1<masked> s/' \
            -e 's/^(samples\/s +)[0-9.]+$/\1<masked>/' \
            -e 's/^(lander-steps\/s +).*$/\1<masked>/' \
            -e 's/^(serial share +).*$/\1<masked>/' \
            -e 's/^(lane occupancy +)[0-9.]+$/\1<masked>/' ;;
        sweep1) sed -E \
            -e 's/^(wall time +)[0-9.]+ s$/\1<masked> s/' \
            -e 's/^(samples\/s +)[0-9.]+$/\1<masked>/' \
            -e 's/^(lander-steps\/s +).*$/\1<masked>/' \
            -e 's/^(serial share +).*$/\1<masked>/' ;;
        study) sed -E \
            -e 's/( samples in )[0-9.]+ s,/\1<masked> s,/' \
            -e 's/^(shard .* done in )[0-9.]+ s;/\1<masked> s;/' ;;
        boundary) sed -E 's/(candidates drawn\) in )[0-9.]+ s\./\1<masked> s./' ;;
        animate) sed -E 's/^(wrote .*: [0-9.]+ MB in )[0-9.]+ s$/\1<masked> s/' ;;
        site) sed -E 's/ in [0-9.]+ s([ ,;.]|$)/ in <masked> s\1/g' ;;
        *) echo "same-bytes: unknown mask $1" >&2; exit 2 ;;
    esac
}

# took NAME START: appends the command's wall time to logs/.../times.txt (not compared).
took() {
    awk -v n="$1" -v a="$2" -v e="$EPOCHREALTIME" 'BEGIN { printf "%8.2f s  %s\n", e - a, n }' \
        >>"$logs/times.txt"
}

# run MASK NAME ARGS...: `touchdown ARGS...`, which must succeed.
run() {
    local m=$1 name=$2 rc=0
    shift 2
    local t0=$EPOCHREALTIME
    "$bin" "$@" >"$logs/$name.stdout.raw" 2>"$logs/$name.log" || rc=$?
    took "$name" "$t0"
    mask "$m" <"$logs/$name.stdout.raw" >"cmd/$name.stdout"
    echo "$rc" >"cmd/$name.exit"
    if [[ $rc -ne 0 ]]; then
        failed+=("$set_name: $name (exit $rc): touchdown $*")
        echo "same-bytes: $set_name: $name FAILED with exit $rc: touchdown $*" >&2
        tail -n 3 "$logs/$name.log" | sed 's/^/    /' >&2
    fi
}

# run_to FILE NAME ARGS...: as `run`, stdout (an output itself, e.g. `--out -`) into FILE.
run_to() {
    local file=$1 name=$2 rc=0
    shift 2
    local t0=$EPOCHREALTIME
    "$bin" "$@" >"$file" 2>"$logs/$name.log" || rc=$?
    took "$name" "$t0"
    echo "$rc" >"cmd/$name.exit"
    if [[ $rc -ne 0 ]]; then
        failed+=("$set_name: $name (exit $rc): touchdown $*")
        echo "same-bytes: $set_name: $name FAILED with exit $rc: touchdown $*" >&2
    fi
}

# must_fail NAME ARGS...: a command that must be refused (exit 2); its stdout, stderr (the
# error message, no timings) and exit code are compared.
must_fail() {
    local name=$1 rc=0
    shift
    "$bin" "$@" >"cmd/$name.stdout" 2>"cmd/$name.stderr" || rc=$?
    echo "$rc" >"cmd/$name.exit"
    if [[ $rc -ne 2 ]]; then
        failed+=("$set_name: $name (exit $rc, not 2): touchdown $*")
        echo "same-bytes: $set_name: $name exited $rc where it must be refused (2): touchdown $*" >&2
    fi
}

# ---------------------------------------------------------------------------------------
# The commands, in the current folder. Relative paths only.

run_set() {
    local t n s
    mkdir -p cmd sweeps shards traces plots anim view
    t=("--threads" "$THREADS")

    # 0. Help texts, version and the default scenario (`touchdown scenario`).
    run none version --version
    run none help --help
    for c in scenario sweep report sensitivity compare study boundary merge plot trace animate view site; do
        run none "help-$c" "$c" --help
    done
    run none scenario scenario

    # 1. Every scenario file at $SAMPLES samples (Arrow), and its report. Sweep times on 2
    #    cores: see SLOW in the header.
    for s in inputs/scenarios/*.toml; do
        n=$(basename "$s" .toml)
        run sweep "sweep-$n" sweep --scenario "$s" --samples "$SAMPLES" "${t[@]}" --quiet \
            --out "sweeps/$n.arrow"
        run none "report-$n" report "sweeps/$n.arrow"
    done

    # 2. The default scenario: Arrow, Parquet, 3 shards merged (into both formats), and the
    #    IPC stream on stdout (its summary goes to stderr).
    run sweep sweep-default sweep --samples "$SAMPLES" "${t[@]}" --quiet --out default.arrow
    run sweep sweep-default-parquet sweep --samples "$SAMPLES" "${t[@]}" --quiet \
        --out default.parquet
    for k in 0 1 2; do
        run sweep "sweep-default-shard-$k" sweep --samples "$SAMPLES" "${t[@]}" --quiet \
            --shard "$k/3" --out "shards/default.shard-$k.arrow"
    done
    run none merge-default merge shards/default.shard-2.arrow shards/default.shard-0.arrow \
        shards/default.shard-1.arrow --out default-merged.arrow
    run none merge-default-parquet merge shards/default.shard-0.arrow \
        shards/default.shard-1.arrow shards/default.shard-2.arrow --out default-merged.pq \
        --format parquet
    run_to default-stream.arrows sweep-default-stream sweep --samples "$SAMPLES" "${t[@]}" \
        --quiet --out -
    run none report-default report default.arrow
    run none report-default-parquet report default.parquet

    # 2b. Flags and code paths of sweep: one thread (whose lane occupancy, unlike that of 2
    #     threads, does not depend on scheduling: kept in the comparison), another seed, the
    #     other kernels (the CPU's; both binaries run on this one), f32 lanes, drawn
    #     parameters, --format against the extension, and the default output name.
    run sweep1 sweep-default-threads1 sweep --samples "$SAMPLES" --threads 1 --quiet \
        --out default-threads1.arrow
    run sweep sweep-default-seed7 sweep --samples "$SAMPLES" --seed 7 "${t[@]}" --quiet \
        --out default-seed7.arrow
    run sweep sweep-default-portable sweep --samples "$SAMPLES" --kernel portable "${t[@]}" \
        --quiet --out default-portable.arrow
    if grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo; then
        run sweep sweep-default-avx2 sweep --samples "$SAMPLES" --kernel avx2 "${t[@]}" \
            --quiet --out default-avx2.arrow
    fi
    run sweep sweep-f32 sweep --scenario inputs/f32.toml --samples "$SAMPLES" "${t[@]}" \
        --quiet --out f32.arrow
    run none report-f32 report f32.arrow
    run sweep sweep-params sweep --scenario inputs/params.toml --samples "$SAMPLES" "${t[@]}" \
        --quiet --out params.arrow
    run none report-params report params.arrow
    run sweep sweep-default-format sweep --samples 500 --format parquet "${t[@]}" --quiet \
        --out default-500.data
    run sweep sweep-default-name sweep --samples 200 "${t[@]}" --quiet   # sweep.arrow

    # 3. A table of our own inputs (CSV), its kept columns, and a trace of one of its rows
    #    (trace --sweep reads the table where the sweep read it).
    run sweep sweep-table sweep --inputs inputs/table.csv --keep-columns "${t[@]}" --quiet \
        --out table.arrow
    run sweep sweep-table-parquet sweep --inputs inputs/table.csv --keep-columns --samples 25 \
        "${t[@]}" --quiet --out table-25.parquet
    run none report-table report table.arrow
    run none trace-table trace --sweep table.arrow --sample 3 --out traces/table-3.arrow --every 50
    run none trace-table-row trace --inputs inputs/table.csv --sample 4 --every 50 \
        --out traces/table-row-4.arrow

    # 4. Sobol: the sensitivity scenarios ran in 1 (design = "sobol-indices" in the file);
    #    --design on the command line, and `sensitivity` (Markdown and --png).
    run sweep sweep-flat-sobol-indices sweep --scenario inputs/scenarios/flat.toml \
        --design sobol-indices --samples 1400 "${t[@]}" --quiet --out sobol-indices-flat.arrow
    run sweep sweep-default-sobol-sequence sweep --design sobol-sequence --samples "$SAMPLES" \
        "${t[@]}" --quiet --out sobol-sequence.arrow
    run none report-sobol-sequence report sobol-sequence.arrow
    for n in sensitivity-flat sensitivity-default; do
        run none "sensitivity-$n" sensitivity "sweeps/$n.arrow" --png "plots/$n.png"
    done
    run none sensitivity-flat-sobol-indices sensitivity sobol-indices-flat.arrow \
        --bootstrap 200 --png plots/sobol-indices-flat.png

    # 5. compare: two scenarios of the same seed and samples (paired).
    run none compare-flat-rate-y compare sweeps/flat.arrow sweeps/flat-rate-y.arrow
    run none compare-honeycomb compare sweeps/honeycomb-50psi.arrow sweeps/honeycomb-140psi.arrow
    run none compare-default-parquet compare default.arrow default.parquet

    # 6. study: 3 footpad radii at 1000 samples (study.arrow, study.md, study.png and each
    #    value's sweep file); then the same study in 2 shards, merged by the command without
    #    --shard.
    run study study study --scenario inputs/scenarios/footpad-radius-study.toml \
        --vary lander.footpad_radius_m=0.6:0.9:3 --samples 1000 "${t[@]}" --quiet \
        --out-dir study
    for k in 0 1; do
        run study "study-shard-$k" study --scenario inputs/scenarios/footpad-radius-study.toml \
            --vary lander.footpad_radius_m=0.6:0.9:3 --samples 1000 "${t[@]}" --quiet \
            --out-dir study-sharded --shard "$k/2"
    done
    run study study-merge study --scenario inputs/scenarios/footpad-radius-study.toml \
        --vary lander.footpad_radius_m=0.6:0.9:3 --samples 1000 "${t[@]}" --quiet \
        --out-dir study-sharded

    # 7. boundary: small rounds, few samples per sector (its report on stdout).
    run boundary boundary-flat boundary --scenario inputs/scenarios/flat.toml --batch 200 \
        --max-samples-per-sector 1000 "${t[@]}" --quiet

    # 8. trace (thrusters: hold-down and descent; the default; --every; a row of a rough
    #    sweep), plot of sweeps and traces, animate (small GIFs) and view (HTML).
    run none trace-default trace --out traces/default.arrow
    run none trace-default-every trace --sample 5 --every 20 --out traces/default-5-every20.arrow
    run none trace-params trace --scenario inputs/params.toml --seed 7 --sample 3 --every 5 \
        --out traces/params-seed7-3.arrow
    run none trace-hold-down trace --scenario inputs/scenarios/hold-down.toml --sample 1 \
        --out traces/hold-down.arrow
    run none trace-descent trace --scenario inputs/scenarios/descent.toml --sample 2 \
        --every 10 --out traces/descent.arrow
    run none trace-rough-sweep trace --sweep sweeps/rough.arrow --sample 7 \
        --out traces/rough-7.arrow
    run none plot-default plot default.arrow --out-dir plots/default
    run none plot-hold-down-sweep plot sweeps/hold-down.arrow --out-dir plots/hold-down-sweep
    run none plot-trace-hold-down plot traces/hold-down.arrow --out-dir plots/trace-hold-down
    run none plot-trace-descent plot traces/descent.arrow --out-dir plots/trace-descent
    run none plot-trace-default plot traces/default.arrow   # beside the trace
    run animate animate-default animate traces/default-5-every20.arrow --size 160x120 --fps 5 \
        --out anim/default.gif
    run animate animate-hold-down animate traces/hold-down.arrow --size 160x120 --fps 4 \
        --speed 20 --out anim/hold-down.gif
    run none view-hold-down view traces/hold-down.arrow --out view/hold-down.html
    run none view-default view traces/default.arrow   # beside the trace
    run none view-descent view traces/descent.arrow --out view/descent.html

    # 9. report on a terrain of slopes (README "Success on a real terrain").
    run none report-flat-rayleigh report sweeps/flat.arrow --slope-distribution rayleigh:10
    run none report-flat-normal report sweeps/flat.arrow --slope-distribution normal:30:8
    run none report-flat-bins report sweeps/flat.arrow --slope-distribution inputs/terrain-bins.csv

    # A landing-site map (its five files) of the Didymos model.
    run site site-didymos site inputs/didymos.obj --units km --density 2170 --spin-period 2.26 \
        --samples 2000 "${t[@]}" --quiet --out-dir site-didymos
    run none report-flat-exponential report sweeps/flat.arrow --slope-distribution exponential:8
    run none report-default-rayleigh report default.arrow --slope-distribution rayleigh:10

    # 10. Refusals: exit 2 and their messages.
    must_fail refuse-unknown-key sweep --scenario inputs/bad-key.toml --samples 10 --out bad.arrow
    must_fail refuse-table-row sweep --inputs inputs/bad-table.csv --out bad-table.arrow
    must_fail refuse-missing-shard merge shards/default.shard-0.arrow \
        shards/default.shard-1.arrow --out bad-merge.arrow
    must_fail refuse-independent-sensitivity sensitivity default.arrow
    must_fail refuse-terrain report sweeps/flat.arrow --slope-distribution rayleigh:20
}

# run_with NAME BINARY: the whole set with BINARY in $work/NAME.
run_with() {
    set_name=$1
    logs=$work/logs/$set_name
    mkdir -p "$work/$set_name" "$logs" "$work/bin/$set_name"
    # Both binaries run under the name `touchdown`: clap's usage lines print the name the
    # program was called by.
    ln -s "$2" "$work/bin/$set_name/touchdown"
    bin=$work/bin/$set_name/touchdown
    cp -r "$work/inputs" "$work/$set_name/inputs"
    local start end
    start=$(date +%s.%N)
    # Not in a subshell: `failed` must outlive the set.
    cd "$work/$set_name"
    run_set
    cd "$work"
    end=$(date +%s.%N)
    awk -v n="$set_name" -v b="$2" -v a="$start" -v e="$end" \
        'BEGIN { printf "same-bytes: %s (%s): %.1f s\n", n, b, e - a }' >&2
    # sed, not head: head would close the pipe while sort still writes (SIGPIPE, and the
    # script ends under pipefail once times.txt outgrows one write).
    sort -rn "$logs/times.txt" | sed -n "1,5s/^/same-bytes: $set_name: slowest: /p" >&2
}

# ---------------------------------------------------------------------------------------
# Comparing.

# The engine string a set's binary writes (`touchdown.engine`, Parquet's created_by):
# as its report of the default sweep names it ("2000 samples, seed 1, touchdown 0.8.0.").
engine_of() {
    sed -n 's/^[0-9]* samples, seed [0-9]*, \(.*\)\.$/\1/p' "$work/$1/cmd/report-default.stdout" \
        2>/dev/null | head -n 1
}

# arrow_equal_but_version OLD NEW: 0 if the two Arrow (file or stream) or Parquet files hold
# the same schema (field metadata included), the same metadata but `touchdown.engine` (and
# Parquet's created_by, which is the engine too), the same batches or row groups and the
# same bits in every column; prints what differs otherwise.
arrow_equal_but_version() {
    "$py" - "$1" "$2" <<'PY'
import sys
import pyarrow as pa
import pyarrow.ipc as ipc
import pyarrow.parquet as pq

VERSION_KEY = b"touchdown.engine"

def load(path):
    with open(path, "rb") as f:
        head = f.read(8)
    if head[:4] == b"PAR1":
        pf = pq.ParquetFile(path)
        md = pf.metadata
        # created_by is the engine (set_created_by(ENGINE)); ARROW:schema is the schema
        # (with its metadata, the engine in it) serialised: compared as pf.schema_arrow.
        kv = {k: v for k, v in (md.metadata or {}).items()
              if k not in (VERSION_KEY, b"ARROW:schema")}
        layout = [(md.row_group(i).num_rows,
                   tuple((md.row_group(i).column(j).compression,
                          md.row_group(i).column(j).encodings)
                         for j in range(md.num_columns)))
                  for i in range(md.num_row_groups)]
        parts = [pf.read_row_group(i) for i in range(md.num_row_groups)]
        return "parquet", pf.schema_arrow, kv, layout, parts
    if head[:6] == b"ARROW1":
        r = ipc.open_file(path)
        parts = [r.get_batch(i) for i in range(r.num_record_batches)]
        return "arrow file", r.schema, {}, [p.num_rows for p in parts], parts
    r = ipc.open_stream(path)
    parts = list(r)
    return "arrow stream", r.schema, {}, [p.num_rows for p in parts], parts

def without_version(schema):
    meta = {k: v for k, v in (schema.metadata or {}).items() if k != VERSION_KEY}
    return schema.with_metadata(meta)

def bits(part):
    # The columns (and their fields' metadata) as IPC bytes: bit for bit, NaN payloads
    # included; the schema's metadata is compared apart.
    sink = pa.BufferOutputStream()
    table = pa.Table.from_batches([part]) if isinstance(part, pa.RecordBatch) else part
    table = table.replace_schema_metadata(None)
    with ipc.new_stream(sink, table.schema) as w:
        w.write_table(table)
    return sink.getvalue().to_pybytes()

def plain_type(t):
    return t.value_type if pa.types.is_dictionary(t) else t

def plain(schema):
    # The schema with each coded (dictionary) column as its texts.
    return pa.schema([f.with_type(plain_type(f.type)) for f in schema], schema.metadata)

def as_table(part):
    return pa.Table.from_batches([part]) if isinstance(part, pa.RecordBatch) else part

def texts(column):
    return column.cast(plain_type(column.type)).to_pylist()

def encoding_changes(a, b):
    # What differs where the values do not: columns coded otherwise, Parquet's encodings or
    # compression; None if the values differ too (or the schemas do otherwise).
    changes = []
    sa, sb = without_version(a[1]), without_version(b[1])
    pa_, pb_ = plain(sa), plain(sb)
    if pa_.serialize().to_pybytes() != pb_.serialize().to_pybytes() or a[2] != b[2]:
        return None
    coded = [f"{x.name} {x.type} -> {y.type}" for x, y in zip(sa, sb) if x.type != y.type]
    if coded:
        changes.append("coded otherwise: " + ", ".join(coded))
    if a[0] == "parquet":
        if [r for r, _ in a[3]] != [r for r, _ in b[3]]:
            return None
        if a[3] != b[3]:
            ca = {c for _, cols in a[3] for c, _ in cols}
            cb = {c for _, cols in b[3] for c, _ in cols}
            changes.append("Parquet encodings" + (f", compression {'/'.join(sorted(ca))} -> "
                                                  f"{'/'.join(sorted(cb))}" if ca != cb else ""))
    elif a[3] != b[3]:
        return None
    # The columns coded on either side compared as texts; all others bit for bit (in
    # Parquet where they hold a value: what its reader puts under a null depends on the
    # encoding).
    recoded = [x.name for x, y in zip(sa, sb) if x.type != y.type]
    for x, y in zip(a[4], b[4]):
        x, y = as_table(x), as_table(y)
        for n in x.column_names:
            cx, cy = x.column(n), y.column(n)
            if n in recoded:
                same = texts(cx) == texts(cy)
            elif a[0] != "parquet":
                same = bits(pa.table({n: cx})) == bits(pa.table({n: cy}))
            else:
                same = (cx.is_null().to_pylist() == cy.is_null().to_pylist()
                        and bits(pa.table({n: cx.drop_null()})) == bits(pa.table({n: cy.drop_null()})))
            if not same:
                return None
    return changes or None

a, b = (load(p) for p in sys.argv[1:3])
why = []
if a[0] != b[0]:
    why.append(f"kinds {a[0]} / {b[0]}")
else:
    sa, sb = without_version(a[1]), without_version(b[1])
    if sa.serialize().to_pybytes() != sb.serialize().to_pybytes():
        ma, mb = sa.metadata or {}, sb.metadata or {}
        keys = sorted(k.decode() for k in set(ma) | set(mb) if ma.get(k) != mb.get(k))
        why.append("schema differs" + (f" (metadata keys {', '.join(keys)})" if keys else
                                        " (fields or their metadata)"))
    if a[2] != b[2]:
        why.append("Parquet key-value metadata differs")
    if a[3] != b[3]:
        why.append("batches / row groups differ")
    elif sa.names == sb.names:
        for i, (pa_, pb_) in enumerate(zip(a[4], b[4])):
            if bits(pa_) != bits(pb_):
                cols = [n for n in sa.names if not pa_.column(n).equals(pb_.column(n))]
                why.append(f"batch {i} differs (columns {', '.join(cols[:8]) or 'bits'}"
                           f"{' ...' if len(cols) > 8 else ''})")
                break
ea = (a[1].metadata or {}).get(VERSION_KEY, b"(none)").decode()
eb = (b[1].metadata or {}).get(VERSION_KEY, b"(none)").decode()
if why:
    changes = encoding_changes(a, b) if a[0] == b[0] else None
    if changes:
        print("; ".join(changes) + (f"; {ea} / {eb}" if ea != eb else ""))
        sys.exit(3)
    print("; ".join(why))
    sys.exit(1)
print(f"{ea} / {eb}")
PY
}

# text_equal_but_version OLD NEW: 0 if OLD with the old engine string replaced by the new
# one is NEW (report's "N samples, seed S, touchdown X.Y.Z.").
text_equal_but_version() {
    [[ -n $old_engine && -n $new_engine && $old_engine != "$new_engine" ]] || return 1
    grep -qF -- "$old_engine" "$1" || return 1
    local pat
    pat=$(printf '%s' "$old_engine" | sed 's/[][\.*^$/]/\\&/g')
    local rep
    rep=$(printf '%s' "$new_engine" | sed 's/[\/&]/\\&/g')
    sed "s/$pat/$rep/g" "$1" | cmp -s - "$2"
}

compare_dirs() {
    local n_cmp=0 n_eq=0 n_ver=0 n_enc=0 n_diff=0 n_only=0 f a b why= kind ok
    # File names of both folders, sorted and joined.
    comm -3 <(cd "$work/old" && find . -type f | sort) <(cd "$work/new" && find . -type f | sort) \
        >"$work/logs/only-in-one.txt" || true
    while IFS= read -r line; do
        if [[ $line == $'\t'* ]]; then
            echo "only in new  ${line#$'\t'./}"
        else
            echo "only in old  ${line#./}"
        fi
        n_only=$((n_only + 1))
    done <"$work/logs/only-in-one.txt"
    while IFS= read -r f; do
        a=$work/old/$f
        b=$work/new/$f
        n_cmp=$((n_cmp + 1))
        if [[ $(sha256sum <"$a" | cut -d' ' -f1) == $(sha256sum <"$b" | cut -d' ' -f1) ]]; then
            echo "equal        $f"
            n_eq=$((n_eq + 1))
            continue
        fi
        case $(head -c 6 "$a" | od -An -c | tr -d ' \n') in
            PAR1* | ARROW1 | 377377377377*) kind=arrow ;;
            *) kind=other ;;
        esac
        ok=1
        if [[ $kind == arrow && $have_pyarrow == 1 ]]; then
            why=$(arrow_equal_but_version "$a" "$b" 2>&1) && ok=0 || ok=$?
            [[ $ok == 3 ]] || [[ $ok == 0 ]] || ok=1
            why=${why##*$'\n'}   # the last line: a python error's own
        elif [[ $kind == arrow ]]; then
            why="no python with pyarrow to look inside"
        fi
        if [[ $ok == 0 ]]; then
            echo "equal but the version  $f  ($why)"
            n_eq=$((n_eq + 1)); n_ver=$((n_ver + 1))
        elif [[ $ok == 3 ]]; then
            echo "same values, encoded otherwise  $f  ($why)"
            n_enc=$((n_enc + 1))
        elif [[ $kind == other ]] && text_equal_but_version "$a" "$b"; then
            echo "equal but the version  $f"
            n_eq=$((n_eq + 1)); n_ver=$((n_ver + 1))
        else
            echo "DIFFERENT    $f${why:+  ($why)}"
            n_diff=$((n_diff + 1))
        fi
        why=
    done < <(comm -12 <(cd "$work/old" && find . -type f | sort) \
                      <(cd "$work/new" && find . -type f | sort) | sed 's|^\./||')
    echo
    echo "$n_cmp files compared, $n_eq equal, $n_enc the same values encoded otherwise, $n_diff different"
    [[ $n_ver -eq 0 ]] || echo "($n_ver of the equal ones differ in the engine version alone: $old_engine / $new_engine)"
    if [[ $n_enc -gt 0 && ${SAME_BYTES_ENCODINGS:-} != allow ]]; then
        echo "FAILED: $n_enc files hold the same values encoded otherwise: a change of encoding, not a move of code (SAME_BYTES_ENCODINGS=allow accepts it)"
        n_diff=$((n_diff + n_enc))
    fi
    [[ $n_only -eq 0 ]] || echo "$n_only files in one folder only"
    [[ $have_pyarrow == 1 ]] || echo "(no python with pyarrow: an Arrow or Parquet file that differs in its bytes is DIFFERENT even if only its engine version does)"
    [[ $n_diff -eq 0 && $n_only -eq 0 ]]
}

# ---------------------------------------------------------------------------------------

rm -rf "$work/old" "$work/new" "$work/logs" "$work/inputs" "$work/bin"
mkdir -p "$work/logs"
make_inputs "$work/inputs"
run_with old "$old_bin"
run_with new "$new_bin"
old_engine=$(engine_of old)
new_engine=$(engine_of new)

status=0
compare_dirs || status=1
if [[ ${#failed[@]} -gt 0 ]]; then
    echo "${#failed[@]} commands exited otherwise than they should (logs in $work/logs):"
    printf '  %s\n' "${failed[@]}"
    status=1
fi
exit "$status"
