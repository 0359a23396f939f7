"""When a frame guard may hold only a frame's prefix, and how much beyond it.

Plain data, apart from the MyHDL guard (`rfc.lib.converters.prefix_guard`), so that checking a
spec's block RAM (`rfc check`) does not import MyHDL.
"""

from __future__ import annotations

from rfc.lib.converters.plan import plan as make_plan
from rfc.lib.converters.steps import End, Loop, Payload, Plan
from rfc.messages.selection import select

#: Beats beyond the longest prefix the buffer holds: the checker emits the sequence's first
#: beat only once it has a beat's worth of it, a beat or two after the sequence starts.
SLACK_BEATS = 4


def checking_plan(converters: Plan) -> Plan | None:
    """The checker's plan (every field parsed and given out) when a prefix suffices, else None.

    A prefix suffices when the frame's size follows from top-level lengths and its last field
    is a primitive sequence with no sequence of messages or strings in the message.
    """
    checking = make_plan(select(converters.layout), 8 * converters.width, converters.limits)
    steps = checking.steps
    last = steps[-2] if len(steps) >= 2 and isinstance(steps[-1], End) else None
    if (
        checking.store_and_forward
        or any(isinstance(s, Loop) for s in steps)
        or not isinstance(last, Payload)
        or last.terminator
        or not last.stream
    ):
        return None
    return checking
