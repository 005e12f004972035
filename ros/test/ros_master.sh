# Sourced by the ROS tests (integration_test.sh, rviz_test.sh) once PY (Debian's python3) and SRC
# (the source tree) are set: a work directory WORK, a ROS master of its own on a free port of
# 127.0.0.1 with /use_sim_time true, fail MESSAGE, and at exit every process in PIDS stopped by its
# PID (TERM, then KILL after 1 s) and, after a failure, the tail of each log in WORK.
WORK=$(mktemp -d /tmp/bipednav-ros-test.XXXXXX)
PORT=$("$PY" -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI=http://127.0.0.1:$PORT ROS_IP=127.0.0.1 ROS_HOME=$WORK ROS_LOG_DIR=$WORK/log
export BIPEDNAV_CONFIG_DIR=$SRC/config
PIDS=()
cleanup() {
  local rc=$?
  for ((i = ${#PIDS[@]} - 1; i >= 0; i--)); do kill -TERM "${PIDS[i]}" 2>/dev/null; done
  sleep 1
  for pid in "${PIDS[@]}"; do kill -KILL "$pid" 2>/dev/null; wait "$pid" 2>/dev/null; done
  if [ $rc -ne 0 ]; then
    for f in "$WORK"/*.log; do echo "----- $f (last 25 lines)"; tail -n 25 "$f"; done
  fi
  rm -rf "$WORK"
  exit $rc
}
trap cleanup EXIT INT TERM
fail() { echo "FAIL: $*"; exit 1; }

echo "master on $ROS_MASTER_URI, logs in $WORK"
rosmaster --core -p "$PORT" >"$WORK/master.log" 2>&1 &
PIDS+=($!)
for _ in $(seq 50); do
  "$PY" -c "import rosgraph; rosgraph.Master('/probe').getPid()" 2>/dev/null && break
  sleep 0.2
done
"$PY" -c "import rosgraph; m = rosgraph.Master('/probe'); m.setParam('/use_sim_time', True)" ||
  fail "master did not come up on port $PORT"
