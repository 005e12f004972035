#!/usr/bin/env bash
# ROS 1 integration test: a master on 127.0.0.1 with its own port, bipednav_sim_node on the
# hexagon_static scenario, bipednav_nav_node sized by the simulator node's ~map_area, and the
# move_base client (move_base_client.py):
# a reachable goal SUCCEEDED, cmd_vel seen while moving, a goal on the centre cylinder ABORTED
# with BLOCKED_GOAL, a goal preempted by another one. Every process is stopped by its PID.
# Usage: integration_test.sh BIN_DIR SOURCE_DIR [REAL_TIME_FACTOR]
# Exit 0 pass, 1 fail, 77 skipped (ROS run-time packages missing).
set -uo pipefail
BIN=${1:?usage: integration_test.sh BIN_DIR SOURCE_DIR}
SRC=${2:?usage: integration_test.sh BIN_DIR SOURCE_DIR}
RTF=${3:-1.0}
PY=/usr/bin/python3
HERE=$(cd "$(dirname "$0")" && pwd)

skip() { echo "SKIPPED: $* (install the ROS packages with scripts/install-deps --ros)"; exit 77; }
command -v rosmaster >/dev/null || skip "rosmaster not found"
command -v rostopic >/dev/null || skip "rostopic not found"
[ -x "$PY" ] && "$PY" -c "import rospy, actionlib, move_base_msgs.msg, geometry_msgs.msg" 2>/dev/null ||
  skip "Debian's ROS Python modules (rospy, actionlib, move_base_msgs) not found"
for exe in bipednav_sim_node bipednav_nav_node; do [ -x "$BIN/$exe" ] || { echo "FAIL: $BIN/$exe missing"; exit 1; }; done

# A master of its own, the work directory, fail() and the cleanup of every process in PIDS.
. "$HERE/ros_master.sh"

SCENARIO=$SRC/scenarios/hexagon_static.yaml
stdbuf -oL "$BIN/bipednav_sim_node" _scenario:="$SCENARIO" _real_time_factor:="$RTF" >"$WORK/sim.log" 2>&1 &
PIDS+=($!)
stdbuf -oL "$BIN/bipednav_nav_node" _map_area_param:=/bipednav_sim_node/map_area >"$WORK/nav.log" 2>&1 &
PIDS+=($!)

stdbuf -oL "$PY" "$HERE/move_base_client.py" --goal 1.7 0.55 0.0 --blocked-goal 0.0 0.0 0.0 \
  >"$WORK/client.log" 2>&1 &
CLIENT=$!
PIDS+=($CLIENT)

# cmd_vel while the robot moves: a message with a non-zero forward speed.
moving=0
for _ in $(seq 30); do
  msg=$(timeout 10 rostopic echo -n1 /cmd_vel 2>/dev/null)
  x=$(echo "$msg" | awk '/linear:/ {getline; print $2; exit}')
  if [ -n "$x" ] && awk -v x="$x" 'BEGIN { exit !(x > 0.01 || x < -0.01) }'; then
    echo "cmd_vel while moving: linear.x = $x"
    moving=1
    break
  fi
  kill -0 $CLIENT 2>/dev/null || break
  sleep 0.5
done

wait $CLIENT
client_rc=$?
cat "$WORK/client.log"
[ $moving -eq 1 ] || fail "no non-zero cmd_vel seen while the goal was active"
[ $client_rc -eq 0 ] || fail "move_base client reported a failure"
# The nav node sized its global map from the simulator node's ~map_area: the grid of a closed-loop
# run of hexagon_static (its bounds + 2 m at 0.1 m).
grep -q "global map 130x118 at 0.10 m" "$WORK/nav.log" || fail "nav node's global map is not hexagon_static's 130x118 cells"
kill -0 "${PIDS[1]}" 2>/dev/null || fail "bipednav_sim_node died"
kill -0 "${PIDS[2]}" 2>/dev/null || fail "bipednav_nav_node died"
# Stopped, the simulator node removes its ~map_area: a nav node started later waits for the next
# simulator instead of sizing its map from a scenario that has ended.
rosparam get /bipednav_sim_node/map_area >/dev/null 2>&1 || fail "no /bipednav_sim_node/map_area while the simulator runs"
kill -INT "${PIDS[1]}"
for _ in $(seq 50); do kill -0 "${PIDS[1]}" 2>/dev/null || break; sleep 0.1; done
kill -0 "${PIDS[1]}" 2>/dev/null && fail "bipednav_sim_node did not stop on SIGINT"
rosparam get /bipednav_sim_node/map_area >/dev/null 2>&1 && fail "/bipednav_sim_node/map_area left after the simulator node stopped"
echo "PASS: ROS integration test"
