"""The names of MyHDL's values at rfc's typed boundary.

MyHDL ships no type information: a `Signal`, its slices and shadows, what a ``@block``
function returns and the members of an interface object are opaque to mypy. rfc's hardware
functions name them with these aliases rather than a bare `Any`, so that the one place types
stop is visible and searchable (typings/myhdl types MyHDL's decorators themselves).
"""

from __future__ import annotations

from typing import Any, TypeAlias

#: A MyHDL `Signal` (or `ResetSignal`, a slice or a shadow of one).
SignalLike: TypeAlias = Any
#: What a MyHDL ``@block`` function returns: its instances, elaborated into a block.
Instances: TypeAlias = Any
#: A member of a MyHDL interface object, found by attribute name: a signal, a list of members or
#: another interface object.
Member: TypeAlias = Any
