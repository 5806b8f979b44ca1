#!/usr/bin/env bash
# The accuracy contract of the contact step's error control (MODEL.md section 2.1), over
# every sweep scenario of scenarios/: each runs three times with one seed, at a quarter of
# its step (the yardstick), at its fixed step, and under the error control, and
# `touchdown compare` pairs the last two with the first.
#
#   tests/step-contract/run.sh TOUCHDOWN WORKDIR [--samples N] [--tolerance T] [NAME...]
#
# TOUCHDOWN    the touchdown binary (e.g. target/release/touchdown)
# WORKDIR      made if missing: NAME-quarter|fixed|controlled.{toml,arrow,log} and
#              NAME-fixed|controlled.md (the comparisons with the quarter step)
# --samples    samples of every sweep (default 2000)
# --tolerance  simulation.tolerance_m_s of the controlled runs (default 1e-4)
# NAME...      only these scenarios (scenarios/NAME.toml); default: all but the studies
#              (each file's [simulation] table must be a bare `[simulation]` line, as in
#              scenarios/, and its step `step_s = X`)
#
# The contract: each outcome share of the controlled run differs from the quarter step's by
# no more than the fixed step's does, or by 0.5 points, whichever is larger; its design
# values at 99 % of the peak axial strut load, the damper stroke and the peak CG
# acceleration differ from the quarter step's by at most 1 %. Prints one Markdown row per
# scenario (steps a sample and samples/s fixed and controlled, the largest share and design
# differences of each, and whether the contract holds); exits 1 where it breaks, 2 on bad
# arguments. A design value near 0 (a damper that barely crushes) may differ by tens of
# percent at any step: the fixed step's own difference beside it shows where.
set -euo pipefail

