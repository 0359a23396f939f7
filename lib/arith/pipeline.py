"""Plumbing shared by rfc.lib's pipelined (II = 1) blocks: stall control and stage registers.

A pipeline with one stall enable moves on every cycle its last stage is empty or its result is
taken; every register of it loads on those cycles only, so a stalled consumer holds the whole
pipeline and nothing is lost or repeated.
"""

from __future__ import annotations

from myhdl import always_comb, always_seq, block


@block
def stall_control(valid_last, out_ready, advance, in_ready, out_valid):
    """`advance` (and `in_ready`) when the last stage is empty or its result is being taken."""

    @always_comb
    def control():
        advance.next = out_ready or not valid_last
        in_ready.next = out_ready or not valid_last
        out_valid.next = valid_last

    return control


@block
def stage_register(clk, rst, advance, source, target):
    """`target` takes `source` on the cycles `advance` is high."""

    @always_seq(clk.posedge, reset=rst)
    def load():
        if advance:
            target.next = source

    return load
