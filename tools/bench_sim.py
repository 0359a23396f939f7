"""rfc sim's marginal cost per message next to a plain testbench's, on each simulator.

For each system (the quaternion example with random orientations 1.5 µs apart, and an Odometry
pass-through fed the /odom messages of a recorded bag) and each simulator, two bags (SMALL and
LARGE messages) go

(a) through ``rfc sim --simulator S`` as a user runs it (a warm-up run fills the cache of
    compiled logic first: Verilator's model, GHDL's program), and
(b) through a plain testbench of the same logic on the same simulator, without Python:
    Verilator runs the C++ testbench (``compiler/sim/testbench/axis_engine.cpp --batch``) on a file
    of transfers; GHDL runs ``tools/bench_sim_plain_tb.vhd``, which reads them with
    textio, on the back-end rfc sim uses (analysis and elaboration are not timed).

With ``myhdl`` as the simulator, (a) runs ``rfc sim --backend myhdl`` (the whole logic in MyHDL's
simulator, in process) and there is no plain testbench.

On Verilator, (c) the cocotb harness rfc sim used before the C++ testbench (cocotbext-axi
driving the streams beat by beat, `simulate_with_ghdl(..., simulator="verilator")` in process,
on SMALL and LARGE_GHDL messages) gives the speed-up over it. On GHDL, (c) is rfc sim on GHDL's
mcode back-end (``GHDL_BACKEND=mcode``, which compiles the logic in memory at every run), the
path rfc sim took before it compiled the logic with the fastest installed back-end; its output
bags must equal the fast back-end's byte for byte. The time GHDL's back-end takes to compile
the logic once (`rfc.toolchain.cocotb_sim.compile_logic`, cold cache) is printed too.

The plain testbench gets the very transfers `rfc sim` sends, at the very cycles it sends them,
with the same idle/backpressure pattern, and runs as many cycles (recorded by an in-process
replay), so both simulate the same work. The marginal cost of a message is
(t_large - t_small) / (LARGE - SMALL), in wall time and in CPU time (user + system of rfc sim
and the simulator it runs, or of the plain testbench: on a loaded machine the figure that does
not depend on the load); the ratio is rfc sim's over the plain testbench's. The plain
testbench's outputs are checked equal to rfc sim's. Prints a Markdown table and the load.

Usage: python tools/bench_sim.py [--systems quaternion odometry]
    [--simulators ghdl verilator myhdl] [--small 20] [--large-ghdl 220] [--large-verilator 2020]
    [--large-myhdl 120] [--bag nav2_turtlebot.mcap]
"""

from __future__ import annotations

import argparse
import os
import resource
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
from rfc.sim.hardware import SimulationTop, simulate_with_ghdl  # noqa: E402
from rfc.sim.settings import ReplaySettings  # noqa: E402
from rfc.sim.stream_engine import (  # noqa: E402
    RESET_CYCLES,
    build_engine,
    pause_pattern,
    simulate_with_engine,
)
from rfc.toolchain.cocotb_sim import (  # noqa: E402
    compile_logic,
    compiled_logic,
    ghdl_environment,
)
from rfc.toolchain.ghdl import STANDARD, analyze, fastest_backend  # noqa: E402

QUATERNION = "geometry_msgs/msg/Quaternion"
ODOMETRY = "nav_msgs/msg/Odometry"
SHARED = Path(os.environ.get("RFC_SHARED_DATA", ROOT.parent / "shared" / "data"))
DRAIN = 300
SEED = 1
#: The replay settings of the in-process harnesses (as ``rfc sim --drain-cycles DRAIN``).
SETTINGS = ReplaySettings(drain_cycles=DRAIN, seed=SEED)
PLAIN_TB = ROOT / "tools" / "bench_sim_plain_tb.vhd"
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
        settings=SETTINGS,
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


@dataclass(frozen=True)
class Cost:
    """Wall and CPU seconds (user + system of the process and everything it waited for)."""

    wall: float
    cpu: float

    def __add__(self, other: Cost) -> Cost:
        return Cost(self.wall + other.wall, self.cpu + other.cpu)

    def __sub__(self, other: Cost) -> Cost:
        return Cost(self.wall - other.wall, self.cpu - other.cpu)

    def per(self, messages: int) -> Cost:
        return Cost(self.wall / messages, self.cpu / messages)

    def text(self) -> str:
        return f"{1000 * self.wall:.2f} ms ({1000 * self.cpu:.2f} ms CPU)"


