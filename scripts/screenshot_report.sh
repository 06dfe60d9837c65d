#!/usr/bin/env bash
# Screenshots a report page (specgen report --out DIR) in headless Chromium, for review by eye:
#   scripts/screenshot_report.sh DIR [OUT.png] [HEIGHT]
# Installs Chromium with apt-get when it is missing (Debian/Ubuntu). The page is self-contained
# (inline SVG and PNG), so the screenshot needs no network.
set -euo pipefail
dir=${1:?usage: scripts/screenshot_report.sh DIR [OUT.png] [HEIGHT]}
out=${2:-$dir/screenshot.png}
height=${3:-9000}
page=$(realpath "$dir/index.html")
browser=$(command -v chromium || command -v chromium-browser || command -v google-chrome || true)
if [ -z "$browser" ]; then
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq chromium
    browser=$(command -v chromium)
fi
"$browser" --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1280,"$height" \
    --screenshot="$(realpath -m "$out")" "file://$page" 2>/dev/null
echo "$out"
