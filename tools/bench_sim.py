"""rfc sim's marginal cost per message next to a plain testbench's, on each simulator.

For each system (the quaternion example with random orientations 1.5 µs apart, and an Odometry
pass-through fed the /odom messages of a recorded bag) and each simulator, two bags (SMALL and
LARGE messages) go

(a) through ``rfc sim --simulator S`` as a user runs it (a warm-up run fills Verilator's cache
    first), and
(b) through a plain testbench of the same logic on the same simulator, without Python:
    Verilator runs the C++ testbench (``compiler/sim/testbench/axis_engine.cpp --batch``) on a file
    of transfers; GHDL runs ``compiler/sim/testbench/axis_plain_tb.vhd``, which reads them with
    textio (analysis and elaboration are not timed).

With ``myhdl`` as the simulator, (a) runs ``rfc sim --backend myhdl`` (the whole logic in MyHDL's
simulator, in process) and there is no plain testbench.

On Verilator, (c) the cocotb harness rfc sim used before the C++ testbench (cocotbext-axi
driving the streams beat by beat, `simulate_with_ghdl(..., simulator="verilator")` in process,
on SMALL and LARGE_GHDL messages) gives the speed-up over it.

The plain testbench gets the very transfers `rfc sim` sends, at the very cycles it sends them,
with the same idle/backpressure pattern, and runs as many cycles (recorded by an in-process
replay), so both simulate the same work. The marginal cost of a message is
(t_large - t_small) / (LARGE - SMALL); the ratio is rfc sim's over the plain testbench's.
The plain testbench's outputs are checked equal to rfc sim's. Prints a Markdown table.

Usage: python tools/bench_sim.py [--systems quaternion odometry]
    [--simulators ghdl verilator myhdl] [--small 20] [--large-ghdl 220] [--large-verilator 2020]
    [--large-myhdl 120] [--bag nav2_turtlebot.mcap]
"""

from __future__ import annotations

import argparse
import os
import struct
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from rfc.driver import compile_spec  # noqa: E402
from rfc.lower.hardware import simulation_top  # noqa: E402
from rfc.lower.runtime_plan import DesignPlan  # noqa: E402
from rfc.messages.rosbags_adapter import (  # noqa: E402
    bag_topics,
    message_types,
    read_bag,
    write_bag,
)
from rfc.runtime.core import Published, QueueConfig, Queued, Runtime  # noqa: E402
from rfc.runtime.protocol import HEADER_SIZE, Chunk  # noqa: E402
from rfc.runtime.stall import DEFAULT_STALL_CYCLES  # noqa: E402
from rfc.sim.hardware import SimulationTop, simulate_with_ghdl  # noqa: E402
from rfc.sim.stream_engine import (  # noqa: E402
    RESET_CYCLES,
    build_engine,
    pause_pattern,
    simulate_with_engine,
)
from rfc.toolchain.ghdl import STANDARD, analyze  # noqa: E402

QUATERNION = "geometry_msgs/msg/Quaternion"
ODOMETRY = "nav_msgs/msg/Odometry"
SHARED = Path(os.environ.get("RFC_SHARED_DATA", ROOT.parent / "shared" / "data"))
DRAIN = 300
SEED = 1
PLAIN_TB = ROOT / "compiler" / "sim" / "testbench" / "axis_plain_tb.vhd"
ODOMETRY_SPEC = """\
project: {name: OdomPass, middleware: ROS2, busWidth: 64, scheduler: LRU}
accelerators:
  - name: PassOdometry
    type: MyHDL
    sources: ./pass.py
    top: pass_through
    interface:
      input: [{message: nav_msgs/Odometry}]
      output: [{message: nav_msgs/Odometry}]
blocks:
  - {name: odom_sub, type: ROS>accelerator, message: nav_msgs/Odometry, topic: /odom,
     outgoing: [{name: pass}]}
  - {name: pass, type: PassOdometry, outgoing: [{name: odom_pub}]}
  - {name: odom_pub, type: accelerator>ROS, message: nav_msgs/Odometry, topic: /odom_out}
"""


