"""A separate rclpy process on the test's ROS 2 graph: publishes inputs, records the outputs.

Usage: python ros2_peer.py JOB.json, where the job names the input topic and type, the
messages to publish (hex of their serialized bytes), the output topic and type and a time
limit. It waits until the node under test has subscribed and published, then sends one message
at a time and waits for its answer before the next (not once the node has left the graph), so
that outputs pair with inputs one by one. Prints a JSON list of the answers (hex; null where
none came in time). Optional: ``silent``, the indices of messages that get no answer (the peer
waits only a moment after them), and ``linger``, seconds to stay on the graph at the end.
"""

import importlib
import json
import sys
import time

import rclpy


def message_class(canonical):
    package, _, name = canonical.rpartition("/")
    return getattr(importlib.import_module(package.replace("/", ".")), name)


def main(job):
    rclpy.init()
    node = rclpy.create_node("rfc_test_peer")
    received = []
    node.create_subscription(
        message_class(job["output_type"]), job["output"], received.append, 100, raw=True
    )
    publisher = node.create_publisher(message_class(job["input_type"]), job["input"], 100)
    deadline = time.monotonic() + job["timeout"]
    while time.monotonic() < deadline and not (
        publisher.get_subscription_count() and node.count_publishers(job["output"])
    ):
        rclpy.spin_once(node, timeout_sec=0.1)
    answers = []
    silent = set(job.get("silent", ()))
    for index, data in enumerate(job["messages"]):
        publisher.publish(bytes.fromhex(data))
        if index in silent:
            end = time.monotonic() + 0.3
            while time.monotonic() < end:
                rclpy.spin_once(node, timeout_sec=0.05)
            answers.append(None)
            continue
        # until the answer comes, the time is up, or the node has left the graph
        while time.monotonic() < deadline and not received and node.count_publishers(job["output"]):
            rclpy.spin_once(node, timeout_sec=0.05)
        answers.append(received.pop(0).hex() if received else None)
    end = time.monotonic() + job.get("linger", 0)
    while time.monotonic() < end:
        rclpy.spin_once(node, timeout_sec=0.05)
    node.destroy_node()
    rclpy.shutdown()
    print(json.dumps(answers))


if __name__ == "__main__":
    with open(sys.argv[1]) as stream:
        main(json.load(stream))
