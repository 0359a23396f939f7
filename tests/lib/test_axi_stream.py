"""An AxiStream reads a converter's ``<bus>_*`` ports in AXI-Stream's order and hands them back."""

from __future__ import annotations

from rfc.lib.axi_stream import AxiStream
from rfc.lib.converters.build import publisher_ports
from rfc.lib.converters.plan import plan
from rfc.lib.converters.ports import Side, dma_ports
from rfc.lib.converters.toplevel import port_signals
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import Middleware, message_types


def test_a_publishers_m_axis_ports_make_its_stream_in_tdata_tkeep_tvalid_tready_tlast_order():
    converter = plan(flatten(message_types(Middleware.ROS2), "sensor_msgs/msg/Imu"), 64)
    ports = port_signals(dma_ports(converter, Side.PUBLISHER))
    assert set(ports) <= set(publisher_ports(converter))

    stream = AxiStream.named(ports, "m_axis")

    assert stream.signals() == tuple(
        ports[f"m_axis_{name}"] for name in ("tdata", "tkeep", "tvalid", "tready", "tlast")
    )
    assert len(stream.tdata) == 64
    assert len(stream.tkeep) == 8
