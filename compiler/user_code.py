"""Running the user's Python code (specs, sources, ROS-SW functions) so it cannot hang rfc.

User code runs under a time limit (`DEFAULT_TIME_LIMIT_S`, or the environment variable
`TIME_LIMIT_ENV` in seconds): an endless loop becomes an `RfcError` naming the code, as does
``sys.exit()`` (which would otherwise end rfc silently with whatever status it gave). The limit
counts the process's CPU time (``ITIMER_PROF``), so a loaded machine does not turn a long
elaboration into a false "endless loop"; a call that blocks without computing is caught by a
wall-clock timer at `WALL_FACTOR` times the limit. Both are interval timers, so they apply on
the main thread of a POSIX process; nested user code (a spec importing a source) runs under the
outermost limit.
"""

from __future__ import annotations

import math
import os
import signal
import threading
from collections.abc import Iterator
from contextlib import contextmanager
from types import FrameType

from rfc.errors import RfcError, SourceLocation

#: Seconds any one piece of user code may run.
DEFAULT_TIME_LIMIT_S = 60.0
#: The environment variable that changes it.
TIME_LIMIT_ENV = "RFC_USER_CODE_TIMEOUT"
#: Wall-clock seconds per second of the limit before code that does not compute is stopped.
WALL_FACTOR = 10.0

_active = threading.local()


class _TimeUp(BaseException):
    """Raised into user code when its time is up; not an Exception, which user code may catch.

    ``blocked`` tells the wall-clock timer (code waiting) from the CPU one (code computing).
    """

    def __init__(self, blocked: bool) -> None:
        super().__init__()
        self.blocked = blocked


def time_limit() -> float:
    """The time limit in seconds, from `TIME_LIMIT_ENV` when set.

    Raises:
        RfcError: The variable is not a positive number of seconds.
    """
    text = os.environ.get(TIME_LIMIT_ENV)
    if text is None:
        return DEFAULT_TIME_LIMIT_S
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not 0 < value < math.inf:
        raise RfcError(
            f"{TIME_LIMIT_ENV}={text!r} is not a positive number of seconds",
            hint=f"unset it for the default of {DEFAULT_TIME_LIMIT_S:g} s",
        )
    return value


@contextmanager
def running_user_code(what: str, location: SourceLocation | None = None) -> Iterator[None]:
    """Run the block's user code under the time limit; a hang or ``sys.exit`` is an `RfcError`.

    Args:
        what: The code, for messages (``the Python spec 'x.py'``, ``ROS-SW function 'f'``).
        location: The spec element responsible, when there is one.

    Raises:
        RfcError: The code ran past the limit or called ``sys.exit``.
    """
    limit = time_limit()
    own_timer = (
        not getattr(_active, "timing", False)
        and threading.current_thread() is threading.main_thread()
        and hasattr(signal, "setitimer")
    )

    def computed_too_long(signum: int, frame: FrameType | None) -> None:
        raise _TimeUp(blocked=False)

    def waited_too_long(signum: int, frame: FrameType | None) -> None:
        raise _TimeUp(blocked=True)

    previous: list[signal._HANDLER] = []
    if own_timer:
        previous = [
            signal.signal(signal.SIGPROF, computed_too_long),
            signal.signal(signal.SIGALRM, waited_too_long),
        ]
        _active.timing = True
        signal.setitimer(signal.ITIMER_PROF, limit)
        signal.setitimer(signal.ITIMER_REAL, limit * WALL_FACTOR)
    try:
        yield
    except _TimeUp as up:
        if not own_timer:
            raise
        waited = f" ({limit * WALL_FACTOR:g} s in all, most of it waiting)" if up.blocked else ""
        raise RfcError(
            f"{what} did not finish within {limit:g} s{waited}",
            location=location,
            hint=f"look for an endless loop or a blocking call; set {TIME_LIMIT_ENV}=SECONDS "
            "to allow longer",
        ) from None
    except SystemExit as exc:
        raise RfcError(
            f"{what} called sys.exit({exc.code!r}); rfc stops instead of exiting silently",
            location=location,
            hint="raise an exception to report an error",
        ) from None
    finally:
        if own_timer:
            signal.setitimer(signal.ITIMER_PROF, 0)
            signal.setitimer(signal.ITIMER_REAL, 0)
            signal.signal(signal.SIGPROF, previous[0])
            signal.signal(signal.SIGALRM, previous[1])
            _active.timing = False
