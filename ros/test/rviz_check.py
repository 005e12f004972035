#!/usr/bin/python3
"""Checks of rviz_test.sh on a running RViz (run with Debian's /usr/bin/python3).

  rviz_check.py CONFIG --wait S    waits up to S seconds until an RViz node subscribes to the topic
                                   of every enabled display of CONFIG (the TF display: /tf and
                                   /tf_static); then, or on time-out, lists the topics missing
  rviz_check.py CONFIG --log FILE  the same check at once, and no ERROR or FATAL line in RViz's log
                                   FILE but the software renderer's map shader link message
                                   (rviz_test.sh says why)
  ... --bag FILE                   also: the bag (what bipednav publishes) has every such topic
Exits 0 when every check passes.
"""
import argparse
import re
import sys
import time

import rosgraph
import yaml

TOPIC_KEYS = ("Topic", "Marker Topic")
# Mesa's software OpenGL under Xvfb rejects the link of RViz's indexed-colour map shader; the maps draw.
SOFTWARE_GL_SHADER = re.compile(r"glsl\d*/indexed_8bit_image|GLSL link result|active samplers with a different type")


def expected_topics(config):
    """{topic: display name} of the enabled displays of an RViz config."""
    with open(config, encoding="utf-8") as f:
        cfg = yaml.safe_load(f)
    topics = {}
    for d in cfg["Visualization Manager"]["Displays"]:
        if not d.get("Enabled", False):
            continue
        if d["Class"] == "rviz/TF":
            topics["/tf"] = topics["/tf_static"] = d["Name"]
        for key in TOPIC_KEYS:
            if key in d:
                topics[d[key]] = d["Name"]
    return topics


def missing_topics(topics):
    """The topics no node named /rviz* subscribes to."""
    _, subscriptions, _ = rosgraph.Master("/rviz_check").getSystemState()
    subscribed = {t for t, nodes in subscriptions if any(n.startswith("/rviz") for n in nodes)}
    return [t for t in topics if t not in subscribed]


def log_errors(log):
    """The ERROR and FATAL messages of RViz's log but the software renderer's shader message."""
    with open(log, encoding="utf-8", errors="replace") as f:
        text = f.read()
    # A message runs from its "[ERROR]"/"[FATAL]"/"[ INFO]" tag to the next tag.
    messages = re.split(r"(?=\[ ?(?:ERROR|FATAL|WARN|INFO|DEBUG)\])", text)
    errors = [m.strip() for m in messages if re.match(r"\[ ?(ERROR|FATAL)\]", m)]
    return [e for e in errors if not SOFTWARE_GL_SHADER.search(e)]


def topics_not_in_bag(topics, bag_file):
    """The topics the bag has no message on."""
    import rosbag  # only with --bag

    with rosbag.Bag(bag_file) as bag:
        recorded = set(bag.get_type_and_topic_info().topics)
    return [t for t in topics if t not in recorded]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("config")
    ap.add_argument("--wait", type=float, default=0.0, help="seconds to wait for the subscriptions")
    ap.add_argument("--log", help="RViz's log to check for errors")
    ap.add_argument("--bag", help="a recorded run that should have every display's topic")
    a = ap.parse_args()
    topics = expected_topics(a.config)
    deadline = time.monotonic() + a.wait
    missing = missing_topics(topics)
    while missing and time.monotonic() < deadline:
        time.sleep(0.5)
        missing = missing_topics(topics)
    ok = True
    if missing:
        ok = False
        for t in missing:
            print(f"rviz_check: no RViz subscription to {t} (display '{topics[t]}')")
    else:
        print(f"rviz_check: RViz subscribes to the {len(topics)} topics of the enabled displays")
    if a.log:
        errors = log_errors(a.log)
        for e in errors:
            print(f"rviz_check: RViz logged: {e}")
        ok = ok and not errors
    if a.bag:
        absent = topics_not_in_bag(topics, a.bag)
        for t in absent:
            print(f"rviz_check: display '{topics[t]}' shows {t}, which the recorded run does not have")
        ok = ok and not absent
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