def orientations_bag(path: Path, count: int) -> None:
    """`count` random unit quaternions on /imu/orientation, 1.5 µs apart."""
    types = message_types("ros2")
    rng = np.random.default_rng(count)
    quaternions = rng.normal(size=(count, 4))
    quaternions /= np.linalg.norm(quaternions, axis=1, keepdims=True)
    messages = [
        (
            "/imu/orientation",
            1500 * (i + 1),
            types.serialize(
                types.build(QUATERNION, dict(zip("xyzw", map(float, q), strict=True))), QUATERNION
            ),
        )
        for i, q in enumerate(quaternions)
    ]
    write_bag(path, types, {"/imu/orientation": QUATERNION}, messages)


def odometry_bag(path: Path, count: int, recorded: Path) -> None:
    """The first `count` /odom messages of the recorded bag."""
    types = message_types("ros2", bags=(str(recorded),))
    messages = []
    for message in read_bag(recorded, types, ["/odom"]):
        messages.append((message.topic, message.timestamp_ns, message.data))
        if len(messages) == count:
            break
    if len(messages) < count:
        raise SystemExit(f"{recorded} has only {len(messages)} /odom messages")
    write_bag(path, types, {"/odom": ODOMETRY}, messages)


@dataclass(frozen=True)
class Stimulus:
    """The transfers rfc sim sends and the cycles it sends them at (after reset)."""

    transfers: list[tuple[int, bytes]]
    end: int
    published: int


class _Recording(Runtime):
    """A runtime that notes every PS→PL transfer with the cycle of the last offer or answer."""

    def __init__(self, *args: object, **kwargs: object) -> None:
        super().__init__(*args, **kwargs)  # type: ignore[arg-type]
        self.now = 0
        self.sent: list[tuple[int, bytes]] = []

    def offer(self, topic: str, data: bytes, stamp: int, now: int = 0) -> list[Published]:
        self.now = now
        return super().offer(topic, data, stamp, now)

    def receive(self, transfer: bytes, stamp: int, now: int = 0) -> list[Published]:
        self.now = now
        return super().receive(transfer, stamp, now)

    def next_transfer(self) -> tuple[Chunk, Queued] | None:
        chosen = super().next_transfer()
        if chosen is not None:
            self.sent.append((self.now - RESET_CYCLES, chosen[0].to_bytes()))
        return chosen


def record(spec: Path, bag: Path, top: object) -> Stimulus:
    """Replay in process once, noting the transfers and when they went."""
    design = compile_spec(spec)
    runtime = _Recording(DesignPlan(design))
    types = message_types("ros2", bags=(str(bag),))
    published = simulate_with_engine(
        runtime,
        read_bag(bag, types, runtime.topics),
        top,  # type: ignore[arg-type]
        clock_mhz=design.project.clock_mhz,
        drain_cycles=DRAIN,
        stall_cycles=DEFAULT_STALL_CYCLES,
        seed=SEED,
    )
    return Stimulus(runtime.sent, runtime.now - RESET_CYCLES + DRAIN, len(published))


def verilator_stimulus(stimulus: Stimulus) -> bytes:
    """The batch commands of the C++ testbench."""
    pattern = pause_pattern(SEED)
    parts = [struct.pack("<I", len(pattern)), pattern]
    at = 0
    for cycle, transfer in stimulus.transfers:
        parts += [b"W", struct.pack("<Q", max(cycle - at, 0))]
        parts += [b"S", struct.pack("<I", len(transfer)), transfer]
        at = max(cycle, at)
    parts += [b"W", struct.pack("<Q", max(stimulus.end - at, 0))]
    return b"".join(parts)


def verilator_frames(output: bytes, messages: int) -> list[bytes]:
    """The PL→PS transfers the C++ testbench wrote (its status registers follow them)."""
    frames, at = [], 0
    for _ in range(messages):
        (size,) = struct.unpack_from("<I", output, at)
        frames.append(output[at + 4 : at + 4 + size])
        at += 4 + size
    return frames


