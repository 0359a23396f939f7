"""check-timing: warn when an rfc.lib block inside a MyHDL accelerator cannot meet the clock.

Each MyHDL accelerator is elaborated (not converted) and its hierarchy searched for the rfc.lib
blocks with measured figures (`rfc.lib.arith.timing`: a block, its variant and its
parameters). A block whose cell delay, with the routing allowance of `--estimate`
(`rfc.toolchain.sta.ROUTING_FACTOR`), is longer than the spec's clock period is a
`BlockTimingWarning` naming the accelerator, the block, its parameters, its estimated Fmax and
what to use instead. Nothing is mapped or timed here: the figures were measured once by
`tools/timing_table.py`. The design is returned unchanged.
"""

from __future__ import annotations

import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from rfc.ir.model import AcceleratorKind, AcceleratorType, Block, BlockKind, Design
from rfc.passes.check_hardware import (
    accelerator_signatures,
    block_function,
    flat_ports,
    takes_interfaces,
)
from rfc.toolchain.sta import ROUTING_FACTOR

if TYPE_CHECKING:  # imported when used: it brings MyHDL
    from rfc.lib.arith.timing import BlockKey


class BlockTimingWarning(UserWarning):
    """An rfc.lib block at its parameters is estimated too slow for the spec's clock."""


@dataclass(frozen=True)
class CheckTiming:
    """Warn about every known rfc.lib block of a MyHDL accelerator too slow for the clock."""

    name: ClassVar[str] = "check-timing"

    def apply(self, design: Design) -> Design:
        """Return `design` unchanged, after warning (`BlockTimingWarning`) about slow blocks."""
        accelerators = list(_myhdl_accelerators(design))
        if not accelerators:
            return design  # MyHDL stays unimported: `rfc check` of other systems starts fast
        from rfc.lib.arith.timing import measured_timing, suggestion

        measured = measured_timing()
        period_ps = 1e6 / design.project.clock_mhz
        for accelerator, block in accelerators:
            for key in _known_blocks(design, accelerator, block):
                timing = measured.get(key)
                if timing is None or timing.delay_ps * ROUTING_FACTOR <= period_ps:
                    continue
                fmax = 1e6 / (timing.delay_ps * ROUTING_FACTOR)
                warnings.warn(
                    f"{accelerator.location}: accelerator '{accelerator.name}' uses {key}, "
                    f"estimated at {fmax:.0f} MHz ({timing.delay_ps / 1000:.2f} ns of cells, "
                    f"period {ROUTING_FACTOR:g}x that), below the clock of "
                    f"{design.project.clock_mhz:g} MHz; use {suggestion(key)}",
                    BlockTimingWarning,
                    stacklevel=2,
                )
        return design


def _myhdl_accelerators(design: Design) -> Iterator[tuple[AcceleratorType, Block]]:
    """Each MyHDL accelerator in the logic once, with a block that uses it."""
    infrastructure = design.infrastructure
    software = infrastructure.software if infrastructure is not None else ()
    seen: set[str] = set()
    for block in design.blocks_of(BlockKind.ACCELERATOR):
        if block.name in software or block.accelerator in seen:
            continue
        accelerator = design.accelerator(block.accelerator or "")
        if accelerator.kind is AcceleratorKind.MYHDL and all(
            path.exists() for path in accelerator.sources
        ):
            seen.add(accelerator.name)
            yield accelerator, block


def _known_blocks(
    design: Design, accelerator: AcceleratorType, block: Block
) -> tuple[BlockKey, ...]:
    """The known rfc.lib blocks the accelerator instantiates (none when it fails to elaborate).

    A block that fails is not this pass's to report: the build converts it and says why.
    """
    from rfc.lib.arith.timing import blocks_in
    from rfc.lib.converters.toplevel import port_signals
    from rfc.lib.interface import typed_block
    from rfc.toolchain import elaboration

    project = design.project
    signatures = accelerator_signatures(block, project.bus_width, project.maxima)
    function = block_function(accelerator)
    signals = port_signals(flat_ports(signatures))
    try:
        with elaboration():
            instance: Any
            if takes_interfaces(accelerator, function, signatures):
                instance = typed_block(function, signatures, f"{accelerator.name}_timing")(
                    **signals
                )
            else:
                instance = function(**signals)
    except Exception:  # the user's code: the build converts it and reports its errors
        return ()
    return blocks_in(instance)
