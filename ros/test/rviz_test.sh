#!/usr/bin/env bash
# RViz test: ros/bipednav.rviz opened in Debian's RViz under Xvfb against a recorded bag (the first
# 12 s of hexagon_dynamic, bipednav_record: the TurtleBot3 half way across among the moving boxes).
# Passes when RViz stays up, subscribes to the topic of every enabled display of the config, the
# recorded run has each of those topics, and RViz logs no error. One error is not the config's and
# is let through: under Xvfb, OpenGL is Mesa's software renderer, which rejects the link of RViz's
# indexed-colour map shader (rviz/glsl*/indexed_8bit_image) while the maps still draw (the
# screenshot shows them). With SCREENSHOT, also writes the screen at the bag's end as a PNG (xwd,
# netpbm; docs/rviz.png is one). Every process is stopped by its PID.
# Usage: rviz_test.sh BIN_DIR SOURCE_DIR [SCREENSHOT.png]
# Exit 0 pass, 1 fail, 77 skipped (rviz, Xvfb or the ROS run-time packages missing).
set -uo pipefail
BIN=${1:?usage: rviz_test.sh BIN_DIR SOURCE_DIR [SCREENSHOT.png]}
SRC=${2:?usage: rviz_test.sh BIN_DIR SOURCE_DIR [SCREENSHOT.png]}
SHOT=${3:-}
PY=/usr/bin/python3
HERE=$(cd "$(dirname "$0")" && pwd)

skip() { echo "SKIPPED: $* (install them with scripts/install-deps --ros --rviz)"; exit 77; }
for cmd in rviz xvfb-run rosmaster rosbag; do command -v $cmd >/dev/null || skip "$cmd not found"; done
[ -x "$PY" ] && "$PY" -c "import rosgraph, yaml" 2>/dev/null || skip "Debian's ROS Python modules not found"
if [ -n "$SHOT" ]; then
  for cmd in xwd xwdtopnm pnmtopng; do command -v $cmd >/dev/null || skip "$cmd not found (for the screenshot)"; done
fi
[ -x "$BIN/bipednav_record" ] || { echo "FAIL: $BIN/bipednav_record missing"; exit 1; }

WORK=$(mktemp -d /tmp/bipednav-rviz-test.XXXXXX)
PORT=$("$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://127.0.0.1:$PORT ROS_IP=127.0.0.1 ROS_HOME=$WORK ROS_LOG_DIR=$WORK/log
export BIPEDNAV_CONFIG_DIR=$SRC/config XDG_RUNTIME_DIR=$WORK
PIDS=()
cleanup() {
  local rc=$?
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do kill -TERM "${PIDS[i]}" 2>/dev/null; done
  for pid in "${PIDS[@]}"; do wait "$pid" 2>/dev/null; done
  if [ $rc -ne 0 ]; then
    for f in "$WORK"/*.log; do echo "----- $f (last 25 lines)"; tail -n 25 "$f"; done
  fi
  rm -rf "$WORK"
  exit $rc
}
trap cleanup EXIT INT TERM
fail() { echo "FAIL: $*"; exit 1; }

# Its exit status says whether the goal was reached (not within 12 s): the bag is what counts.
"$BIN/bipednav_record" "$SRC/scenarios/hexagon_dynamic.yaml" --bag "$WORK/run.bag" --time-limit 12 >"$WORK/record.log" 2>&1
grep -q "messages written" "$WORK/record.log" && [ -s "$WORK/run.bag" ] || fail "bipednav_record wrote no bag"
rosmaster --core -p "$PORT" >"$WORK/master.log" 2>&1 &
PIDS+=($!)
for _ in $(seq 50); do
  "$PY" -c "import rosgraph; rosgraph.Master('/probe').getPid()" 2>/dev/null && break
  sleep 0.2
done
"$PY" -c "import rosgraph; rosgraph.Master('/probe').setParam('/use_sim_time', True)" ||
  fail "master did not come up on port $PORT"

# RViz in its own X server; the session ends when the check below does.
xvfb-run -a -s "-screen 0 1280x800x24" "$HERE/rviz_session.sh" "$SRC/ros/bipednav.rviz" "$WORK" "$SHOT" &
PIDS+=($!)
wait "${PIDS[-1]}"
rc=$?
unset 'PIDS[-1]'
[ $rc -eq 0 ] || fail "see $WORK/rviz.log above"
echo "PASS: RViz loads ros/bipednav.rviz${SHOT:+ (screenshot: $SHOT)}"
