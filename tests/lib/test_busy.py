"""The busy watch of one block, in MyHDL's simulator, cycle by cycle.

A block of two inputs and two outputs: busy while an input offers a message, and from taking
one until each output has ended a message since (in the cycle it is taken, or after); an output
beat without ``last`` does not end one, and outputs before any input leave it idle.
"""

from __future__ import annotations

from myhdl import ResetSignal, Signal, StopSimulation, always, block, delay, instance

from rfc.lib.busy import busy_body

NAMES = ("in0_valid", "in0_ready", "in1_valid", "in1_ready")
NAMES += tuple(f"out{j}_{s}" for j in range(2) for s in ("valid", "ready", "last"))


def run(script: list[dict[str, int]]) -> list[bool]:
    """Drive the watch with one dict of high wires per cycle; ``busy`` after each cycle's edge."""
    clk, rst = Signal(bool(0)), ResetSignal(1, active=1, isasync=False)
    ports = {"clk": clk, "rst": rst, "busy": Signal(bool(0))}
    ports |= {name: Signal(bool(0)) for name in NAMES}
    seen: list[bool] = []

    @block
    def bench():
        dut = busy_body(2, 2, **ports)

        @always(delay(5))
        def tick():
            clk.next = not clk

        @instance
        def drive():
            yield clk.negedge
            rst.next = 0
            for high in script:
                yield clk.negedge
                for name in NAMES:
                    ports[name].next = bool(high.get(name, 0))
                yield clk.posedge
                yield delay(1)
                seen.append(bool(ports["busy"]))
            raise StopSimulation

        return dut, tick, drive

    bench().run_sim(quiet=1)
    return seen


def ended(j: int, last: int = 1) -> dict[str, int]:
    return {f"out{j}_valid": 1, f"out{j}_ready": 1, f"out{j}_last": last}


def test_busy_from_taking_a_message_until_every_output_has_ended_one():
    taken = {"in1_valid": 1, "in1_ready": 1}
    script = [taken, *[{}] * 30, ended(0), *[{}] * 5, ended(1, last=0), {}, ended(1), {}, {}]
    seen = run(script)
    assert all(seen[:39])  # taken, computing, one output ended, the other only begun
    assert seen[39:] == [False] * 3  # from the second output's last handshake


def test_an_offered_message_is_busy_until_withdrawn_and_outputs_alone_are_not():
    offered = {"in0_valid": 1}
    seen = run([{}, offered, offered, offered, {}, ended(0), ended(1), {}])
    assert seen == [False, True, True, True, False, False, False, False]


def test_outputs_ending_as_a_message_is_taken_answer_it():
    taken = {"in0_valid": 1, "in0_ready": 1}
    assert run([taken | ended(0) | ended(1), {}]) == [True, False]  # input goes with the answer
    assert run([taken | ended(0), {}, ended(1), {}]) == [True, True, False, False]


def test_a_new_message_while_owing_waits_for_outputs_after_it():
    taken = {"in0_valid": 1, "in0_ready": 1}
    seen = run([taken, ended(0), {}, taken, ended(1), {}, ended(0), {}])
    # out0 ended before the second message: it must end again
    assert seen == [True] * 6 + [False, False]