def ghdl_stimulus(stimulus: Stimulus) -> str:
    """The stimulus file of the VHDL testbench."""
    pattern = "".join(str(b) for b in pause_pattern(SEED))
    lines = [pattern, str(stimulus.end)]
    lines += [f"{cycle} {len(t)} {t.hex()}" for cycle, t in stimulus.transfers]
    return "\n".join(lines) + "\n"


def rfc_sim(spec: Path, bag: Path, out: Path, simulator: str) -> float:
    """Wall time of `rfc sim` as a user runs it."""
    start = time.perf_counter()
    chosen = ["--backend", "myhdl"] if simulator == "myhdl" else ["--simulator", simulator]
    options = ["--json", "--drain-cycles", str(DRAIN), *chosen]
    subprocess.run(
        [sys.executable, "-m", "rfc", "sim", spec, "--bag", bag, "--out", out, *options],
        check=True,
        capture_output=True,
        cwd=ROOT,
    )
    return time.perf_counter() - start


class Plain:
    """The plain testbenches of one system's logic."""

    def __init__(self, spec: Path, folder: Path) -> None:
        self.folder = folder
        self.design = compile_spec(spec)
        self.top = simulation_top(self.design, folder / "hdl")
        self.lanes = self.top.bus_width // 8
        self._engine: Path | None = None
        self._ghdl_work: Path | None = None

    def verilator(self, stimulus: Stimulus) -> tuple[float, list[bytes]]:
        """Wall time of the C++ testbench and the transfers it received."""
        if self._engine is None:
            subscribers = DesignPlan(self.design).subscriber_names
            self._engine, _ = build_engine(self.top, subscribers)  # rfc sim's very binary
        commands = verilator_stimulus(stimulus)
        start = time.perf_counter()
        result = subprocess.run(
            [str(self._engine), "--batch"], input=commands, capture_output=True, check=True
        )
        elapsed = time.perf_counter() - start
        return elapsed, verilator_frames(result.stdout, stimulus.published)

    def ghdl(self, stimulus: Stimulus) -> tuple[float, list[bytes]]:
        """Wall time of the VHDL testbench (after analysis) and the transfers it received."""
        work = self.folder / "ghdl"
        if self._ghdl_work is None:
            tb = self.folder / "rfc_plain_tb.vhd"
            text = PLAIN_TB.read_text().replace("RFC_TOP", self.top.top)
            if self.top.busy:
                text = text.replace("-- RFC_BUSY", "busy => busy,")
            tb.write_text(text)
            analyze([*self.top.sources, tb], work, "rfc_plain_tb")
            self._ghdl_work = work
        source = self.folder / "stimulus.txt"
        results = self.folder / "results.txt"
        source.write_text(ghdl_stimulus(stimulus))
        options = [f"--std={STANDARD}", "-fsynopsys", f"--workdir={work}"]
        generics = [f"-gstimulus={source}", f"-gresults={results}", f"-glanes={self.lanes}"]
        generics.append(f"-gbusy_bits={max(len(self.top.busy), 1)}")
        start = time.perf_counter()
        subprocess.run(
            ["ghdl", "-r", *options, "rfc_plain_tb", *generics, "--ieee-asserts=disable"],
            check=True,
            capture_output=True,
            cwd=work,
        )
        elapsed = time.perf_counter() - start
        frames = [bytes.fromhex(line) for line in results.read_text().split()]
        return elapsed, frames


def cocotb_harness(spec: Path, bag: Path, folder: Path, top: SimulationTop) -> float:
    """Wall time of the replay through the cocotb harness on Verilator."""
    design = compile_spec(spec)
    types = message_types("ros2", bags=(str(bag),))
    topics = {topic: topic for topic in bag_topics(bag, types)}
    folder.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    simulate_with_ghdl(
        design, bag, topics, top, folder, queues=QueueConfig(), drain_cycles=DRAIN, seed=SEED,
        simulator="verilator",
    )  # fmt: skip
    return time.perf_counter() - start


