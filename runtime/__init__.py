"""rfc.runtime: what runs on the processor side of a generated system.

The wire protocol, per-subscriber queues, the software scheduler, the node and bag replay.
Layer: beside the hardware library (neither imports the other); it depends on the message
layer, `rfc.user_code` and `rfc.errors` only, so a board runs it with NumPy and rosbags.
The harnesses that replay through simulated logic for ``rfc sim`` drive the compiler too, and
live a layer up, in `rfc.sim`.
"""
