"""`rfc sim SPEC --bag IN --out OUT`: replay a bag through the whole system, write its outputs.

Everything the user can get wrong — the spec, the bag's topics and types, the output path, a
ROS-SW accelerator's function — is checked before anything runs; nothing is written unless the
run completes. The account at the end says what came in, what went out and what was dropped
where and why (`rfc.runtime.account`).
"""

from __future__ import annotations

import json
import shutil
import sys
import tempfile
from collections.abc import Generator
from contextlib import closing
from dataclasses import dataclass, replace
from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, Annotated

import typer
from rich.console import Console
from rich.table import Table

from rfc.cli.notes import note_skipped_topics
from rfc.cli.options import JsonOption, Simulator
from rfc.cli.progress import counting_bar
from rfc.errors import RfcError, did_you_mean
from rfc.runtime.core import DEFAULT_DEPTH, QueuePolicy
from rfc.runtime.stall import DEFAULT_STALL_CYCLES
from rfc.sim.settings import DEFAULT_DRAIN_CYCLES, ReplaySettings

if TYPE_CHECKING:
    from rfc.ir.model import Design
    from rfc.lower.runtime_plan import DesignPlan
    from rfc.messages.rosbags_adapter import BagMessage, MessageTypes
    from rfc.runtime.account import Account
    from rfc.runtime.core import Published, Runtime
    from rfc.sim.hardware import SimulationTop


class Backend(StrEnum):
    """Which simulator runs the logic."""

    GHDL = "ghdl"
    """The VHDL of the whole logic in GHDL, the runtime in cocotb (any system)."""
    MYHDL = "myhdl"
    """MyHDL's simulator, in process (logic whose top provider gives a MyHDL design)."""


sim_app = typer.Typer()
#: The top provider of ``--netlist``: the logic as GHDL synthesizes it.
NETLIST_TOP_PROVIDER = "rfc.lower.hardware:netlist_top"


