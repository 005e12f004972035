#!/usr/bin/python3
"""move_base client of the ROS integration test (run with Debian's /usr/bin/python3).

Checks, in order:
  1. a reachable goal is SUCCEEDED within --timeout seconds (wall clock);
  2. a goal inside an obstacle is ABORTED with BLOCKED_GOAL in the status text;
  3. a goal from a second client preempts a running goal (PREEMPTED), then is canceled.
Prints one line per check and exits 0 only if all passed.
"""
import argparse
import math
import sys
import time

import actionlib
import rospy
from actionlib_msgs.msg import GoalStatus
from move_base_msgs.msg import MoveBaseAction, MoveBaseGoal

STATE = {v: k for k, v in GoalStatus.__dict__.items() if k.isupper() and isinstance(v, int)}


def make_goal(x, y, yaw):
    g = MoveBaseGoal()
    g.target_pose.header.frame_id = "map"
    g.target_pose.header.stamp = rospy.Time.now()
    g.target_pose.pose.position.x = x
    g.target_pose.pose.position.y = y
    g.target_pose.pose.orientation.z = math.sin(yaw / 2.0)
    g.target_pose.pose.orientation.w = math.cos(yaw / 2.0)
    return g


def wait_result(client, timeout_s, feedback_seen):
    """Waits on the wall clock (sim time may run at any rate)."""
    end = time.monotonic() + timeout_s
    while time.monotonic() < end and not rospy.is_shutdown():
        if client.get_state() not in (GoalStatus.PENDING, GoalStatus.ACTIVE):
            return client.get_state(), client.get_goal_status_text()
        time.sleep(0.1)
    return None, "timeout after %.0f s (last feedback: %s)" % (timeout_s, feedback_seen[-1:] or "none")


def run_goal(client, name, pose, timeout_s):
    feedback = []
    start = time.monotonic()
    client.send_goal(make_goal(*pose), feedback_cb=lambda fb: feedback.append(
        (round(fb.base_position.pose.position.x, 2), round(fb.base_position.pose.position.y, 2))))
    state, text = wait_result(client, timeout_s, feedback)
    print("%s: goal %s -> %s '%s' after %.1f s wall, %d feedback messages" % (
        name, pose, STATE.get(state, state), text, time.monotonic() - start, len(feedback)), flush=True)
    return state, text, feedback


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--goal", type=float, nargs=3, default=[1.7, 0.55, 0.0])
    ap.add_argument("--blocked-goal", type=float, nargs=3, default=[0.0, 0.0, 0.0])
    ap.add_argument("--far-goal", type=float, nargs=3, default=[-1.65, -0.55, math.pi])
    ap.add_argument("--timeout", type=float, default=150.0)
    args = ap.parse_args()
    rospy.init_node("bipednav_move_base_client", anonymous=True, disable_signals=True)
    client = actionlib.SimpleActionClient("move_base", MoveBaseAction)
    if not client.wait_for_server(rospy.Duration(60.0)):
        print("FAIL: no move_base action server within 60 s", flush=True)
        return 1
    ok = True
    state, text, feedback = run_goal(client, "reachable", args.goal, args.timeout)
    if state != GoalStatus.SUCCEEDED or not feedback:
        print("FAIL: expected SUCCEEDED with feedback", flush=True)
        ok = False
    state, text, _ = run_goal(client, "blocked", args.blocked_goal, args.timeout)
    if state != GoalStatus.ABORTED or "BLOCKED_GOAL" not in text:
        print("FAIL: expected ABORTED with BLOCKED_GOAL in the text", flush=True)
        ok = False
    # Preemption: client A's goal (far from the robot) is replaced by client B's.
    other = actionlib.SimpleActionClient("move_base", MoveBaseAction)
    other.wait_for_server(rospy.Duration(10.0))
    client.send_goal(make_goal(*args.far_goal))
    time.sleep(2.0)
    other.send_goal(make_goal(*args.goal))
    state, text = wait_result(client, 30.0, [])
    print("preempt: first goal -> %s '%s'" % (STATE.get(state, state), text), flush=True)
    if state != GoalStatus.PREEMPTED:
        print("FAIL: expected PREEMPTED", flush=True)
        ok = False
    other.cancel_goal()
    state, text = wait_result(other, 30.0, [])
    print("cancel: second goal -> %s '%s'" % (STATE.get(state, state), text), flush=True)
    print("PASS" if ok else "FAILED", flush=True)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
