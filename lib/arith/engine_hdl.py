"""The MyHDL engine that runs a `rfc.lib.arith.engine.Program`, one step per cycle.

One multiply-accumulate pipeline (`mac_pipeline`), an optional iterative sine/cosine unit, one
pipelined float64 → fixed and one fixed → float64 converter, all shared by every step; the
words live in a memory with two read ports and one write port (distributed RAM). A message's
inputs are captured whole into a shift chain that LOAD steps consume; STORE steps shift results
into an output chain that holds them until taken (the bits every result has zero written as
zeros into each of its registers). Each step's fields are registered from the program's ROM
one cycle ahead, and every unit is pipelined (`rfc.lib.arith.engine.Latencies`: the schedule
writes each word when its pipeline delivers it), so no cycle holds more than one of a ROM
lookup, a memory read, a wide adder or a conversion stage. The engine takes a message only
while idle.
"""

from __future__ import annotations

from myhdl import Signal, always, always_comb, always_seq, block, concat, intbv

from rfc.lib.arith.engine import Op, Program, latencies, write_delay
from rfc.lib.arith.mac_hdl import mac_pipeline
from rfc.lib.arith.pipeline import data_delay, delay_line, stage_register
from rfc.lib.arith.sincos_hdl import sincos_iterative
from rfc.lib.converters.wiring import follow
from rfc.lib.fixed.layout import SIGNIFICAND_BITS
from rfc.lib.fixed.pipeline import fixed_to_float_pipeline, float_to_fixed_pipeline
from rfc.lib.types import Instances, SignalLike


def _unsigned(limit: int) -> Signal:
    return Signal(intbv(0, min=0, max=max(limit, 2)))


def zero_result_bits(program: Program) -> int:
    """How many low bits of every result are zero: float64s made from words of few bits.

    A raw word of ``fmt.width`` bits has a magnitude of at most ``fmt.width`` bits (the most
    negative word's included), so its float64 (`rfc.lib.fixed.ieee754.fixed_to_float`) leaves
    the lowest ``53 - fmt.width`` bits of the significand zero; raw results have no such bits.
    """
    if not program.float_io:
        return 0
    return max(SIGNIFICAND_BITS - program.fmt.width, 0)


