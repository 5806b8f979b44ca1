#!/usr/bin/env bash
# Run every scenario in this directory and print one Markdown table of the results.
#
#   scenarios/run-all.sh TOUCHDOWN OUTDIR [--samples N]
#
# TOUCHDOWN  path of the touchdown binary (e.g. target/release/touchdown)
# OUTDIR     where each scenario NAME.toml leaves NAME.arrow (the sweep), NAME.md (its
#            `touchdown report`) and NAME.log (the sweep's own summary)
# --samples  passed on to every `touchdown sweep` (accepts 1e6, 20000, ...); without it each
#            scenario runs its own `samples`
#
# The table (stdout) has per scenario: samples, wall time of the sweep, outcome shares, and
# the allowable slope of each 45-deg sector of downhill azimuth relative to X_B, in deg
# ("none": no slope in that sector has >= 99 % stable samples below it; "few": fewer than
# 100 samples in the sector; NAME.md has each slope's 95 % interval). Progress goes to
# stderr.
set -euo pipefail

usage() {
    sed -n '2,15p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
    exit "${1:-2}"
}

[[ $# -ge 1 && ( $1 == -h || $1 == --help ) ]] && usage 0
[[ $# -ge 2 ]] || usage
bin=$1
outdir=$2
shift 2
extra=()
while [[ $# -gt 0 ]]; do
    case $1 in
        --samples)
            [[ $# -ge 2 ]] || usage
            extra+=(--samples "$2")
            shift 2
            ;;
        --samples=*)
            extra+=(--samples "${1#--samples=}")
            shift
            ;;
        -h | --help) usage 0 ;;
        *)
            echo "run-all.sh: unknown argument: $1" >&2
            usage
            ;;
    esac
done

[[ -x $bin ]] || { echo "run-all.sh: not an executable: $bin" >&2; exit 2; }
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p "$outdir"
shopt -s nullglob
scenarios=("$here"/*.toml)
[[ ${#scenarios[@]} -gt 0 ]] || { echo "run-all.sh: no *.toml in $here" >&2; exit 2; }

echo "| scenario | samples | wall time s | stable % | tipped % | sliding % | bouncing % | diverged % | held % | allowable slope per sector, deg (0-45 / 45-90 / ... / 315-360) |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"
for f in "${scenarios[@]}"; do
    name=$(basename "$f" .toml)
    echo "run-all.sh: $name ..." >&2
    start=$(date +%s.%N)
    if ! "$bin" sweep --scenario "$f" --out "$outdir/$name.arrow" --quiet \
        ${extra[@]+"${extra[@]}"} >"$outdir/$name.log" 2>&1; then
        echo "run-all.sh: sweep of $name failed:" >&2
        cat "$outdir/$name.log" >&2
        exit 1
    fi
    end=$(date +%s.%N)
    "$bin" report "$outdir/$name.arrow" >"$outdir/$name.md"
    awk -F'|' -v name="$name" -v start="$start" -v end="$end" '
        function trim(s) { gsub(/^[ \t]+|[ \t]+$/, "", s); return s }
        /^[0-9]+ samples, seed/ { samples = $1 + 0 }
        /^## / { section = $0 }
        section == "## Outcomes" && /^\| (stable|tipped|sliding|bouncing|diverged|held) \|/ {
            share[trim($2)] = trim($4)
        }
        section == "## Allowable slope" && /^\| [0-9]/ {
            a = trim($5); sub(/ deg$/, "", a)
            if (a ~ /^too few/) a = "few"
            if (a ~ /^no slope/) a = "none"
            slopes = slopes (n++ ? " / " : "") a
        }
        END {
            if (n == 0 || samples == 0) { print "run-all.sh: cannot parse the report of " name > "/dev/stderr"; exit 1 }
            o = ""
            # held: listed only by the reports of sweeps with a control loop ("-" otherwise)
            split("stable tipped sliding bouncing diverged held", k, " ")
            for (i = 1; i <= 6; i++) {
                s = (k[i] in share) ? share[k[i]] : "-"; sub(/ %$/, "", s); o = o " | " s
            }
            printf "| %s | %d | %.1f%s | %s |\n", name, samples, end - start, o, slopes
        }' "$outdir/$name.md"
done
