"""Mirror: a MyHDL accelerator with its reference (skeleton written by rfc stub)."""

from myhdl import always_comb, always_seq, block

from rfc.messages.rosbags_adapter import message_types


@block
def mirror(clk, rst, p, m):
    """geometry_msgs/msg/Point p in, geometry_msgs/msg/Point m out: x negated, y and z kept."""

    @always_comb
    def accept():
        p.ready.next = not m.valid or m.ready  # take a point when the last one has gone

    @always_seq(clk.posedge, reset=rst)
    def logic():
        if m.valid and m.ready:
            m.valid.next = 0
        if p.valid and p.ready:
            m.x.next[63] = not p.x[63]  # the sign bit flipped: x becomes -x
            m.x.next[63:] = p.x[63:]
            m.y.next = p.y
            m.z.next = p.z
            m.valid.next = 1

    return accept, logic


def mirror_reference(p):
    """Mirror on rosbags messages: the reference, or the ROS-SW function."""
    types = message_types("ros2", "humble")
    return types.build("geometry_msgs/msg/Point", {"x": -p.x, "y": p.y, "z": p.z})