@sim_app.command("sim")
def sim(
    ctx: typer.Context,
    spec: Annotated[Path, typer.Argument(metavar="SPEC", help="The system specification.")],
    bag: Annotated[
        Path,
        typer.Option(
            "--bag",
            metavar="IN",
            help="Input bag: ROS 1 .bag, ROS 2 .mcap/.db3; or a directory of bags, each replayed "
            "into OUT/<its name>.",
        ),
    ],
    out: Annotated[
        Path,
        typer.Option("--out", metavar="OUT", help="Output bag: .bag (ROS 1), .mcap or .db3."),
    ],
    backend: Annotated[
        Backend, typer.Option("--backend", help="Simulator of the logic (when it has any).")
    ] = Backend.GHDL,
    queue: Annotated[
        QueuePolicy,
        typer.Option("--queue", help="Callback queues: one per subscriber, or ROS's shared one."),
    ] = QueuePolicy.PER_SUBSCRIBER,
    depth: Annotated[
        int, typer.Option("--depth", min=1, help="Depth of each callback queue.")
    ] = DEFAULT_DEPTH,
    drain_cycles: Annotated[
        int,
        typer.Option("--drain-cycles", min=1, help="Quiet cycles after which the logic is idle."),
    ] = DEFAULT_DRAIN_CYCLES,
    stall_cycles: Annotated[
        int,
        typer.Option(
            "--stall-cycles",
            min=1,
            help="Cycles without a completed DMA transfer, while work is pending, after which "
            "the logic counts as stalled (plus 4x the longest transfer).",
        ),
    ] = DEFAULT_STALL_CYCLES,
    seed: Annotated[int, typer.Option("--seed", help="Seed of random idle/backpressure.")] = 1,
    as_json: JsonOption = False,
    send_malformed: Annotated[
        bool,
        typer.Option(
            "--send-malformed",
            help="Send malformed messages to the logic too: its subscribers drop them and count "
            "why (logic:<reason>) instead of the processor refusing them (malformed).",
        ),
    ] = False,
    top_provider: Annotated[
        str | None, typer.Option("--top-provider", hidden=True, metavar="MODULE:FUNCTION")
    ] = None,
    force: Annotated[
        bool, typer.Option("--force", help="Replace OUT even when it exists and is not a bag.")
    ] = False,
    limit: Annotated[
        int | None,
        typer.Option("--limit", min=1, metavar="N", help="Replay only the bag's first N messages."),
    ] = None,
    # Typer declares every option in the signature: rfc build's options look alike, not the same.
    topics: Annotated[
        list[str] | None,
        typer.Option(
            "--topics",
            metavar="T",
            help="Replay only these subscribed topics (repeatable, or comma-separated).",
        ),
    ] = None,
    simulator: Annotated[
        Simulator | None,
        typer.Option(
            "--simulator",
            help="Simulator of the logic with --backend ghdl: GHDL (the VHDL) or Verilator (the "
            "Verilog); by default Verilator when the whole logic is in Verilog.",
        ),
    ] = None,
    netlist: Annotated[
        bool,
        typer.Option(
            "--netlist",
            help="Simulate GHDL's synthesized netlist of each generated component (the "
            "structural top level kept): what synthesis makes of the logic.",
        ),
    ] = False,
    jobs: Annotated[
        int, typer.Option(min=1, help="A directory of bags: replay on a local Dask cluster.")
    ] = 1,
    cluster: Annotated[
        str | None,
        typer.Option(metavar="ADDRESS", help="A directory of bags: replay on this Dask scheduler."),
    ] = None,
) -> None:
    """Replay a bag through the whole system and write each publisher's messages to OUT."""
    from rfc.cli.sim_batch import is_batch, refuse_batch_options, run_batch

    if is_batch(bag):
        run_batch(ctx, spec, bag, out, as_json, jobs, cluster)
        return
    refuse_batch_options(jobs, cluster)
    from rfc.driver import compile_spec
    from rfc.lower.runtime_plan import DesignPlan
    from rfc.messages.bag_files import check_input_bag, refuse_to_replace_a_non_bag
    from rfc.messages.rosbags_adapter import check_bag_path, message_types, write_bag
    from rfc.passes.pipeline import PIPELINE
    from rfc.runtime.core import QueueConfig, Runtime
    from rfc.sim.hls_csim import HlsOnProcessor, attach_c_simulations

    # HLS accelerators run on the processor, C-simulated (rfc.sim.hls_csim)
    design = compile_spec(str(spec), pipeline=(HlsOnProcessor(), *PIPELINE))
    project = design.project
    check_bag_path(out, project.middleware)
    refuse_to_replace_a_non_bag(out, force)
    check_input_bag(bag, project.middleware)
    if out.resolve() == bag.resolve():
        raise RfcError(f"--out '{out}' is the input bag", hint="write the outputs to a new file")
    types = message_types(
        project.middleware, project.distro, tuple(str(p) for p in project.msg_paths), (str(bag),)
    )
    design = attach_c_simulations(design)
    plan = DesignPlan(design)
    note_skipped_topics(bag)
    topic_names = _chosen_topics(_match_topics(plan, bag, types), topics)
    if limit is not None or topics:
        bag = _subset(ctx, bag, types, topic_names, limit)
    queues = QueueConfig(queue, depth)
    # finds every ROS-SW function before anything runs
    runtime = Runtime(plan, queues, screen=not send_malformed)
    if netlist:
        if backend is Backend.MYHDL:
            raise typer.BadParameter("--netlist simulates VHDL netlists: use --backend ghdl")
        if simulator is Simulator.VERILATOR:
            raise typer.BadParameter("--netlist simulates VHDL netlists: use --simulator ghdl")
        simulator = Simulator.GHDL
        top_provider = top_provider or NETLIST_TOP_PROVIDER
    run = _Run(spec, bag, types, topic_names, runtime, design, backend, top_provider, simulator)
    warnings: list[str] = []
    with counting_bar("replaying", hidden=as_json) as bar:
        task = bar.add_task("replay", total=run.total())
        settings = ReplaySettings(
            drain_cycles,
            stall_cycles,
            seed,
            progress=lambda done: bar.update(task, completed=done),
            warnings=warnings,
        )
        published, account = run.execute(settings)
    write_bag(
        out,
        types,
        {output.topic: output.message for output in plan.outputs},
        ((p.topic, p.stamp, p.data) for p in published),
    )
    for warning in warnings:
        print(f"warning: {warning}", file=sys.stderr)
    if as_json:
        document = {"out": str(out), **account.to_json(), "warnings": warnings}
        print(json.dumps(document, indent=1))
    else:
        _print_account(Console(highlight=False), account, plan, out)