usage() {
    sed -n '2,25p' "${BASH_SOURCE[0]}" | sed 's/^# \{0,1\}//' >&2
    exit "${1:-2}"
}
[[ $# -ge 1 && ( $1 == -h || $1 == --help ) ]] && usage 0
[[ $# -ge 2 ]] || usage
bin=$(realpath "$1")
work=$2
shift 2
samples=2000
tolerance=1e-4
names=()
while [[ $# -gt 0 ]]; do
    case $1 in
        --samples) samples=${2:?}; shift 2 ;;
        --tolerance) tolerance=${2:?}; shift 2 ;;
        -*) usage ;;
        *) names+=("$1"); shift ;;
    esac
done
[[ -x $bin ]] || { echo "run.sh: $bin is not an executable" >&2; exit 2; }
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
if [[ ${#names[@]} -eq 0 ]]; then
    for f in "$here"/scenarios/*.toml; do
        n=$(basename "$f" .toml)
        # Studies and sensitivity designs run many sweeps of their own.
        [[ $n == *study* || $n == sensitivity-* ]] && continue
        names+=("$n")
    done
fi
mkdir -p "$work"

# The scenario file with `step_s` and the error control's keys set: the [simulation]
# table's own lines for them dropped, ours put first in it (or a table of ours appended).
variant() { # FILE STEP_S [TOLERANCE]
    local keys="step_s = $2"
    [[ -n ${3:-} ]] && keys+=$'\n'"tolerance_m_s = $3"
    if grep -q '^\[simulation\]' "$1"; then
        awk -v keys="$keys" '
            /^\[/ { in_sim = ($0 == "[simulation]") }
            in_sim && /^(step_s|tolerance_m_s|step_min_s|step_max_s)[ =]/ { next }
            { print }
            $0 == "[simulation]" { print keys }' "$1"
    else
        cat "$1"
        printf '\n[simulation]\n%s\n' "$keys"
    fi
}

# The B - A column of the outcome shares and the design values of a comparison, as
# "outcome value" lines (percentage points; design values: percent).
differences() {
    awk -F'|' '
        /^## Outcome shares/ { part = "shares" }
        /^## Samples by outcome/ { part = "" }
        /^## Design values/ { part = "design" }
        part == "shares" && $2 ~ /[a-z]/ && $5 ~ /%/ { gsub(/[ %+]/, "", $5); gsub(/ /, "", $2); print $2, $5 }
        part == "design" && $2 ~ /axial strut|stroke|CG acceleration/ && $5 ~ /%/ {
            gsub(/[ %+]/, "", $5); name = $2; gsub(/^ +| +$/, "", name); gsub(/ /, "_", name); print "design:" name, $5 }' "$1"
}

echo "| scenario | steps, fixed | steps, controlled | samples/s, fixed | samples/s, controlled | largest share difference, fixed | controlled | largest design difference, fixed | controlled | contract |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---:|---|"
broken=0
for n in "${names[@]}"; do
    f=$here/scenarios/$n.toml
    [[ -f $f ]] || { echo "run.sh: no scenario $f" >&2; exit 2; }
    step=$(awk '/^\[/ { s = ($0 == "[simulation]") } s && /^step_s *=/ { print $3 }' "$f")
    step=${step:-0.001}
    quarter=$(awk -v s="$step" 'BEGIN { printf "%.10g", s / 4 }')
    variant "$f" "$quarter" > "$work/$n-quarter.toml"
    variant "$f" "$step" > "$work/$n-fixed.toml"
    variant "$f" "$step" "$tolerance" > "$work/$n-controlled.toml"
    ok=1
    for v in quarter fixed controlled; do
        if ! "$bin" sweep --scenario "$work/$n-$v.toml" --samples "$samples" \
            --out "$work/$n-$v.arrow" > "$work/$n-$v.log" 2>&1; then
            echo "| $n | the $v sweep failed ($(tail -1 "$work/$n-$v.log")) | | | | | | | | breaks |"
            ok=0
            broken=1
            break
        fi
    done
    [[ $ok == 1 ]] || continue
    field() { awk -v k="$2" 'index($0, k) == 1 { print $NF }' "$work/$n-$1.log"; }
    "$bin" compare "$work/$n-quarter.arrow" "$work/$n-fixed.arrow" > "$work/$n-fixed.md"
    "$bin" compare "$work/$n-quarter.arrow" "$work/$n-controlled.arrow" > "$work/$n-controlled.md"
    differences "$work/$n-fixed.md" > "$work/$n-fixed.differences"
    differences "$work/$n-controlled.md" > "$work/$n-controlled.differences"
    # Both comparisons must have given their shares: an empty one would pass unread.
    verdict=$(awk '
        function abs(x) { return x < 0 ? -x : x }
        # A difference that is not a number ("inf", "NaN": a design value of 0 in the quarter
        # run) breaks the contract.
        function number(x) { return x ~ /^-?[0-9]+(\.[0-9]+)?$/ }
        FNR == NR {
            fixed[$1] = $2; if ($1 !~ /^design:/) fixed_shares++
            if ($1 ~ /^design:/ && abs($2) > fd) fd = abs($2)
            next
        }
        !number($2) { bad = bad " " $1 "(" $2 ")"; next }
        $1 ~ /^design:/ { d = abs($2); if (d > design) design = d; if (d > 1) bad = bad " " substr($1, 8); next }
        {
            shares++
            c = abs($2); f = abs(fixed[$1]); allowed = f > 0.5 ? f : 0.5
            if (f > sf) sf = f
            if (c > sc) sc = c
            if (c > allowed + 1e-9) bad = bad " " $1
        }
        END {
            if (shares == 0 || fixed_shares == 0) bad = bad " (no outcome shares read)"
            printf "%.2f points | %.2f points | %.2f %% | %.2f %% | %s\n", sf, sc, fd, design, bad == "" ? "holds" : "breaks:" bad
        }' "$work/$n-fixed.differences" "$work/$n-controlled.differences")
    [[ $verdict == *breaks* ]] && broken=1
    echo "| $n | $(field fixed 'mean steps per sample') | $(field controlled 'mean steps per sample') | $(field fixed 'samples/s') | $(field controlled 'samples/s') | $verdict |"
done
exit $broken