def now() -> Cost:
    """The wall clock, and the CPU time of the finished child processes so far."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return Cost(time.perf_counter(), children.ru_utime + children.ru_stime)


def timed(command: list[str | Path], **options: object) -> tuple[Cost, bytes]:
    """Run `command` to its end; what it cost and its standard output."""
    start = now()
    result = subprocess.run(command, check=True, capture_output=True, **options)  # type: ignore[call-overload]
    return now() - start, result.stdout


def rfc_sim(spec: Path, bag: Path, out: Path, simulator: str, backend: str = "") -> Cost:
    """What `rfc sim` costs as a user runs it (on GHDL: on `backend`, else the fastest)."""
    chosen = ["--backend", "myhdl"] if simulator == "myhdl" else ["--simulator", simulator]
    options = ["--json", "--drain-cycles", str(DRAIN), *chosen]
    command = [sys.executable, "-m", "rfc", "sim", spec, "--bag", bag, "--out", out, *options]
    env = {**os.environ, "GHDL_BACKEND": backend} if backend else None
    return timed(command, cwd=ROOT, env=env)[0]


class Plain:
    """The plain testbenches of one system's logic."""

    def __init__(self, spec: Path, folder: Path) -> None:
        self.folder = folder
        self.design = compile_spec(spec)
        self.top = simulation_top(self.design, folder / "hdl")
        self.lanes = self.top.bus_width // 8
        self._engine: Path | None = None
        self._ghdl_work: Path | None = None
        self.backend = fastest_backend().name

    def verilator(self, stimulus: Stimulus) -> tuple[Cost, list[bytes]]:
        """What the C++ testbench costs and the transfers it received."""
        if self._engine is None:
            subscribers = DesignPlan(self.design).subscriber_names
            self._engine, _ = build_engine(self.top, subscribers)  # rfc sim's very binary
        commands = verilator_stimulus(stimulus)
        cost, output = timed([str(self._engine), "--batch"], input=commands)
        return cost, verilator_frames(output, stimulus.published)

    def ghdl_compile(self) -> Cost:
        """What GHDL's fastest back-end costs to compile rfc sim's logic once (cold cache)."""
        backend = fastest_backend()
        saved = os.environ.get("RFC_CACHE_DIR")
        os.environ["RFC_CACHE_DIR"] = str(self.folder / "cold-cache")
        try:
            logic = compiled_logic(self.top.sources, self.top.top, backend)
            start = now()
            compile_logic(logic, self.top.sources)
            return now() - start
        finally:
            if saved is None:
                os.environ.pop("RFC_CACHE_DIR")
            else:
                os.environ["RFC_CACHE_DIR"] = saved

    def ghdl(self, stimulus: Stimulus) -> tuple[Cost, list[bytes]]:
        """What the VHDL testbench costs (after analysis) and the transfers it received."""
        work = self.folder / "ghdl"
        backend = fastest_backend()
        if self._ghdl_work is None:
            tb = self.folder / "rfc_plain_tb.vhd"
            text = PLAIN_TB.read_text().replace("RFC_TOP", self.top.top)
            if self.top.busy:
                text = text.replace("-- RFC_BUSY", "busy => busy,")
            tb.write_text(text)
            with ghdl_environment(backend):
                analyze([*self.top.sources, tb], work, "rfc_plain_tb")
            self._ghdl_work = work
        source = self.folder / "stimulus.txt"
        results = self.folder / "results.txt"
        source.write_text(ghdl_stimulus(stimulus))
        options = [f"--std={STANDARD}", "-fsynopsys", f"--workdir={work}"]
        generics = [f"-gstimulus={source}", f"-gresults={results}", f"-glanes={self.lanes}"]
        generics.append(f"-gbusy_bits={max(len(self.top.busy), 1)}")
        command = ["ghdl", "-r", *options, "rfc_plain_tb", *generics, "--ieee-asserts=disable"]
        cost, _ = timed(command, cwd=work, env={**os.environ, **backend.environment()})
        frames = [bytes.fromhex(line) for line in results.read_text().split()]
        return cost, frames