@dataclass(frozen=True)
class _Run:
    """One replay: the bag's messages of the spec's topics through the chosen backend."""

    spec: Path
    bag: Path
    types: MessageTypes
    topic_names: dict[str, str]
    runtime: Runtime
    design: Design
    backend: Backend
    top_provider: str | None
    simulator: Simulator | None = None

    def total(self) -> int:
        from rfc.messages.rosbags_adapter import bag_topics

        counts = bag_topics(self.bag, self.types, counts=True)
        return sum(counts[topic] for topic in self.topic_names)

    def messages(self) -> Generator[BagMessage, None, None]:
        from rfc.messages.rosbags_adapter import read_bag

        for message in read_bag(self.bag, self.types, sorted(self.topic_names)):
            yield replace(message, topic=self.topic_names[message.topic])

    def execute(self, settings: ReplaySettings) -> tuple[list[Published], Account]:
        from rfc.runtime.replay import replay
        from rfc.toolchain import CosimError

        runtime, design = self.runtime, self.design
        if not runtime.plan.has_logic:
            with closing(self.messages()) as messages:
                return replay(runtime, messages, None, settings.progress), runtime.account
        scratch = Path(tempfile.mkdtemp(prefix="rfc-sim-"))
        try:
            top = self._top(scratch / "hdl")
            if self.backend is Backend.MYHDL:
                published = self._myhdl(top, settings)
            else:
                published, account = self._ghdl(top, scratch, settings)
                runtime.account = account
        except CosimError as exc:  # the logic or a ROS-SW function failed in the simulator
            raise RfcError(f"the simulation of {design.project.name} failed: {exc}") from None
        except BaseException:
            shutil.rmtree(scratch, ignore_errors=True)
            raise
        shutil.rmtree(scratch, ignore_errors=True)  # kept above when it failed, for its log
        return published, runtime.account

    def _top(self, directory: Path) -> SimulationTop:
        """The logic generated into `directory`, its converted blocks reused from earlier runs.

        The conversion cache `rfc build` fills (`rfc.lower.system.conversion_cache`) serves
        rfc's own top providers under a key of their own (sim's pipeline moves HLS cores to the
        processor); another provider's code is not in any key, so it always converts.
        """
        from rfc.lower.system.conversion_cache import conversion_key, conversions_cached
        from rfc.sim.hardware import DEFAULT_TOP_PROVIDER, load_top_provider

        reference = self.top_provider or DEFAULT_TOP_PROVIDER
        provider = load_top_provider(reference)
        if reference not in (DEFAULT_TOP_PROVIDER, NETLIST_TOP_PROVIDER):
            return provider(self.design, directory)
        with conversions_cached(conversion_key(self.spec, self.design, "rfc sim")):
            return provider(self.design, directory)

    def _ghdl(
        self, top: SimulationTop, scratch: Path, settings: ReplaySettings
    ) -> tuple[list[Published], Account]:
        from rfc.sim.hardware import simulate_with_ghdl

        simulator = self._simulator(top)
        if simulator == "verilator":
            return self._engine(top, settings), self.runtime.account
        run = simulate_with_ghdl(
            self.design,
            self.bag.resolve(),
            self.topic_names,
            top,
            scratch,
            queues=self.runtime.queues,
            screen=self.runtime.screen,
            settings=settings,
            simulator=simulator,
            notice=lambda line: print(line, file=sys.stderr),
        )
        return run.published, run.account

    def _engine(self, top: SimulationTop, settings: ReplaySettings) -> list[Published]:
        """Verilator with the DMA streams driven in C++ (`rfc.sim.stream_engine`)."""
        from rfc.sim.stream_engine import EngineError, simulate_with_engine
        from rfc.toolchain import CosimError
        from rfc.toolchain.verilator import VerilatorError

        try:
            with closing(self.messages()) as messages:
                return simulate_with_engine(
                    self.runtime,
                    messages,
                    top,  # type: ignore[arg-type]  # _simulator checked it has Verilog
                    clock_mhz=self.design.project.clock_mhz,
                    settings=settings,
                )
        except (VerilatorError, EngineError) as exc:
            raise CosimError(str(exc)) from None

    def _simulator(self, top: SimulationTop) -> str:
        """The simulator asked for, else the fastest the logic allows."""
        verilog = bool(getattr(top, "verilog", ())) and not (
            getattr(top, "vhdl_only", ()) or getattr(top, "ghdl_verilog", ())
        )
        if self.simulator is Simulator.VERILATOR and not verilog:
            raise RfcError(
                "this logic is not all in rfc's Verilog (a VHDL accelerator, or a top provider "
                "without Verilog), so it cannot run in Verilator",
                hint="use --simulator ghdl",
            )
        if self.simulator is None:
            return "verilator" if verilog else "ghdl"
        return self.simulator.value

    def _myhdl(self, top: SimulationTop, settings: ReplaySettings) -> list[Published]:
        from rfc.sim.myhdl_sim import simulate_with_myhdl

        factory = getattr(top, "myhdl", None)
        if factory is None:
            if without := getattr(top, "without_myhdl", ()):
                raise RfcError(
                    f"the logic holds entities that are not MyHDL ({', '.join(without)}: VHDL "
                    "accelerators or vendor cores), so it cannot run in MyHDL's simulator",
                    hint="use --backend ghdl, or switch those accelerators to MyHDL or ROS-SW",
                )
            raise RfcError(
                "the logic of this system is not a MyHDL design, so it cannot run in MyHDL",
                hint="use --backend ghdl",
            )
        with closing(self.messages()) as messages:
            return simulate_with_myhdl(
                factory,
                top.bus_width,
                self.runtime,
                messages,
                clock_mhz=self.design.project.clock_mhz,
                settings=settings,
                busy=tuple(getattr(top, "busy", ())),
            )


