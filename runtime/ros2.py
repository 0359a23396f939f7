"""The rclpy side of the generated node: subscriptions and publishers of serialized messages.

Only this module imports rclpy, and only when the node runs. Subscriptions take raw CDR bytes
(``raw=True``) and publishers publish bytes, so messages cross the node without being
deserialized unless a ROS-SW accelerator needs them. Message classes come from the ROS 2
packages of the types (``geometry_msgs.msg``), which the node's ROS installation provides.
"""

from __future__ import annotations

import argparse
import importlib
from collections.abc import Callable, Sequence
from typing import Any

from rfc.errors import RfcError
from rfc.runtime.core import Published, QueueConfig
from rfc.runtime.dma_device import DmaChannels
from rfc.runtime.node import NodeCore
from rfc.runtime.plan import RuntimePlan

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


# The same parameters as `rfc.runtime.ros1.spin`: the node calls one or the other by its
# middleware; the two share the signature, not the body.
def spin(
    plan: RuntimePlan,
    open_dma: Callable[[], DmaChannels],
    queues: QueueConfig,
    args: argparse.Namespace,
    ros_arguments: Sequence[str],
) -> None:
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
    names = {i.message for i in plan.inputs} | {o.message for o in plan.outputs}
    classes = {name: message_class(name) for name in names}
    dma = open_dma()
    rclpy.init(args=list(ros_arguments))
    node = rclpy.create_node(plan.node_name)
    publishers = {
        output.topic: node.create_publisher(classes[output.message], output.topic, queues.depth)
        for output in plan.outputs
    }

    def publish(message: Published) -> None:
        publishers[message.topic].publish(message.data)

    core = NodeCore(
        plan,
        dma,
        publish,
        queues,
        clock=lambda: node.get_clock().now().nanoseconds,
        screen=not args.send_malformed,
        status_period=args.status_period,
    )
    for topic_input in plan.inputs:
        node.create_subscription(
            classes[topic_input.message],
            topic_input.topic,
            _deliver(core, topic_input.topic),
            queues.depth,
            raw=True,
        )
    node.create_timer(CHECK_PERIOD, lambda: core.check(args.answer_timeout))
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
