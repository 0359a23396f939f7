"""Message types, their flattened layouts, selections, limits and the reference codec.

Layer: the message layer, under the hardware library and the runtime; it imports nothing of
rfc but `rfc.errors`, and needs only rosbags and NumPy, so the processor side reads it too.
"""
