"""The reference codec, re-exported: it lives in `rfc.runtime.codec` (the processor side needs it).

rosbags is its oracle: for every type, `encode` must reproduce rosbags' serialization byte for
byte and `decode` must agree with rosbags' deserialization.
"""

from __future__ import annotations

from rfc.runtime.codec import (
    CDR_LITTLE_ENDIAN,
    FrameError,
    Values,
    decode,
    default_values,
    encode,
)

__all__ = ["CDR_LITTLE_ENDIAN", "FrameError", "Values", "decode", "default_values", "encode"]
