"""The manager entity in MyHDL's simulator: whole chunks both ways, one beat every cycle.

PS→PL, chunks offered back to back reach their subscribers intact while the DMA's MM2S stream
moves a beat on every cycle, headers included. PL→PS, two publishers that always have a beat
ready share the S2MM stream without a dead cycle between their chunks, and a lone publisher
loses only the cycle its scheduler takes to grant it again.
"""

from __future__ import annotations

import itertools
import random

import pytest
from myhdl import Simulation, StopSimulation, always, delay, instance

from rfc.lib.converters.toplevel import port_signals
from rfc.lib.manager.entity import ManagerShape, manager_body, manager_ports
from rfc.lib.schedulers.spec import Algorithm, SchedulerSpec
from rfc.runtime.protocol import Chunk, ChunkFlags, Reassembler, message_chunk
from rfc.toolchain import elaboration

WIDTH = 64


def beats_of(transfer: bytes, lanes: int) -> list[tuple[int, int, bool]]:
    """A transfer as (tdata, tkeep, tlast) beats of `lanes` bytes, little-endian."""
    beats = []
    for start in range(0, len(transfer), lanes):
        part = transfer[start : start + lanes]
        last = start + lanes >= len(transfer)
        beats.append((int.from_bytes(part, "little"), (1 << len(part)) - 1, last))
    return beats


def run(shape: ManagerShape, mm2s: list[bytes], published: list[list[bytes]], cycles: int):
    """Drive the manager for `cycles` cycles; every consumer is always ready.

    Returns:
        Per subscriber the payloads it received, the chunks that left on S2MM with the cycle
        of each beat, and the cycles on which the MM2S stream moved a beat.
    """
    lanes = shape.width // 8
    ports = port_signals(manager_ports(shape))
    clk, rst = ports["clk"], ports["rst"]
    received: list[list[bytes]] = [[] for _ in range(shape.subscribers)]
    chunks: list[bytes] = []
    s2mm_cycles: list[int] = []
    mm2s_cycles: list[int] = []
    inputs = [beat for transfer in mm2s for beat in beats_of(transfer, lanes)]
    queues = [
        [beat for message in messages for beat in beats_of(message, lanes)]
        for messages in published
    ]
    lengths = [[len(m) for m in messages for _ in beats_of(m, lanes)] for messages in published]

    with elaboration():  # MyHDL alone reads the source context of every caller
        dut = manager_body(shape, **ports)

    @always(delay(5))
    def tick():
        clk.next = not clk

    @instance
    def drive():
        partial = [b""] * shape.subscribers
        chunk = b""
        rst.next = 1
        for _ in range(3):
            yield clk.posedge
        rst.next = 0
        ports["m_axis_s2mm_tready"].next = 1
        for i in range(shape.subscribers):
            ports[f"sub{i}_tready"].next = 1
        for cycle in range(cycles):
            yield clk.negedge
            ports["s_axis_mm2s_tvalid"].next = bool(inputs)
            if inputs:
                data, keep, last = inputs[0]
                ports["s_axis_mm2s_tdata"].next = data
                ports["s_axis_mm2s_tkeep"].next = keep
                ports["s_axis_mm2s_tlast"].next = last
            for j, queue in enumerate(queues):
                ports[f"pub{j}_tvalid"].next = bool(queue)
                if queue:
                    data, keep, last = queue[0]
                    ports[f"pub{j}_tdata"].next = data
                    ports[f"pub{j}_tkeep"].next = keep
                    ports[f"pub{j}_tlast"].next = last
                    ports[f"pub{j}_length"].next = lengths[j][0]
            yield clk.posedge
            if ports["s_axis_mm2s_tvalid"] and ports["s_axis_mm2s_tready"]:
                inputs.pop(0)
                mm2s_cycles.append(cycle)
            for j, queue in enumerate(queues):
                if ports[f"pub{j}_tvalid"] and ports[f"pub{j}_tready"]:
                    queue.pop(0)
                    lengths[j].pop(0)
            for i in range(shape.subscribers):
                if ports[f"sub{i}_tvalid"]:
                    keep = int(ports[f"sub{i}_tkeep"])
                    data = int(ports[f"sub{i}_tdata"]).to_bytes(lanes, "little")
                    partial[i] += data[: bin(keep).count("1")]
                    if ports[f"sub{i}_tlast"]:
                        received[i].append(partial[i])
                        partial[i] = b""
            if ports["m_axis_s2mm_tvalid"]:
                keep = int(ports["m_axis_s2mm_tkeep"])
                data = int(ports["m_axis_s2mm_tdata"]).to_bytes(lanes, "little")
                chunk += data[: bin(keep).count("1")]
                s2mm_cycles.append(cycle)
                if ports["m_axis_s2mm_tlast"]:
                    chunks.append(chunk)
                    chunk = b""
        raise StopSimulation

    Simulation(dut, tick, drive).run(quiet=True)
    return received, chunks, s2mm_cycles, mm2s_cycles