def measure(
    name: str,
    spec: Path,
    bags: dict[int, Path],
    simulator: str,
    folder: Path,
    plain: Plain,
    before: dict[int, Path],
) -> tuple[str, ...]:
    """One row: both bag sizes through rfc sim and the plain testbench (and the old harness)."""
    small, large = sorted(bags)
    rfc_sim(spec, bags[small], folder / "warm.mcap", simulator)  # caches, page cache
    sim = {n: rfc_sim(spec, bag, folder / f"out{n}.mcap", simulator) for n, bag in bags.items()}
    per_sim = (sim[large] - sim[small]) / (large - small)
    if simulator == "myhdl":
        cost = f"{1000 * per_sim:.3f} ms"
        return name, simulator, f"{small} and {large}", cost, "—", "—", f"{1 / per_sim:,.1f}", "—"
    run = plain.verilator if simulator == "verilator" else plain.ghdl
    bare, outputs = {}, {}
    for count, bag in bags.items():
        bare[count], outputs[count] = run(record(spec, bag, plain.top))
        types = message_types("ros2", bags=(str(bag),))
        published = [m.data for m in read_bag(folder / f"out{count}.mcap", types)]
        if [frame[HEADER_SIZE:] for frame in outputs[count]] != published:
            raise SystemExit(f"{name}: the plain testbench's outputs are not rfc sim's")
    per_plain = (bare[large] - bare[small]) / (large - small)
    speedup = "—"
    if simulator == "verilator":
        few, many = sorted(before)
        cocotb_harness(spec, before[few], folder / "warm-cocotb", plain.top)
        old = {
            n: cocotb_harness(spec, bag, folder / f"cocotb{n}", plain.top)
            for n, bag in before.items()
        }
        per_old = (old[many] - old[few]) / (many - few)
        speedup = f"{1000 * per_old:.2f} ms: {per_old / per_sim:.0f}x"
    return (
        name,
        simulator,
        f"{small} and {large}",
        f"{1000 * per_sim:.3f} ms",
        f"{1000 * per_plain:.3f} ms",
        f"{per_sim / per_plain:.1f}x",
        f"{1 / per_sim:,.0f}",
        speedup,
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--systems", nargs="+", default=["quaternion", "odometry"])
    parser.add_argument("--simulators", nargs="+", default=["ghdl", "verilator"])
    parser.add_argument("--small", type=int, default=20)
    parser.add_argument("--large-ghdl", type=int, default=220)
    parser.add_argument("--large-verilator", type=int, default=2020)
    parser.add_argument("--large-myhdl", type=int, default=120)
    parser.add_argument("--bag", type=Path, default=SHARED / "bags" / "nav2_turtlebot.mcap")
    args = parser.parse_args()
    rows = []
    with tempfile.TemporaryDirectory(prefix="rfc-bench-sim-") as scratch:
        folder = Path(scratch)
        (folder / "pass.py").write_text("from rfc.lib.passthrough import pass_through\n")
        (folder / "odometry.yaml").write_text(ODOMETRY_SPEC)
        specs = {
            "quaternion": ROOT / "examples/quaternion_to_euler/project.yaml",
            "odometry": folder / "odometry.yaml",
        }
        for system in args.systems:
            plain = Plain(specs[system], folder / system)
            bags = {}
            for count in {args.small, args.large_ghdl, args.large_verilator, args.large_myhdl}:
                bags[count] = folder / f"{system}{count}.mcap"
                if system == "quaternion":
                    orientations_bag(bags[count], count)
                else:
                    odometry_bag(bags[count], count, args.bag)
            before = {n: bags[n] for n in (args.small, args.large_ghdl)}
            for simulator in args.simulators:
                large = {"ghdl": args.large_ghdl, "myhdl": args.large_myhdl}.get(
                    simulator, args.large_verilator
                )
                chosen = {n: bags[n] for n in (args.small, large)}
                row = measure(system, specs[system], chosen, simulator, folder, plain, before)
                rows.append(row)
    print(
        "| system | simulator | bags | rfc sim | plain testbench | ratio | rfc sim msg/s "
        "| cocotb harness: rfc sim's speed-up |"
    )
    print("|---|---|---|---:|---:|---:|---:|---:|")
    for row in rows:
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
