#!/bin/bash
# Runs MBDyn and romdyn on every .mbd file of a folder and prints, per file: whether each
# program accepted and ran it, the final position of every node both wrote to the .mov,
# the eigenvalues of the first eigenanalysis (from the .m files), and the relative
# differences. A reference check for issue 12, run by hand: never in CI, never from
# `cargo test`. MBDyn is not built or shipped here: point MBDYN at an installed binary.
#
#   scripts/compare_mbdyn.sh FOLDER [OUTDIR]
#   MBDYN=/path/to/mbdyn ROMDYN=target/release/romdyn scripts/compare_mbdyn.sh examples
#
# Output, per file:
#   FILE  mbdyn: ok|failed (last message)  romdyn: ok|failed (first error line)
#   node LABEL  x y z (mbdyn)  x y z (romdyn)  |Δx|/max(|x|, 1)
#   eig  Re Im (mbdyn)  Re Im (romdyn)  |Δλ|/|λ|         (eigenvalues with Im > 1e-3 rad/s, by Im: numerically split zero eigenvalues, |λ| ≈ 1e-6, are not modes)
#   worst: position RELDIFF, eigenvalue RELDIFF
set -u
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
# file's dCoef and alpha rows; those with Im λ > 0, sorted by Im λ.
eigenvalues() {
    awk '
        /^dCoef *=/ { v = $0; sub(/^dCoef *= */, "", v); sub(/;.*/, "", v); dcoef = v + 0 }
        /^alpha *= *\[/ { inside = 1; sub(/^alpha *= *\[/, "") }
        inside {
            line = $0; last = (line ~ /\]/); gsub(/[];[]/, " ", line)
            n = split(line, a, " ")
            if (n >= 3) {
                ar = a[1]; ai = a[2]; b = a[3]
                d = dcoef * ((ar + b) ^ 2 + ai ^ 2)
                if (d != 0 && b != 0) { re = (ar ^ 2 + ai ^ 2 - b ^ 2) / d; im = 2 * ai * b / d; if (im > 1e-3) printf "%.10e %.10e\n", re, im }
            }
            if (last) inside = 0
        }' "$1" | sort -g -k2
}

for f in "$folder"/*.mbd; do
    [ -e "$f" ] || continue
    name=$(basename "$f" .mbd)
    m="$out/$name.mbdyn"; r="$out/$name.romdyn"
    mkdir -p "$m" "$r"
    if timeout 600 "$mbdyn" -f "$f" -o "$m/$name" > "$m/stdout" 2>&1; then ms="ok"; else ms="failed ($(grep -v '^$' "$m/stdout" | grep -iv 'aborting' | tail -1))"; fi
    if timeout 600 "$romdyn" run "$f" -o "$r/$name" > "$r/stdout" 2> "$r/stderr"; then rs="ok"; else rs="failed ($(head -1 "$r/stderr"))"; fi
    echo "$name  mbdyn: $ms  romdyn: $rs"
    worst_x=0; worst_l=0
    if [ -s "$m/$name.mov" ] && [ -s "$r/$name.mov" ]; then
        while read -r label mx my mz rx ry rz; do
            d=$(awk -v a="$mx" -v b="$my" -v c="$mz" -v p="$rx" -v q="$ry" -v s="$rz" 'BEGIN { n = sqrt(a*a + b*b + c*c); if (n < 1) n = 1; printf "%.2e", sqrt((a-p)^2 + (b-q)^2 + (c-s)^2) / n }')
            echo "  node $label  $mx $my $mz (mbdyn)  $rx $ry $rz (romdyn)  $d"
            worst_x=$(awk -v a="$worst_x" -v b="$d" 'BEGIN { print (b + 0 > a + 0) ? b : a }')
        done < <(join <(last_positions "$m/$name.mov" | sort -k1,1) <(last_positions "$r/$name.mov" | sort -k1,1) | sort -n -k1,1)
    fi
    me=$(ls "$m"/*.m 2>/dev/null | head -1); re=$(ls "$r"/*.m 2>/dev/null | head -1)
    if [ -n "$me" ] && [ -n "$re" ]; then
        while read -r a b c d; do
            rel=$(awk -v a="$a" -v b="$b" -v c="$c" -v d="$d" 'BEGIN { n = sqrt(a*a + b*b); if (n == 0) n = 1; printf "%.2e", sqrt((a-c)^2 + (b-d)^2) / n }')
            echo "  eig  $a $b (mbdyn)  $c $d (romdyn)  $rel"
            worst_l=$(awk -v x="$worst_l" -v y="$rel" 'BEGIN { print (y + 0 > x + 0) ? y : x }')
        done < <(paste -d' ' <(eigenvalues "$me") <(eigenvalues "$re") | awk 'NF == 4')
    fi
    echo "  worst: position $worst_x, eigenvalue $worst_l"
done
echo "files in $out"
