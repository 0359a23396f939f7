"""The rclpy side of the generated node: subscriptions and publishers of serialized messages.

Only this module imports rclpy, and only when the node runs. Subscriptions take raw CDR bytes
(``raw=True``) and publishers publish bytes, so messages cross the node without being
deserialized unless a ROS-SW accelerator needs them. Message classes come from the ROS 2
packages of the types (``geometry_msgs.msg``), which the node's ROS installation provides.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

from rfc.errors import RfcError
from rfc.runtime.core import Published
from rfc.runtime.node import NodeCore, NodeSetup

#: Seconds between two checks that the logic answers.
CHECK_PERIOD = 0.5


def message_class(canonical: str) -> Any:
    """The rclpy message class of ``pkg/msg/Name``.

    Raises:
        RfcError: ROS 2 has no Python package for the type here.
    """
    package, _, name = canonical.rpartition("/")
    try:
        return getattr(importlib.import_module(package.replace("/", ".")), name)
    except (ImportError, AttributeError):
        raise RfcError(
            f"this ROS 2 installation has no Python message class for {canonical}",
            hint=f"install or source the package that defines it ({package.split('/')[0]})",
        ) from None


def spin(setup: NodeSetup) -> None:
    """Create the node, run it until interrupted, and log its account.

    Raises:
        RfcError: rclpy is not installed, a message class is missing, or the logic does not
            answer.
    """
    try:
        import rclpy
        from rclpy.executors import ExternalShutdownException
        from rclpy.utilities import try_shutdown
    except ImportError as exc:
        raise RfcError(
            f"cannot import ROS 2's Python client ({exc.name})",
            hint="source a ROS 2 installation (setup.bash), or pip install 'rfc[ros2]'",
        ) from None
    plan = setup.plan
    names = {i.message for i in plan.inputs} | {o.message for o in plan.outputs}
    classes = {name: message_class(name) for name in names}
    dma = setup.open_dma()
    rclpy.init(args=list(setup.ros_arguments))
    node = rclpy.create_node(plan.node_name)
    depth = setup.queues.depth
    publishers = {
        output.topic: node.create_publisher(classes[output.message], output.topic, depth)
        for output in plan.outputs
    }

    def publish(message: Published) -> None:
        publishers[message.topic].publish(message.data)

    core = setup.core(dma, publish, lambda: node.get_clock().now().nanoseconds)
    for topic_input in plan.inputs:
        node.create_subscription(
            classes[topic_input.message],
            topic_input.topic,
            _deliver(core, topic_input.topic),
            depth,
            raw=True,
        )
    node.create_timer(CHECK_PERIOD, lambda: core.check(setup.answer_timeout))
    core.start()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass  # Ctrl-C, or a signal rclpy's own handler turned into a shutdown of the context
    finally:
        account = core.stop()
        node.get_logger().info(f"rfc account: {account.to_json()}")
        node.destroy_node()
        try_shutdown()


def _deliver(core: NodeCore, topic: str) -> Callable[[bytes], None]:
    """The subscription callback of `topic`: its raw messages into the node's queues."""
    return lambda data: core.on_message(topic, data)
