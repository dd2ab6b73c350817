#!/usr/bin/env bash
# Headless Chromium check + screenshot of the demo report (issue 11):
#   scripts/screenshot-report.sh [REPORT_DIR (default out/demo)] [PNG (default REPORT_DIR/screenshot.png)]
# Loads REPORT_DIR/index.html in a checker page (an iframe, file access allowed), then fails
# when an image did not load, a section is empty, or Chromium logged a console error; on
# success writes a full-page screenshot. Exit 0 ok, 1 check failed, 3 no Chromium (skipped;
# `scripts/install-deps.sh --browser` installs it).
set -euo pipefail
dir=$(realpath "${1:-out/demo}")
png=${2:-$dir/screenshot.png}
page="$dir/index.html"
[ -f "$page" ] || { echo "screenshot-report: $page not found (run make demo)" >&2; exit 1; }
browser=""
for b in chromium chromium-browser google-chrome; do
  if command -v "$b" >/dev/null 2>&1; then browser=$b; break; fi
done
if [ -z "$browser" ]; then
  echo "screenshot-report: skipped, no Chromium (scripts/install-deps.sh --browser installs it)" >&2
  exit 3
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# No sandbox: CI containers run as root, where Chromium's sandbox refuses to start.
flags=(--headless --no-sandbox --disable-gpu --hide-scrollbars --no-first-run --user-data-dir="$tmp/profile")

cat > "$tmp/check.html" <<HTML
<!DOCTYPE html><html><body><pre id="out">pending</pre>
<iframe id="f" src="file://$page" style="width:1280px;height:900px"></iframe>
<script>
window.addEventListener('error', e => console.error('checker: ' + e.message));
document.getElementById('f').addEventListener('load', () => {
  const w = document.getElementById('f').contentWindow, d = w.document, lines = [];
  const imgs = [...d.images];
  const bad = imgs.filter(i => !(i.complete && i.naturalWidth > 0));
  lines.push('IMAGES ' + (imgs.length - bad.length) + '/' + imgs.length);
  for (const b of bad) lines.push('BROKEN ' + b.getAttribute('src'));
  for (const s of d.querySelectorAll('section')) {
    const h = Math.round(s.getBoundingClientRect().height);
    lines.push((h > 0 ? 'SECTION ' : 'EMPTY ') + s.id + ' height=' + h + ' images=' + s.querySelectorAll('img').length +
               ' charts=' + s.querySelectorAll('svg').length + ' tables=' + s.querySelectorAll('table').length);
  }
  lines.push('HEIGHT ' + d.documentElement.scrollHeight);
  document.getElementById('out').textContent = lines.join('\n');
});
</script></body></html>
HTML

"$browser" "${flags[@]}" --allow-file-access-from-files --virtual-time-budget=30000 \
  --enable-logging=stderr --v=0 --dump-dom "file://$tmp/check.html" >"$tmp/dom.html" 2>"$tmp/log.txt" || true
report=$(sed -n '/<pre id="out">/,/<\/pre>/p' "$tmp/dom.html" | sed -e 's/.*<pre id="out">//' -e 's/<\/pre>.*//')
echo "$report"
status=0
if ! grep -q '^IMAGES' <<<"$report"; then
  echo "screenshot-report: the checker did not run:" >&2; tail -5 "$tmp/log.txt" >&2; exit 1
fi
if grep -qE '^(BROKEN|EMPTY)' <<<"$report"; then status=1; fi
if grep -q '^IMAGES 0/' <<<"$report"; then status=1; fi
# Console messages of either page, at warning level or above ("CONSOLE" lines).
if grep -E 'CONSOLE' "$tmp/log.txt" | grep -viE ':INFO:' ; then
  echo "screenshot-report: console errors above" >&2; status=1
fi
height=$(sed -n 's/^HEIGHT //p' <<<"$report")
height=$(( height > 16000 ? 16000 : (height < 600 ? 600 : height) ))
"$browser" "${flags[@]}" --window-size=1280,"$height" --screenshot="$png" "file://$page" >/dev/null 2>&1 || true
if [ ! -s "$png" ]; then echo "screenshot-report: no screenshot written" >&2; exit 1; fi
echo "screenshot-report: $png (1280×$height)$([ $status = 0 ] && echo ', every image loaded, no console errors' || echo ', CHECK FAILED')"
exit $status
