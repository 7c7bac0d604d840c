#!/usr/bin/env bash
# Takes docs/lcm-spy.png: lcm-spy (scripts/spy.sh, with the message jar)
# under Xvfb while a server runs the default scene and contactsim-ctl adds a
# body; the STATE row opened (xdotool double-click) beside the channel list,
# then ImageMagick's import of the virtual screen (docs/packaging.md,
# "lcm-spy"). A one-off, not a test: it needs xvfb, xauth, xdotool and
# imagemagick, which `make deps` does not install.
#   scripts/spy_screenshot.sh [BUILD_DIR] [OUT.png]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:-build}
OUT=$(realpath -m "${2:-docs/lcm-spy.png}")
URL="udpm://239.255.76.67:7698?ttl=0&recv_buf_size=8388608"
for tool in xvfb-run xdotool import; do
  command -v $tool >/dev/null \
    || { echo "spy-screenshot: needs $tool (apt-get install xvfb xauth xdotool imagemagick)" >&2; exit 1; }
done
cmake --build "$BUILD" --target contactsim_lcmtypes_jar contactsim-server contactsim-ctl >/dev/null
"$BUILD/bin/contactsim-server" --config config/server.pbtxt --lcm-url "$URL" --no-live-line >/dev/null 2>&1 &
server=$!
trap 'kill -INT $server 2>/dev/null; wait $server 2>/dev/null || true' EXIT
# lcm-spy scans its class path for ~10 s before its window opens; a channel
# is listed from its first message on (rows sorted by name: BODY_CMD,
# CONTACTS, REPLY, STATE, ...; 16 px each below a 20 px header)
xvfb-run -a -s "-screen 0 1450x600x24" bash -c "
  bash scripts/spy.sh '$BUILD' --lcm-url='$URL' >/dev/null 2>&1 & spy=\$!
  sleep ${SPY_SECONDS:-14}
  '$BUILD/bin/contactsim-ctl' --lcm-url '$URL' add sphere --radius 0.2 --position 0 0 3 --density 500 >/dev/null
  sleep 2
  list=\$(xdotool search --name 'LCM Spy' | head -1)
  xdotool mousemove --window \$list 80 76 click --repeat 2 --delay 80 1
  sleep 2
  view=\$(xdotool search --name 'CONTACTSIM_STATE' | head -1)
  xdotool windowmove \$view 800 0 windowsize \$view 650 600
  sleep 3
  import -window root '$OUT'
  kill \$spy"
echo "spy-screenshot: $OUT"
