#!/usr/bin/env bash
# The Octave/MATLAB script export (issue 37 point 5) in a real Octave with its control
# package: `romdyn rom -o FILE.m` of the shipped beam, ordinary, descriptor and 2048 Hz
# discrete, each run() in Octave. sys must be an ss object with romdyn's names and sampling
# time, and its dcgain must equal the ROM's static gain that the JSON export states
# (1e-10 relative). Usage: scripts/check_octave.sh ROMDYN_BINARY OUT_DIR
# (Octave: Debian's `octave` and `octave-control`).
set -euo pipefail
bin="$1"
out="$2"
rm -rf "$out"
mkdir -p "$out"
rom=("$bin" rom examples/simply_supported_beam.mbd --static --input 5:Fy --output 5:y --count 1 --damping 0.02)
"${rom[@]}" --residualize-modes 7 -o "$out/ordinary.m" 2> /dev/null
"${rom[@]}" --residualize-modes 7 -o "$out/ordinary.json" 2> /dev/null
"${rom[@]}" --form descriptor -o "$out/descriptor.m" 2> /dev/null
"${rom[@]}" --form descriptor -o "$out/descriptor.json" 2> /dev/null
"${rom[@]}" --residualize-modes 7 --sample-rate 2048 -o "$out/discrete.m" 2> /dev/null
gain() { python3 -c "import json,sys; print(repr(json.load(open(sys.argv[1]))['rom_static_gain'][0][0]))" "$1"; }
cd "$out"
timeout 300 octave --no-gui --quiet --eval "
pkg load control;
function check(file, expected, ts)
  run(file);
  assert(isa(sys, 'ss'), [file ': sys is not an ss object']);
  assert(strcmp(sys.inputname{1}, 'node 5 Fy [N]') && strcmp(sys.outputname{1}, 'node 5 y [m]'), [file ': names']);
  assert(abs(sys.Ts - ts) <= 1e-15, [file ': sampling time']);
  g = dcgain(sys);
  assert(abs(g - expected) <= 1e-10 * abs(expected), sprintf('%s: dcgain %.15e, the ROM %.15e', file, g, expected));
  printf('%s: ss, dcgain %.12e (ROM %.12e), Ts %g\n', file, g, expected, sys.Ts);
end
check('ordinary.m', $(gain ordinary.json), 0);
check('descriptor.m', $(gain descriptor.json), 0);
check('discrete.m', $(gain ordinary.json), 1 / 2048);
"
