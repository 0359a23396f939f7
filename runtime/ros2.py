"""The rclpy side of the generated node: subscriptions and publishers of serialized messages.

Only this module imports rclpy, and only when the node runs: rclpy exists on the target (a
Zynq running ROS 2), not where rfc generates and tests the node. Subscriptions take raw CDR
bytes (``raw=True``) and publishers publish bytes, so messages cross the node without being
deserialized unless a ROS-SW accelerator needs them.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rfc.runtime.core import Published, QueueConfig
from rfc.runtime.dma_device import DmaChannels
from rfc.runtime.node import NodeCore
from rfc.runtime.plan import RuntimePlan


def spin(
    plan: RuntimePlan,
    dma: DmaChannels,
    queues: QueueConfig,
    config: dict[str, Any],
    ros_arguments: Sequence[str],
) -> None:
    """Create the node, run it until interrupted, and log its account.

    Raises:
        SystemExit: rclpy is not installed (ROS 2 not sourced).
    """
    try:
        import rclpy
        from rosidl_runtime_py.utilities import get_message
    except ImportError as exc:
        dma.close()
        raise SystemExit(
            f"rfc node: cannot import ROS 2's Python client ({exc.name}); source a ROS 2 "
            "installation (setup.bash) first"
        ) from None

    rclpy.init(args=list(ros_arguments))
    node = rclpy.create_node(config["node_name"])
    publishers = {
        output.topic: node.create_publisher(get_message(output.message), output.topic, 10)
        for output in plan.outputs
    }

    def publish(message: Published) -> None:
        publishers[message.topic].publish(message.data)

    core = NodeCore(plan, dma, publish, queues, clock=lambda: node.get_clock().now().nanoseconds)
    for topic_input in plan.inputs:
        node.create_subscription(
            get_message(topic_input.message),
            topic_input.topic,
            lambda data, topic=topic_input.topic: core.on_message(topic, data),
            config["queues"]["depth"],
            raw=True,
        )
    core.start()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    finally:
        account = core.stop()
        node.get_logger().info(f"rfc account: {account.to_json()}")
        node.destroy_node()
        rclpy.try_shutdown()