def payloads(rng: random.Random, count: int) -> list[bytes]:
    return [rng.randbytes(rng.randrange(1, 60)) for _ in range(count)]


@pytest.mark.parametrize("width", [8, 32, 64])
def test_chunks_back_to_back_reach_their_subscribers_at_a_beat_every_cycle(width):
    rng = random.Random(3)
    shape = ManagerShape(width, 2, 0, None)
    sent = [(rng.randrange(2), payload) for payload in payloads(rng, 30)]
    transfers = [message_chunk(ident, payload).to_bytes() for ident, payload in sent]
    beats = sum(len(beats_of(t, width // 8)) for t in transfers)
    received, _, _, moved = run(shape, transfers, [], beats + 20)
    assert received == [[p for ident, p in sent if ident == i] for i in range(2)]
    # every beat, headers included, moved on consecutive cycles
    assert moved == list(range(moved[0], moved[0] + beats))


@pytest.mark.parametrize(
    ("algorithm", "width"), [(a, 64) for a in Algorithm if not a.preemptive] + [("LRU", 8)]
)
def test_two_busy_publishers_share_the_dma_without_a_dead_cycle(algorithm, width):
    rng = random.Random(f"{algorithm}{width}")
    published = [payloads(rng, 12), payloads(rng, 12)]
    shape = ManagerShape(width, 1, 2, SchedulerSpec.create(algorithm, 2))
    _, chunks, cycles, _ = run(shape, [], published, 2500)
    reassembler, by_publisher = Reassembler(), [[], []]
    for raw in chunks:
        chunk = Chunk.from_bytes(raw)
        assert chunk.flags == ChunkFlags.WHOLE
        message = reassembler.feed(chunk)
        if message is not None:
            by_publisher[chunk.id].append(message)
    assert by_publisher == published
    # while both publishers have beats to give, the stream never pauses between chunks
    total = sum(-(-len(raw) // (width // 8)) for raw in chunks)
    assert cycles == list(range(cycles[0], cycles[0] + total))


def test_a_lone_publisher_waits_only_for_its_schedulers_new_grant():
    rng = random.Random(7)
    published = [[rng.randbytes(28) for _ in range(10)]]  # a Point: 4 beats
    shape = ManagerShape(WIDTH, 1, 1, SchedulerSpec.create(Algorithm.LRU, 2))
    _, chunks, cycles, _ = run(shape, [], published, 200)
    assert [Chunk.from_bytes(raw).payload for raw in chunks] == published[0]
    ends = [cycle for cycle, next_cycle in itertools.pairwise(cycles) if next_cycle != cycle + 1]
    # 5 beats a chunk (header and 4 payload beats), and the cycle after `tlast` in which the
    # scheduler, its holder done, picks the next one (docs/schedulers.md)
    assert [b - a for a, b in itertools.pairwise(ends)] == [6] * (len(ends) - 1)
