#!/bin/bash
# Runs MBDyn and romdyn on every .mbd file of a folder and prints, per file: whether each
# program accepted and ran it, the final position of every node both wrote to the .mov,
# the eigenvalues of the first eigenanalysis (from the .m files), and the relative
# differences. A reference check for issue 12, run by hand: never in CI, never from
# `cargo test`. MBDyn is not built or shipped here: point MBDYN at an installed binary.
#
#   scripts/compare_mbdyn.sh FOLDER [OUTDIR]
#   MBDYN=/path/to/mbdyn ROMDYN=target/release/romdyn scripts/compare_mbdyn.sh examples
#   TIMEOUT=60 scripts/compare_mbdyn.sh /work/mbdyn-collection   (see mbdyn_collection.sh)
#   ROMDYN_ARGS="--beam-update path-independent" scripts/compare_mbdyn.sh examples
#   CPU=120 TIMEOUT=600 nice -n 5 scripts/compare_mbdyn.sh DIR   (120 s of CPU per run)
#
# The files are FOLDER/*.mbd, or the paths listed in FOLDER/list.txt when it exists (MBDyn
# input files often have no extension). Each program runs in the file's own directory (so
# `include:` and file drivers find their neighbours), limited to TIMEOUT seconds (600) of
# wall time and, when CPU is set, to CPU seconds of CPU time (`ulimit -t`; a run stopped by
# either is a timeout).
# OUTDIR/summary.tsv gets one line a file: name, mbdyn ok|failed|timeout, romdyn
# ok|failed|timeout, romdyn's first error message without its file:line:col, worst position
# and eigenvalue differences, the worst eigenvalue difference beyond what MBDyn's printed
# digits allow (KEEP=0 deletes each run's output files once compared, keeping
# stdout and stderr); the end of the run prints the counts and romdyn's refusals
# grouped by message. MBDYN_OUTPUTS=DIR keeps MBDyn's runs in DIR and reuses them on the
# next call (a file's MBDyn run is redone only when DIR/NAME.mbdyn/state is missing): MBDyn
# does not change between romdyn's versions, so re-measuring romdyn then costs romdyn's runs.
#
# Output, per file:
#   FILE  mbdyn: ok|failed (last message)  romdyn: ok|failed (first error line)
#   node LABEL  x y z (mbdyn)  x y z (romdyn)  |Δx|/max(|x|, 1)
#   eig  Re Im (mbdyn, ±U relative by its printed digits)  Re Im (romdyn, the nearest)  |Δλ|/|λ|  [(within MBDyn's printed digits)]
#                                                        (eigenvalues with Im > 1e-3 rad/s and > 1e-3 |λ|, by Im: numerically split zero or real eigenvalues are not modes)
#   worst: position RELDIFF, eigenvalue RELDIFF (RELDIFF beyond MBDyn's printed digits)
set -u
# Extra options of `romdyn run` (e.g. MBDyn's incremental beams), split on spaces.
read -r -a romdyn_args <<< "${ROMDYN_ARGS:-}"
folder=${1:?usage: compare_mbdyn.sh FOLDER [OUTDIR]}
out=${2:-$(mktemp -d /tmp/compare_mbdyn.XXXXXX)}
mbdyn=${MBDYN:-$HOME/mbdyn/bin/mbdyn}
romdyn=${ROMDYN:-$(dirname "$0")/../target/debug/romdyn}
[ -x "$mbdyn" ] || { echo "MBDyn not found at $mbdyn (set MBDYN)" >&2; exit 2; }
[ -x "$romdyn" ] || { echo "romdyn not found at $romdyn (set ROMDYN, or cargo build)" >&2; exit 2; }
mkdir -p "$out"

# Last output instant of a .mov: "label x y z" per node (the rows after the last repeat of
# the first label).
last_positions() {
    awk 'NR == 1 { first = $1 } $1 == first { n = 0; delete rows } { rows[n++] = $1 " " $2 " " $3 " " $4 } END { for (i = 0; i < n; i++) print rows[i] }' "$1"
}