def cocotb_harness(spec: Path, bag: Path, folder: Path, top: SimulationTop) -> Cost:
    """What the replay through the cocotb harness on Verilator costs (in process)."""
    design = compile_spec(spec)
    types = message_types("ros2", bags=(str(bag),))
    topics = {topic: topic for topic in bag_topics(bag, types)}
    folder.mkdir(parents=True, exist_ok=True)
    start = now()
    own = resource.getrusage(resource.RUSAGE_SELF)
    simulate_with_ghdl(
        design, bag, topics, top, folder, queues=QueueConfig(), settings=SETTINGS,
        simulator="verilator",
    )  # fmt: skip
    after = resource.getrusage(resource.RUSAGE_SELF)
    return now() - start + Cost(0, after.ru_utime + after.ru_stime - own.ru_utime - own.ru_stime)


def marginal(costs: dict[int, Cost]) -> Cost:
    """The cost of one more message, from the costs of two bags."""
    small, large = sorted(costs)
    return (costs[large] - costs[small]).per(large - small)


def measure(
    name: str,
    spec: Path,
    bags: dict[int, Path],
    simulator: str,
    folder: Path,
    plain: Plain,
    before: dict[int, Path],
) -> tuple[str, ...]:
    """One row: both bag sizes through rfc sim and the plain testbench, and the path before."""
    small, large = sorted(bags)
    rfc_sim(spec, bags[small], folder / "warm.mcap", simulator)  # caches, page cache
    sim = {n: rfc_sim(spec, bag, folder / f"out{n}.mcap", simulator) for n, bag in bags.items()}
    per_sim = marginal(sim)
    rate = f"{1 / per_sim.wall:,.1f}"
    if simulator == "myhdl":
        return name, simulator, f"{small} and {large}", per_sim.text(), "—", "—", rate, "—"
    run = plain.verilator if simulator == "verilator" else plain.ghdl
    bare, outputs = {}, {}
    for count, bag in bags.items():
        bare[count], outputs[count] = run(record(spec, bag, plain.top))
        types = message_types("ros2", bags=(str(bag),))
        published = [m.data for m in read_bag(folder / f"out{count}.mcap", types)]
        if [frame[HEADER_SIZE:] for frame in outputs[count]] != published:
            raise SystemExit(f"{name}: the plain testbench's outputs are not rfc sim's")
    per_plain = marginal(bare)
    if simulator == "verilator":
        cocotb_harness(spec, before[min(before)], folder / "warm-cocotb", plain.top)
        old = {
            n: cocotb_harness(spec, bag, folder / f"cocotb{n}", plain.top)
            for n, bag in before.items()
        }
        what = "cocotb harness"
    else:
        old = {
            n: rfc_sim(spec, bag, folder / f"mcode{n}.mcap", "ghdl", "mcode")
            for n, bag in bags.items()
        }
        for n in bags:
            if (folder / f"mcode{n}.mcap").read_bytes() != (folder / f"out{n}.mcap").read_bytes():
                raise SystemExit(
                    f"{name}: rfc sim's outputs on mcode are not those on {plain.backend}"
                )
        compiled = plain.ghdl_compile()
        what = (
            f"mcode back-end (compiling on {plain.backend}: "
            f"{compiled.wall:.1f} s, {compiled.cpu:.1f} s CPU)"
        )
    per_old = marginal(old)
    ratio = f"{per_old.wall / per_sim.wall:.1f}x ({per_old.cpu / per_sim.cpu:.1f}x CPU)"
    speedup = f"{what}: {per_old.text()}: {ratio}"
    return (
        name,
        simulator if simulator != "ghdl" else f"ghdl ({plain.backend})",
        f"{small} and {large}",
        per_sim.text(),
        per_plain.text(),
        f"{per_sim.wall / per_plain.wall:.1f}x ({per_sim.cpu / per_plain.cpu:.1f}x CPU)",
        rate,
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
        "| the path before: rfc sim's speed-up |"
    )
    print("|---|---|---|---:|---:|---:|---:|---:|")
    for row in rows:
        print("| " + " | ".join(row) + " |")
    print(f"load average: {' '.join(f'{load:.1f}' for load in os.getloadavg())}")


if __name__ == "__main__":
    main()
