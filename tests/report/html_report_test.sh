#!/usr/bin/env bash
# The HTML report in headless Chromium (Debian's chromium-headless-shell):
# the page loads with no console error, its screenshot is not blank, and the
# final mesh's vertex count in the page equals the mesh file's. Both ways of
# making it: `fit --html` and `report REPORT.json -o`. A missing three.js is
# refused before the fit. Skips (77) without Chromium unless CI=true.
set -euo pipefail
mcquad=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
chromium=$(command -v chromium-headless-shell || command -v chromium || true)
if [[ -z "$chromium" ]]; then
  [[ "${CI:-}" == "true" ]] && { echo "no headless Chromium (install chromium-headless-shell)"; exit 1; }
  echo "skipped: no headless Chromium"; exit 77
fi
browse() {  # browse PAGE ARGS...: headless Chromium with software WebGL
  local page=$1; shift
  timeout 120 "$chromium" --no-sandbox --use-angle=swiftshader --enable-unsafe-swiftshader --window-size=1200,800 \
    --virtual-time-budget=10000 --enable-logging=stderr --v=0 "$@" "file://$page"
}
check_page() {  # check_page PAGE MESH
  local page=$1 mesh=$2
  browse "$page" --dump-dom > "$work/dom.html" 2> "$work/console.txt"
  if grep -E "CONSOLE.*(Uncaught|Error)" "$work/console.txt"; then echo "console errors in $page"; exit 1; fi
  field() { sed -n "s/.*id=\"$1\">\([^<]*\)<.*/\1/p" "$work/dom.html" | head -1; }
  [[ "$(field page-errors)" == "0" ]] || { echo "page errors: $(field page-errors)"; exit 1; }
  local in_file; in_file=$(grep -c '^v ' "$mesh")
  [[ "$(field final-vertex-count)" == "$in_file" ]] || { echo "page shows $(field final-vertex-count) vertices, $mesh has $in_file"; exit 1; }
  (( $(field rendered-pixels) > 5000 )) || { echo "only $(field rendered-pixels) pixels drawn"; exit 1; }
  browse "$page" --screenshot="$work/shot.png" 2>/dev/null >/dev/null
  python3 - "$work/shot.png" <<'PY'
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, width, height = 8, b"", 0, 0
while pos < len(data):
    length, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + length]
    if kind == b"IHDR":
        width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        assert depth == 8 and colour in (2, 6), "unexpected PNG format"
        channels = 3 if colour == 2 else 4
    elif kind == b"IDAT":
        idat += body
    pos += 12 + length
raw, stride = zlib.decompress(idat), width * channels
previous, colours = bytearray(stride), set()
for y in range(height):
    kind, line = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for i in range(stride):
        a = line[i - channels] if i >= channels else 0
        b, c = previous[i], previous[i - channels] if i >= channels else 0
        if kind == 1: line[i] = (line[i] + a) & 255
        elif kind == 2: line[i] = (line[i] + b) & 255
        elif kind == 3: line[i] = (line[i] + (a + b) // 2) & 255
        elif kind == 4:
            p = a + b - c; pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    if y % 4 == 0:
        colours.update(bytes(line[x:x + 3]) for x in range(0, 3 * (width // 2) * channels // 3, channels * 4))
    previous = line
assert len(colours) > 50, f"screenshot looks blank: {len(colours)} colours in the view"
print(f"screenshot {width}x{height}: {len(colours)} colours in the view")
PY
}

"$mcquad" generate t-shape -o "$work" --points 20000 > /dev/null
"$mcquad" fit "$work/t-shape.ply" "$work/t-shape.skeleton.obj" -o "$work/t.obj" --backend serial --iterations 8 \
  --report "$work/t.json" --html "$work/t.html" > /dev/null
check_page "$work/t.html" "$work/t.obj"
"$mcquad" report "$work/t.json" -o "$work/again.html" > /dev/null
check_page "$work/again.html" "$work/t.obj"

# three.js missing: refused before the fit, nothing written.
set +e
MCQUAD_THREE_JS_DIR=$work/none "$mcquad" fit "$work/t-shape.ply" "$work/t-shape.skeleton.obj" -o "$work/u.obj" \
  --html "$work/u.html" 2> "$work/err.txt"
code=$?
set -e
[[ $code == 6 ]] || { echo "missing three.js: exit $code, expected 6"; exit 1; }
grep -q "libjs-three" "$work/err.txt" || { cat "$work/err.txt"; exit 1; }
[[ ! -e "$work/u.obj" && ! -e "$work/u.html" ]] || { echo "outputs written despite the error"; exit 1; }
echo "HTML report: ok"
