"""A ROS 2 bag as `ros2 bag record` writes it with service introspection: a service event too."""

from __future__ import annotations

from pathlib import Path

from rosbags.rosbag2 import StoragePlugin
from rosbags.rosbag2 import Writer as Rosbag2Writer
from rosbags.typesys import Stores, get_typestore

SERVICE_TOPIC = "/set/_service_event (std_srvs/srv/SetBool_Event)"


def bag_with_a_service_event(folder: Path) -> tuple[Path, bytes]:
    """Write one geometry_msgs/Point on /p beside a service-event schema; return bag and frame."""
    store = get_typestore(Stores.ROS2_HUMBLE)
    point = store.types["geometry_msgs/msg/Point"](1.0, 2.0, 3.0)
    frame = bytes(store.serialize_cdr(point, "geometry_msgs/msg/Point"))
    with Rosbag2Writer(folder / "rec", version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        messages = writer.add_connection("/p", "geometry_msgs/msg/Point", typestore=store)
        writer.add_connection(
            "/set/_service_event",
            "std_srvs/srv/SetBool_Event",
            msgdef="bool data\n---\nbool success\nstring message\n",
            rihs01="RIHS01_" + "0" * 64,
        )
        writer.write(messages, 1, frame)
    (bag,) = (folder / "rec").glob("*.mcap")
    return bag, frame
