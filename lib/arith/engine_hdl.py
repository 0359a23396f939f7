"""The MyHDL engine that runs a `rfc.lib.arith.engine.Program`, one step per cycle.

One multiply-accumulate pipeline (`mac_pipeline`), an optional iterative sine/cosine unit, one
float64 → fixed and one fixed → float64 converter, all shared by every step; the words live in
a memory with two read ports and one write port (distributed RAM). A message's inputs are
captured whole into a shift chain that LOAD steps consume; STORE steps shift results into an
output chain that holds them until taken. The engine takes a message only while idle.
"""

from __future__ import annotations

from myhdl import Signal, always, always_comb, always_seq, block, intbv

from rfc.lib.arith.engine import WORD_WRITERS, Op, Program
from rfc.lib.arith.mac_hdl import mac_pipeline
from rfc.lib.arith.sincos_hdl import sincos_iterative
from rfc.lib.fixed.hdl import fixed_to_float, float_to_fixed
from rfc.lib.types import Instances, SignalLike


def _unsigned(limit: int) -> Signal:
    return Signal(intbv(0, min=0, max=max(limit, 2)))


@block
def engine(
    clk: SignalLike,
    rst: SignalLike,
    in_valid: SignalLike,
    in_ready: SignalLike,
    inputs: SignalLike,
    out_valid: SignalLike,
    out_ready: SignalLike,
    outputs: SignalLike,
    program: Program,
) -> Instances:
    """Run `program` on each message of `inputs`; results on `outputs` (bits of `engine.run`).

    Args:
        clk: Clock.
        rst: Synchronous reset (a MyHDL ``ResetSignal``).
        in_valid: Input, `inputs` hold a message to take.
        in_ready: Output, the engine takes the message on this cycle when `in_valid` is high.
        inputs: Input signals, ``program.inputs`` of them: float64 patterns (``intbv[64:]``)
            when ``program.float_io``, else raw words of ``program.fmt``.
        out_valid: Output, `outputs` hold a result.
        out_ready: Input, the consumer takes the result on this cycle.
        outputs: Output signals, ``program.outputs`` of them, typed as `inputs`.
        program: What to compute.
    """
    fmt = program.fmt
    if len(inputs) != program.inputs or len(outputs) != program.outputs:
        raise ValueError(
            f"the program takes {program.inputs} inputs and gives {program.outputs} outputs"
        )

    def io_signal() -> Signal:
        return Signal(intbv(0)[64:]) if program.float_io else fmt.signal()

    steps = program.steps
    op_rom = tuple(int(s.op) for s in steps)
    a_rom = tuple(s.a for s in steps)
    b_rom = tuple(s.b for s in steps)
    dst_rom = tuple(s.dst for s in steps)
    first_rom = tuple(int(s.first) for s in steps)
    last_rom = tuple(int(s.last) for s in steps)
    const_rom = program.constants or (0,)
    index_rom = tuple(s.a if s.op == Op.CONST else 0 for s in steps)
    writes_rom = tuple(int(s.op in WORD_WRITERS) for s in steps)
    # Operation codes as plain ints: MyHDL converts names bound to ints, not enum members.
    mac_op, load_op, const_op, store_op = int(Op.MAC), int(Op.LOAD), int(Op.CONST), int(Op.STORE)
    done_op, sincos_op, cos_op = int(Op.DONE), int(Op.SINCOS), int(Op.PUT_COS)

    pc = _unsigned(len(steps))
    op = _unsigned(len(Op))
    ra, rb, dst = _unsigned(program.size), _unsigned(program.size), _unsigned(program.size)
    first, last, writes_word = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    const_index = _unsigned(len(const_rom))
    const_value = fmt.signal()
    running, full, waiting = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    capture, shift_in, shift_out = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    memory = [fmt.signal() for _ in range(max(program.size, 2))]
    read_a, read_b = fmt.signal(), fmt.signal()
    put, put_value = Signal(bool(0)), fmt.signal()
    write_enable, write_address = Signal(bool(0)), _unsigned(program.size)
    write_data = fmt.signal()

    # Input and output chains: element 0 is the next input to load / the first output.
    chain_in = [io_signal() for _ in range(program.inputs + 1)]
    chain_out = [io_signal() for _ in range(program.outputs + 1)]
    head_in, tail_out = chain_in[0], chain_out[program.outputs]
    loading = [
        chain_stage(clk, rst, capture, shift_in, source, chain_in[i + 1], chain_in[i])
        for i, source in enumerate(inputs)
    ]
    storing = [
        output_stage(clk, rst, shift_out, chain_out[i + 1], chain_out[i], port)
        for i, port in enumerate(outputs)
    ]
    loaded, stored = fmt.signal(), io_signal()
    if program.float_io:
        overflow, invalid = Signal(bool(0)), Signal(bool(0))
        to_fixed = float_to_fixed(head_in, loaded, overflow, invalid, fmt)
        to_float = fixed_to_float(read_a, stored, fmt)
    else:
        to_fixed = copy(head_in, loaded)
        to_float = copy(read_a, stored)

    # The multiply-accumulate pipeline, and the write address and flag beside it.
    always_on = Signal(bool(1))
    mac_valid, mac_done, mac_result = Signal(bool(0)), Signal(bool(0)), fmt.signal()
    mac = mac_pipeline(clk, rst, always_on, mac_valid, read_a, read_b, first, mac_done,
                       mac_result, fmt)  # fmt: skip
    writes = [Signal(bool(0)) for _ in range(4)]
    targets = [_unsigned(program.size) for _ in range(4)]
    w1, w2, w3, w4 = writes
    d1, d2, d3, d4 = targets

    # The sine/cosine unit, when the program uses one.
    cos_word, sin_word = fmt.signal(), fmt.signal()
    sc_in_valid, sc_in_ready = Signal(bool(0)), Signal(bool(0))
    sc_out_valid, sc_out_ready = Signal(bool(0)), Signal(bool(0))
    units = []
    config = program.sincos
    if config is not None:
        if config.frac_bits != fmt.frac_bits or config.angle_format.width > fmt.width:
            raise ValueError(f"{config} does not fit words of {fmt}")
        angle_bits = config.angle_format.width
        angle = config.angle_format.signal()
        sc_cos, sc_sin = config.out_format.signal(), config.out_format.signal()
        units.append(
            sincos_iterative(
                clk,
                rst,
                sc_in_valid,
                sc_in_ready,
                angle,
                sc_out_valid,
                sc_out_ready,
                sc_cos,
                sc_sin,
                config,
            )
        )

        @always_comb
        def narrow() -> None:
            angle.next = read_a[angle_bits:].signed()

        @always_seq(clk.posedge, reset=rst)
        def take() -> None:
            if sc_out_valid and sc_out_ready:
                cos_word.next = sc_cos
                sin_word.next = sc_sin

        units += [narrow, take]

    @always_comb
    def decode() -> None:
        op.next = op_rom[pc]
        ra.next = a_rom[pc]
        rb.next = b_rom[pc]
        dst.next = dst_rom[pc]
        first.next = first_rom[pc]
        last.next = last_rom[pc]
        writes_word.next = writes_rom[pc]
        const_index.next = index_rom[pc]

    @always_comb
    def lookup() -> None:
        const_value.next = const_rom[const_index]

    @always_comb
    def read() -> None:
        read_a.next = memory[ra]
        read_b.next = memory[rb]

    @always_comb
    def control() -> None:
        in_ready.next = not running and not full
        out_valid.next = full
        capture.next = in_valid and not running and not full
        shift_in.next = running and op == load_op
        shift_out.next = running and op == store_op
        mac_valid.next = running and op == mac_op
        sc_in_valid.next = running and op == sincos_op and not waiting
        sc_out_ready.next = waiting
        put.next = running and writes_word
        if op == load_op:
            put_value.next = loaded
        elif op == const_op:
            put_value.next = const_value
        elif op == cos_op:
            put_value.next = cos_word
        else:
            put_value.next = sin_word

    @always_comb
    def select_write() -> None:
        write_enable.next = w4 or put
        if w4:
            write_address.next = d4
            write_data.next = mac_result
        else:
            write_address.next = dst
            write_data.next = put_value

    # One write statement, so that synthesis infers a memory (distributed RAM).
    @always(clk.posedge)
    def write() -> None:
        if write_enable:
            memory[write_address].next = write_data

    @always_seq(clk.posedge, reset=rst)
    def sequence() -> None:
        w1.next = running and op == mac_op and last
        d1.next = dst
        w2.next = w1
        d2.next = d1
        w3.next = w2
        d3.next = d2
        w4.next = w3
        d4.next = d3
        if not running:
            if full:
                if out_ready:
                    full.next = False
            elif in_valid:
                running.next = True
                pc.next = 0
        elif op == done_op:
            running.next = False
            full.next = True
            pc.next = 0
        elif op == sincos_op:
            if not waiting:
                waiting.next = True
            elif sc_out_valid:
                waiting.next = False
                pc.next = pc + 1
        else:
            pc.next = pc + 1

    @always_comb
    def chain_tail() -> None:
        tail_out.next = stored

    return (loading, storing, to_fixed, to_float, mac, units, decode, lookup, read, control,
            select_write, write, sequence, chain_tail)  # fmt: skip


@block
def chain_stage(
    clk: SignalLike,
    rst: SignalLike,
    capture: SignalLike,
    shift: SignalLike,
    source: SignalLike,
    following: SignalLike,
    stage: SignalLike,
) -> Instances:
    """One element of the input chain: the port's value on capture, the next one's on shift."""

    @always_seq(clk.posedge, reset=rst)
    def hold() -> None:
        if capture:
            stage.next = source
        elif shift:
            stage.next = following

    return hold


@block
def output_stage(
    clk: SignalLike,
    rst: SignalLike,
    shift: SignalLike,
    following: SignalLike,
    stage: SignalLike,
    port: SignalLike,
) -> Instances:
    """One element of the output chain, shown on its port."""

    @always_seq(clk.posedge, reset=rst)
    def hold() -> None:
        if shift:
            stage.next = following

    @always_comb
    def show() -> None:
        port.next = stage

    return hold, show


@block
def copy(source: SignalLike, target: SignalLike) -> Instances:
    """``target = source`` (comb)."""

    @always_comb
    def assign() -> None:
        target.next = source

    return assign
