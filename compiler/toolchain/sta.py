"""Timing without vendor tools: Yosys' `sta` on a netlist mapped to the 7-series.

Yosys annotates its 7-series cells (LUTs, CARRY4, MUXF7/8, flip-flops, DSP48E1, block RAM)
with delays from Project X-Ray's Artix-7 timing database, the fabric of the xc7z020; `sta`
adds them up along every path from a register or input to a register or output and prints the
latest one. There is no routing in it, so an Fmax comes from the cell delay and
`ROUTING_FACTOR` (docs/performance.md, Timing, says where that factor comes from).
"""

from __future__ import annotations

import re
from dataclasses import dataclass

#: Estimated period over cell delay: routing takes about as much again as the cells (the
#: "50/50 rule" of Xilinx's timing guides for a design before placement; docs/performance.md).
ROUTING_FACTOR = 2.0


_HEADER = re.compile(r"^Latest arrival time in '(?P<module>[^']+)' is (?P<arrival>-?\d+):")
_STEP = re.compile(r"^\s+(?P<arrival>-?\d+)\s+(?P<name>.*?)\s*\((?P<what>[^()]*)\)\s*$")
#: Pins a path starts from when it leaves a register (flip-flop, DSP, block RAM, LUT RAM).
_CLOCK_PINS = frozenset({"C", "CLK", "CLKARDCLK", "CLKBWRCLK", "WCLK"})
#: The part of a register's name after the signal it drives: the bit and the cell type that
#: ``rename -wire`` appends (``count[3]\\FDRE``), or what ``autoname`` appends
#: (``count_FDRE_Q_3``).
_CELL_SUFFIX = re.compile(
    r"(?:\[\d+\])?\\\w+$|_(?:FD[A-Z]*|LUT\d|CARRY4|MUXF\d|DSP48E1|RAM\w*|SRL\w*|BUFG)_.*$"
)


@dataclass(frozen=True)
class TimingPath:
    """The latest-arriving path of a design: its critical path before routing.

    Attributes:
        delay_ps: Cell delay along the path in picoseconds, from the launching register's
            clock pin (or an input) to the capturing register's pin (or an output).
        start: Where it starts: a register (hierarchical name, ``cell.signal``) or an input.
        end: Where it ends: a register or an output.
        levels: Cells the signal goes through between the two (LUTs, carries, muxes, DSPs).
    """

    delay_ps: int
    start: str
    end: str
    levels: int

    @property
    def delay_ns(self) -> float:
        """The cell delay in nanoseconds."""
        return self.delay_ps / 1000

    @property
    def fmax_mhz(self) -> float:
        """The clock the path allows once routing (`ROUTING_FACTOR`) is added."""
        return 1e6 / (max(self.delay_ps, 1) * ROUTING_FACTOR)

    @property
    def start_cell(self) -> str:
        """The block (top-level cell) the path starts in; '' for a port of the design."""
        return cell_of(self.start)

    @property
    def end_cell(self) -> str:
        """The block (top-level cell) the path ends in; '' for a port of the design."""
        return cell_of(self.end)

    def to_json(self) -> dict[str, object]:
        """The path as ``--json`` documents carry it."""
        return {
            "delay_ns": round(self.delay_ns, 3),
            "fmax_mhz": round(self.fmax_mhz, 1),
            "start": self.start,
            "end": self.end,
            "levels": self.levels,
        }


def cell_of(name: str) -> str:
    """The top-level cell a flattened name lies in (``quat_to_euler`` of ``quat_to_euler.x``)."""
    return name.split(".", 1)[0] if "." in name else ""


def parse_sta(log: str) -> TimingPath | None:
    """The critical path Yosys' `sta` printed, or None for a design without a timed path.

    Raises:
        ValueError: The log has no `sta` report at all (the command did not run).
    """
    lines = log.splitlines()
    header = next((i for i, line in enumerate(lines) if _HEADER.match(line)), None)
    if header is None:
        if "No timing paths found." in log:
            return None
        raise ValueError("Yosys printed no static timing report")
    arrival = int(_HEADER.match(lines[header]).group("arrival"))  # type: ignore[union-attr]
    steps: list[tuple[int, str, str]] = []  # (arrival, cell, what), endpoint first
    nets: list[str] = []  # the net under each step: the signal that enters that cell
    for line in lines[header + 1 :]:
        if not line.strip():
            break
        step = _STEP.match(line)
        if step:
            steps.append((int(step["arrival"]), _plain(step["name"]), step["what"]))
        elif steps and not line.startswith("Warning:"):
            nets.append(_plain(line))
    end_step = steps[0]
    if end_step[2] == "<primary output>":
        end = nets[0]
    elif end_step[2] == "<unknown>" or "$" in end_step[1]:
        # no name of its own (a carry output nothing reads, a DSP): the signal it comes from
        named = next((net for net in nets if "$" not in net), nets[0])
        end = _register(re.sub(r"\s*\[\d+\]$", "", named))
        if end_step[2] != "<unknown>":
            end += f" ({end_step[2].split('.', 1)[0]})"
    else:
        end = _register(end_step[1])
    launch = next((i for i, (_, _, what) in enumerate(steps) if _pin(what) in _CLOCK_PINS), None)
    if launch is None:  # from an input port: the path's last step
        start, origin, launch = steps[-1][1], 0, len(steps) - 1
    else:
        start, origin = _register(steps[launch][1]), _clock_arrival(steps, launch)
    levels = sum(1 for _, _, what in steps[1:launch] if "->" in what)
    return TimingPath(arrival - origin, start, end, levels)


def _clock_arrival(steps: list[tuple[int, str, str]], launch: int) -> int:
    """When the clock reaches the launching register (the clock buffer's delay, or 0)."""
    return steps[launch + 1][0] if launch + 1 < len(steps) else 0


def _pin(what: str) -> str:
    """The input pin of a step such as ``FDRE.C->Q``."""
    return what.split(".", 1)[-1].split("->", 1)[0] if "->" in what else ""


def _register(cell: str) -> str:
    return _CELL_SUFFIX.sub("", cell)


def _plain(name: str) -> str:
    """A Yosys name as a user reads it: no escaping backslash, ``x [3]`` as ``x[3]``."""
    return re.sub(r"\s+\[", "[", name.strip().lstrip("\\"))