def _chosen_topics(topic_names: dict[str, str], topics: list[str] | None) -> dict[str, str]:
    """Keep the bag topics whose spec topics `--topics` names (all when it names none)."""
    wanted = [t.strip() for entry in topics or () for t in entry.split(",") if t.strip()]
    subscribed = {spec.lstrip("/"): spec for spec in topic_names.values()}
    for topic in wanted:
        if topic.lstrip("/") not in subscribed:
            raise RfcError(
                f"--topics names '{topic}', which no subscriber of the spec takes",
                hint=did_you_mean(topic, subscribed.values())
                or f"the subscribed topics are {', '.join(sorted(subscribed.values()))}",
            )
    chosen = {t.lstrip("/") for t in wanted}
    return {
        found: spec
        for found, spec in topic_names.items()
        if not chosen or spec.lstrip("/") in chosen
    }


def _subset(
    ctx: typer.Context,
    bag: Path,
    types: MessageTypes,
    topic_names: dict[str, str],
    limit: int | None,
) -> Path:
    """The part of the bag to replay, in a folder removed when the command ends."""
    from rfc.messages.bag_subset import write_subset

    folder = Path(tempfile.mkdtemp(prefix="rfc-sim-bag-"))
    ctx.call_on_close(lambda: shutil.rmtree(folder, ignore_errors=True))
    return write_subset(bag, types, topic_names, limit, folder)


def _match_topics(plan: DesignPlan, bag: Path, types: MessageTypes) -> dict[str, str]:
    """Bag topic → spec topic for every subscriber; a leading '/' may differ (ROS 1 bags)."""
    from rfc.messages.rosbags_adapter import bag_topics

    present = bag_topics(bag, types)
    by_name = {topic.lstrip("/"): topic for topic in present}
    names: dict[str, str] = {}
    for topic_input in plan.inputs:
        block = plan.design.block(topic_input.block)
        found = by_name.get(topic_input.topic.lstrip("/"))
        if found is None:
            raise RfcError(
                f"bag '{bag}' has no topic '{topic_input.topic}', which subscriber "
                f"'{topic_input.block}' takes",
                location=block.at("topic"),
                hint=did_you_mean(topic_input.topic, present)
                or f"its topics are {', '.join(sorted(present)) or 'none'}",
            )
        if present[found] != topic_input.message:
            raise RfcError(
                f"topic '{found}' of bag '{bag}' carries {present[found]}, but subscriber "
                f"'{topic_input.block}' takes {topic_input.message}",
                location=block.at("message"),
                hint=f"subscribe to a topic of {topic_input.message}, or set the subscriber's "
                f"message to {present[found]}",
            )
        names[found] = topic_input.topic
    return names


def _print_account(console: Console, account: Account, plan: DesignPlan, out: Path) -> None:
    table = Table(title=f"account of {plan.design.project.name}", title_justify="left")
    for column in ("", "where", "messages"):
        table.add_column(column, justify="right" if column == "messages" else "left")
    for topic, count in account.received.items():
        table.add_row("in", topic, str(count))
    for name, count in account.to_logic.items():
        table.add_row("to logic", name, str(count))
    for name, count in account.from_logic.items():
        table.add_row("from logic", name, str(count))
    for name, count in account.software_calls.items():
        table.add_row("software calls", name, str(count))
    for output in plan.outputs:
        table.add_row("out", output.topic, str(account.published.get(output.topic, 0)))
    for (where, reason), count in sorted(account.dropped.items()):
        table.add_row(f"dropped: {reason}", where, str(count))
    if not account.dropped:
        table.add_row("dropped", "—", "0")
    console.print(table)
    total = sum(account.published.values())
    print(f"wrote {total} message{'s' if total != 1 else ''} to {out}", file=sys.stderr)
