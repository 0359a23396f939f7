"""The rospy side of the generated node, for ROS 1 systems: the same core, the same options.

Only this module imports rospy, and only when the node runs. Subscriptions take the raw bytes
(``rospy.AnyMsg``); publishers publish them through a message class that carries the type's
name, MD5 sum and definition from the runtime plan and serializes the bytes as they are.
rospy cannot be installed where rfc is tested; the node's loop (`rfc.runtime.node.NodeCore`)
is what the tests run, with the plan of a ROS 1 build.
"""

from __future__ import annotations

from typing import Any

from rfc.errors import RfcError
from rfc.runtime.core import Published
from rfc.runtime.node import NodeSetup

#: Seconds between two checks that the logic answers.
CHECK_PERIOD = 0.5


def ros1_name(canonical: str) -> str:
    """ROS 1 spells ``pkg/msg/Name`` as ``pkg/Name``."""
    package, _, name = canonical.partition("/msg/")
    return f"{package}/{name}" if name else canonical


def spin(setup: NodeSetup) -> None:
    """Create the node, run it until shut down, and log its account.

    Raises:
        RfcError: rospy is not installed, or the logic does not answer.
    """
    try:
        import rospy
    except ImportError as exc:
        raise RfcError(
            f"cannot import ROS 1's Python client ({exc.name})",
            hint="source a ROS 1 installation (setup.bash) first",
        ) from None
    plan = setup.plan

    def raw_class(canonical: str) -> Any:
        entry = plan.messages.definitions[canonical]
        return type(
            canonical.rpartition("/")[2],
            (rospy.AnyMsg,),
            {
                "_type": ros1_name(canonical),
                "_md5sum": entry["md5"],
                "_full_text": entry["definition"],
            },
        )

    dma = setup.open_dma()
    rospy.init_node(plan.node_name, argv=[plan.node_name, *setup.ros_arguments])
    publishers = {
        o.topic: rospy.Publisher(o.topic, raw_class(o.message), queue_size=setup.queues.depth)
        for o in plan.outputs
    }

    def publish(message: Published) -> None:
        raw = publishers[message.topic].data_class()
        raw._buff = message.data
        publishers[message.topic].publish(raw)

    core = setup.core(dma, publish, lambda: rospy.Time.now().to_nsec())
    for topic_input in plan.inputs:
        rospy.Subscriber(
            topic_input.topic,
            rospy.AnyMsg,
            lambda raw, topic=topic_input.topic: core.on_message(topic, raw._buff),
            queue_size=setup.queues.depth,
        )
    core.start()
    failure: list[RfcError] = []

    def check(_: object) -> None:
        try:
            core.check(setup.answer_timeout)
        except RfcError as error:
            failure.append(error)
            rospy.signal_shutdown(error.message)

    rospy.Timer(rospy.Duration(CHECK_PERIOD), check)
    try:
        rospy.spin()
    finally:
        account = core.stop()
        rospy.loginfo(f"rfc account: {account.to_json()}")
    if failure:
        raise failure[0]