# Eigenvalues λ = (1/dCoef)(Λ − 1)/(Λ + 1), Λ = (αr + j αi)/β, from an eigenanalysis .m
# file's dCoef and alpha rows; the modes, Im λ > 1e-3 rad/s and > 1e-3 |λ| (a real eigenvalue
# that round-off split into a pair, −6.07e4 ± 3.2j rad/s in MBDyn's croce_shaker_v1 where
# romdyn's is real, is not one), sorted by Im λ: "Re Im BOUND", BOUND the
# largest change of λ the rounding of the printed αr, αi, β (half a unit of their last
# digit) allows: |dλ/dΛ| |ΔΛ| = 2 |ΔΛ| / (dCoef |Λ + 1|²), |ΔΛ| ≤ (|Δαr| + |Δαi| + |Λ| |Δβ|)/|β|.
# MBDyn 1.7.3 prints 7 digits unless the file says `results output precision` (eigenanalysis)
# or `output precision` (control data); with a small `parameter`, Λ ≈ 1 and the bound is
# large: on eig/joints/revolutehinge (parameter 1e-6) ±0.82 rad/s, its damping −6.531 s⁻¹
# printed against −6.6666666697 with 16 digits (the closed form −C/(2J) = −20/3).
eigenvalues() {
    awk '
        function half_unit(s,   n, parts, m, e, p) {
            n = split(s, parts, /[eE]/); m = parts[1]; e = (n > 1) ? parts[2] + 0 : 0
            p = index(m, "."); return 0.5 * 10 ^ (e - ((p > 0) ? length(m) - p : 0))
        }
        /^dCoef *=/ { v = $0; sub(/^dCoef *= */, "", v); sub(/;.*/, "", v); dcoef = v + 0 }
        /^alpha *= *\[/ { inside = 1; sub(/^alpha *= *\[/, "") }
        inside {
            line = $0; last = (line ~ /\]/); gsub(/[];[]/, " ", line)
            n = split(line, a, " ")
            if (n >= 3) {
                ar = a[1]; ai = a[2]; b = a[3]
                d = dcoef * ((ar + b) ^ 2 + ai ^ 2)
                if (d != 0 && b != 0) {
                    re = (ar ^ 2 + ai ^ 2 - b ^ 2) / d; im = 2 * ai * b / d
                    ab = (b < 0) ? -b : b
                    dl = (half_unit(a[1]) + half_unit(a[2]) + sqrt(ar ^ 2 + ai ^ 2) / ab * half_unit(a[3])) / ab
                    if (im > 1e-3 && im > 1e-3 * sqrt(re ^ 2 + im ^ 2)) printf "%.10e %.10e %.3e\n", re, im, 2 * dl * b ^ 2 / d
                }
            }
            if (last) inside = 0
        }' "$1" | sort -g -k2
}

# Pairs the eigenvalues of the first list ("Re Im BOUND" rows) with those of the second,
# the closest pair (relative to the first's modulus) first, then the closest of the rest:
# "Re Im BOUND Re Im", in the first list's order; one left without a partner prints "-"
# for it. Pairing by rank went astray where one program reports a numerically split zero
# pair (a free body's rigid motion, |λ| ≈ √ε ω) above the Im > 1e-3 rad/s filter and the
# other not (eig/eigfree), or a huge eigenvalue of a nearly singular pencil (−2e6 rad/s in
# croce_analisi_modale_smorzato's MBDyn run) the other does not have.
pair_nearest() {
    awk 'FNR == NR { m[++nm] = $0; next } { r[++nr] = $0 }
        END {
            for (i = 1; i <= nm; i++) { split(m[i], a, " "); mr[i] = a[1]; mi[i] = a[2]; mn[i] = sqrt(a[1] ^ 2 + a[2] ^ 2); if (mn[i] == 0) mn[i] = 1 }
            for (j = 1; j <= nr; j++) { split(r[j], b, " "); rr[j] = b[1]; ri[j] = b[2] }
            left = (nm < nr) ? nm : nr
            while (left-- > 0) {
                best = 0
                for (i = 1; i <= nm; i++) {
                    if (i in partner) continue
                    for (j = 1; j <= nr; j++) {
                        if (j in taken) continue
                        d = sqrt((mr[i] - rr[j]) ^ 2 + (mi[i] - ri[j]) ^ 2) / mn[i]
                        if (best == 0 || d < bestd) { best = i; bj = j; bestd = d }
                    }
                }
                partner[best] = bj; taken[bj] = 1
            }
            for (i = 1; i <= nm; i++) print m[i], (i in partner) ? rr[partner[i]] " " ri[partner[i]] : "- -"
        }' "$1" "$2"
}

limit=${TIMEOUT:-600}
cpu=${CPU:-unlimited}
# Exit status of a run stopped by the wall-clock or the CPU limit (SIGXCPU, or SIGKILL past
# the hard limit): 124, 152, 137.
run_state() { case $1 in 0) echo ok ;; 124|152|137) echo timeout ;; *) echo failed ;; esac; }
case "$mbdyn" in /*) ;; *) mbdyn=$(pwd)/$mbdyn ;; esac
case "$romdyn" in /*) ;; *) romdyn=$(pwd)/$romdyn ;; esac
case "$out" in /*) ;; *) out=$(pwd)/$out ;; esac
files() {
    if [ -f "$folder/list.txt" ]; then
        while IFS= read -r p; do [ -n "$p" ] && echo "$folder/$p"; done < "$folder/list.txt"
    else
        for f in "$folder"/*.mbd; do [ -e "$f" ] && echo "$f"; done
    fi
}
: > "$out/summary.tsv"
while IFS= read -r f; do
    rel=${f#"$folder"/}; name=$(echo "${rel%.mbd}" | tr '/ ' '__')
    dir=$(dirname "$f"); base=$(basename "$f")
    m="${MBDYN_OUTPUTS:-$out}/$name.mbdyn"; r="$out/$name.romdyn"
    mkdir -p "$m" "$r"
    if [ -n "${MBDYN_OUTPUTS:-}" ] && [ -s "$m/state" ]; then
        mstate=$(cat "$m/state")
    else
        mstate=$( (cd "$dir" && ulimit -t "$cpu" && timeout "$limit" "$mbdyn" -f "$base" -o "$m/$name" > "$m/stdout" 2>&1 < /dev/null); run_state $?)
        echo "$mstate" > "$m/state"
    fi
    rstate=$( (cd "$dir" && ulimit -t "$cpu" && timeout "$limit" "$romdyn" run "$base" ${romdyn_args[@]+"${romdyn_args[@]}"} -o "$r/$name" > "$r/stdout" 2> "$r/stderr" < /dev/null); run_state $?)
    ms=$mstate; [ "$mstate" = failed ] && ms="failed ($(grep -v '^$' "$m/stdout" | grep -iv 'aborting' | tail -1))"
    rerr=$(grep -m1 -E 'error' "$r/stderr" | tr '\t' ' ' | sed -E 's/^[^ ]*:[0-9]+:[0-9]+: //; s/^error: //')
    [ -z "$rerr" ] && rerr=$(head -1 "$r/stderr")
    rs=$rstate; [ "$rstate" = failed ] && rs="failed ($rerr)"
    echo "$name  mbdyn: $ms  romdyn: $rs"
    worst_x=0; worst_l=0; worst_beyond=0
    if [ -s "$m/$name.mov" ] && [ -s "$r/$name.mov" ]; then
        while read -r label mx my mz rx ry rz; do
            d=$(awk -v a="$mx" -v b="$my" -v c="$mz" -v p="$rx" -v q="$ry" -v s="$rz" 'BEGIN { n = sqrt(a*a + b*b + c*c); if (n < 1) n = 1; printf "%.2e", sqrt((a-p)^2 + (b-q)^2 + (c-s)^2) / n }')
            echo "  node $label  $mx $my $mz (mbdyn)  $rx $ry $rz (romdyn)  $d"
            worst_x=$(awk -v a="$worst_x" -v b="$d" 'BEGIN { print (b + 0 > a + 0) ? b : a }')
        done < <(join <(last_positions "$m/$name.mov" | sort -k1,1) <(last_positions "$r/$name.mov" | sort -k1,1) | sort -n -k1,1)
    fi
    me=$(ls "$m"/*.m 2>/dev/null | head -1); re=$(ls "$r"/*.m 2>/dev/null | head -1)
    if [ -n "$me" ] && [ -n "$re" ]; then
        while read -r a b u c d _; do
            if [ "$c" = - ]; then echo "  eig  $a $b (mbdyn, ±$u by its printed digits)  (no romdyn eigenvalue left to pair)"; continue; fi
            rel=$(awk -v a="$a" -v b="$b" -v c="$c" -v d="$d" 'BEGIN { n = sqrt(a*a + b*b); if (n == 0) n = 1; printf "%.2e", sqrt((a-c)^2 + (b-d)^2) / n }')
            digits=$(awk -v a="$a" -v b="$b" -v u="$u" 'BEGIN { n = sqrt(a*a + b*b); if (n == 0) n = 1; printf "%.2e", u / n }')
            within=""; awk -v r="$rel" -v u="$digits" 'BEGIN { exit !(r + 0 <= u + 0) }' && within="  (within MBDyn's printed digits)"
            echo "  eig  $a $b (mbdyn, ±$digits relative by its printed digits)  $c $d (romdyn, the nearest)  $rel$within"
            worst_l=$(awk -v x="$worst_l" -v y="$rel" 'BEGIN { print (y + 0 > x + 0) ? y : x }')
            [ -z "$within" ] && worst_beyond=$(awk -v x="$worst_beyond" -v y="$rel" 'BEGIN { print (y + 0 > x + 0) ? y : x }')
        done < <(pair_nearest <(eigenvalues "$me") <(eigenvalues "$re"))
    fi
    echo "  worst: position $worst_x, eigenvalue $worst_l ($worst_beyond beyond MBDyn's printed digits)"
    [ "$rstate" = failed ] || rerr=""
    [ "${KEEP:-1}" = 0 ] && find "$r" -type f ! -name stdout ! -name stderr -delete
    [ "${KEEP:-1}" = 0 ] && [ -z "${MBDYN_OUTPUTS:-}" ] && find "$m" -type f ! -name stdout ! -name stderr ! -name state -delete
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$mstate" "$rstate" "$rerr" "$worst_x" "$worst_l" "$worst_beyond" >> "$out/summary.tsv"
done < <(files)
echo
echo "files: $(wc -l < "$out/summary.tsv")"
echo "mbdyn ok: $(awk -F'\t' '$2 == "ok"' "$out/summary.tsv" | wc -l), romdyn ok: $(awk -F'\t' '$3 == "ok"' "$out/summary.tsv" | wc -l), both ok: $(awk -F'\t' '$2 == "ok" && $3 == "ok"' "$out/summary.tsv" | wc -l)"
echo "romdyn's refusals, grouped (numbers and quoted names kept):"
awk -F'\t' '$3 == "failed" { print $4 }' "$out/summary.tsv" | sort | uniq -c | sort -rn
echo "files in $out"