# Signatures alike across rfc.lib blocks are its handshake convention, not a repeated idea.
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

    Ports: clock and handshakes named as in `rfc.lib.arith.pipeline`.

    Args:
        inputs: Input signals, ``program.inputs`` of them: float64 patterns (``intbv[64:]``)
            when ``program.float_io``, else raw words of ``program.fmt``.
        outputs: Output signals, ``program.outputs`` of them, typed as `inputs`.
        program: What to compute.
    """
    fmt = program.fmt
    if len(inputs) != program.inputs or len(outputs) != program.outputs:
        raise ValueError(
            f"the program takes {program.inputs} inputs and gives {program.outputs} outputs"
        )
    delays = latencies(fmt, program.float_io)

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
    # Steps that write their word on their own cycle (the others go through a pipeline).
    now_rom = tuple(int(write_delay(s, delays) == 0) for s in steps)
    # Operation codes as plain ints: MyHDL converts names bound to ints, not enum members.
    mac_op, load_op, const_op, store_op = int(Op.MAC), int(Op.LOAD), int(Op.CONST), int(Op.STORE)
    done_op, sincos_op, cos_op = int(Op.DONE), int(Op.SINCOS), int(Op.PUT_COS)

    pc, pc_next = _unsigned(len(steps)), _unsigned(len(steps))
    op = _unsigned(len(Op))
    ra, rb, dst = _unsigned(program.size), _unsigned(program.size), _unsigned(program.size)
    first, last, writes_now = Signal(bool(0)), Signal(bool(0)), Signal(bool(0))
    const_index = _unsigned(len(const_rom))
    const_value = fmt.signal()
    running, full = Signal(bool(0)), Signal(bool(0))
    armed, waiting = Signal(bool(0)), Signal(bool(0))
    capture, shift_in, shift_out, storing_now = (Signal(bool(0)) for _ in range(4))
    memory = [fmt.signal() for _ in range(max(program.size, 2))]
    read_a, read_b, read_held = fmt.signal(), fmt.signal(), fmt.signal()
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
    zeros = zero_result_bits(program)
    storing = [
        result_register(clk, rst, shift_out, chain_out[i + 1], chain_out[i], zeros)
        if zeros
        else stage_register(clk, rst, shift_out, chain_out[i + 1], chain_out[i])
        for i in range(program.outputs)
    ]
    storing += [
        follow(stage, port)
        for stage, port in zip(chain_out[: program.outputs], outputs, strict=True)
    ]

    # LOAD and STORE: through the pipelined converters, or straight for raw words.
    always_on = Signal(bool(1))
    loaded, stored = fmt.signal(), io_signal()
    loading_now, load_write, load_target = Signal(bool(0)), Signal(bool(0)), _unsigned(program.size)
    if program.float_io:
        overflow, invalid = Signal(bool(0)), Signal(bool(0))
        conversions = [
            float_to_fixed_pipeline(clk, always_on, head_in, loaded, overflow, invalid, fmt),
            delay_line(clk, rst, always_on, loading_now, load_write, delays.load),
            data_delay(clk, always_on, dst, load_target, delays.load),
            fixed_to_float_pipeline(clk, always_on, read_held, stored, fmt),
            delay_line(clk, rst, always_on, storing_now, shift_out, delays.store),
        ]
    else:
        conversions = [
            follow(head_in, loaded),
            follow(read_a, stored),
            follow(storing_now, shift_out),
        ]

    # The multiply-accumulate pipeline, and the write flag and address beside it.
    mac_valid, mac_done, mac_result = Signal(bool(0)), Signal(bool(0)), fmt.signal()
    mac = mac_pipeline(clk, rst, always_on, mac_valid, read_a, read_b, first, mac_done,
                       mac_result, fmt)  # fmt: skip
    sum_ends, mac_write, mac_target = Signal(bool(0)), Signal(bool(0)), _unsigned(program.size)
    mac_writes = [
        delay_line(clk, rst, always_on, sum_ends, mac_write, delays.mac),
        data_delay(clk, always_on, dst, mac_target, delays.mac),
    ]

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
            angle.next = read_held[angle_bits:].signed()

        @always_seq(clk.posedge, reset=rst)
        def take() -> None:
            if sc_out_valid and sc_out_ready:
                cos_word.next = sc_cos
                sin_word.next = sc_sin

        units += [narrow, take]

    @always_comb
    def next_step() -> None:
        if not running or op == done_op:
            pc_next.next = 0
        elif op == sincos_op and not (waiting and sc_out_valid):
            pc_next.next = pc
        else:
            pc_next.next = pc + 1

    # The step's fields, registered from the ROM one cycle ahead.
    @always(clk.posedge)
    def fetch() -> None:
        op.next = op_rom[pc_next]
        ra.next = a_rom[pc_next]
        rb.next = b_rom[pc_next]
        dst.next = dst_rom[pc_next]
        first.next = first_rom[pc_next]
        last.next = last_rom[pc_next]
        writes_now.next = now_rom[pc_next]
        const_index.next = index_rom[pc_next]

    @always_comb
    def lookup() -> None:
        const_value.next = const_rom[const_index]

    @always_comb
    def read() -> None:
        read_a.next = memory[ra]
        read_b.next = memory[rb]

    # The word read on the last cycle: the STORE converter's and the sine/cosine unit's input.
    @always(clk.posedge)
    def hold_read() -> None:
        read_held.next = read_a

    @always_comb
    def control() -> None:
        in_ready.next = not running and not full
        out_valid.next = full
        capture.next = in_valid and not running and not full
        shift_in.next = running and op == load_op
        loading_now.next = running and op == load_op
        storing_now.next = running and op == store_op
        mac_valid.next = running and op == mac_op
        sum_ends.next = running and op == mac_op and last
        sc_in_valid.next = running and op == sincos_op and armed
        sc_out_ready.next = waiting
        put.next = running and writes_now
        if op == load_op:
            put_value.next = loaded
        elif op == const_op:
            put_value.next = const_value
        elif op == cos_op:
            put_value.next = cos_word
        else:
            put_value.next = sin_word

    # The schedule lets at most one of these write on a cycle.
    @always_comb
    def select_write() -> None:
        write_enable.next = mac_write or load_write or put
        if mac_write:
            write_address.next = mac_target
            write_data.next = mac_result
        elif load_write:
            write_address.next = load_target
            write_data.next = loaded
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
        pc.next = pc_next
        if not running:
            if full:
                if out_ready:
                    full.next = False
            elif in_valid:
                running.next = True
        elif op == done_op:
            running.next = False
            full.next = True
        elif op == sincos_op:
            # A cycle to register the angle, the handshake, then the wait for the result.
            if not armed and not waiting:
                armed.next = True
            elif armed:
                armed.next = False
                waiting.next = True
            elif sc_out_valid:
                waiting.next = False

    chain_tail = follow(stored, tail_out)

    return (loading, storing, conversions, mac, mac_writes, units, next_step, fetch, lookup,
            read, hold_read, control, select_write, write, sequence, chain_tail)  # fmt: skip


# Signatures of one-register blocks look alike across rfc.lib (converters' length_register).
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


# Signatures of one-register blocks look alike across rfc.lib (converters' length_register).
@block
def result_register(
    clk: SignalLike,
    rst: SignalLike,
    advance: SignalLike,
    source: SignalLike,
    target: SignalLike,
    zeros: int,
) -> Instances:
    """`stage_register` for results whose lowest `zeros` (1 or more) bits are always zero.

    Those bits are written as zeros rather than copied: synthesis then finds them constant in
    every register of the output chain at once, where from copies it finds one more register
    per round of its optimization (Franka's 112 results took 125 rounds over the whole engine).
    """
    width = len(source)

    @always_seq(clk.posedge, reset=rst)
    def load() -> None:
        if advance:
            target.next = concat(source[width:zeros], intbv(0)[zeros:])

    return load
