#!/usr/bin/env bash
# The X session of rviz_test.sh, run under xvfb-run: RViz with the config, the bag played into it,
# the checks (rviz_check.py), the screenshot. RViz is stopped by its PID when the session ends.
# Usage: rviz_session.sh CONFIG WORK_DIR [SCREENSHOT.png]   (WORK_DIR holds run.bag; logs go there)
set -uo pipefail
CONFIG=${1:?usage: rviz_session.sh CONFIG WORK_DIR [SCREENSHOT.png]}
WORK=${2:?usage: rviz_session.sh CONFIG WORK_DIR [SCREENSHOT.png]}
SHOT=${3:-}
PY=/usr/bin/python3
HERE=$(cd "$(dirname "$0")" && pwd)

rviz -d "$CONFIG" >"$WORK/rviz.log" 2>&1 &
RVIZ=$!
trap 'kill -TERM $RVIZ 2>/dev/null; wait $RVIZ 2>/dev/null' EXIT
# RViz has loaded the config once it subscribes to every enabled display's topic.
"$PY" "$HERE/rviz_check.py" "$CONFIG" --wait 90 || exit 1
# -d 2: RViz connects to every advertised topic before the first message (the bag's one /tf_static).
rosbag play --clock -q -d 2 "$WORK/run.bag" >"$WORK/play.log" 2>&1 || { echo "rosbag play failed"; exit 1; }
sleep 1  # RViz draws the last messages
kill -0 $RVIZ 2>/dev/null || { echo "RViz exited while the bag played"; exit 1; }
"$PY" "$HERE/rviz_check.py" "$CONFIG" --log "$WORK/rviz.log" --bag "$WORK/run.bag" || exit 1
if [ -n "$SHOT" ]; then
  xwd -root -silent | xwdtopnm 2>/dev/null | pnmtopng >"$SHOT" || { echo "screenshot failed"; exit 1; }
fi
