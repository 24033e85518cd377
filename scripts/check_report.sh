#!/usr/bin/env bash
# The HTML report in a real browser (issue 37 point 6): `romdyn rom … --report DIR` on the
# shipped beam, opened in headless Chromium. Fails unless the page's script ran to its first
# frame (body data-status="ok") and raised no error (no data-error attribute: the page
# records any uncaught error there); leaves a screenshot to look at.
# Usage: scripts/check_report.sh ROMDYN_BINARY OUT_DIR   (Chromium: Debian's `chromium`)
set -euo pipefail
bin="$1"
out="$2"
rm -rf "$out"
mkdir -p "$out"
"$bin" rom examples/simply_supported_beam.mbd --static --input 5:Fy --output 5:y --count 3 --report "$out/report" > /dev/null 2> "$out/rom.log"
browser=$(command -v chromium || command -v chromium-browser || command -v google-chrome)
page="file://$(cd "$out/report" && pwd)/index.html"
flags=(--headless --no-sandbox --disable-gpu --hide-scrollbars)
body=$(timeout 120 "$browser" "${flags[@]}" --dump-dom "$page" 2> /dev/null | grep -o '<body[^>]*>' || true)
timeout 120 "$browser" "${flags[@]}" --window-size=1100,1400 --screenshot="$out/report.png" "$page" > /dev/null 2>&1
if [[ "$body" != *'data-status="ok"'* || "$body" == *data-error* ]]; then
    echo "report check: the page did not render in Chromium: $body" >&2
    exit 1
fi
echo "report check: rendered in $("$browser" --version 2> /dev/null | head -1), screenshot $out/report.png"
