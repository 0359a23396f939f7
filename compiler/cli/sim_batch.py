"""`rfc sim SPEC --bag DIR --out DIR`: every bag of a directory replayed, one output bag each.

A directory holding ``metadata.yaml`` is one rosbag2 bag, as before. Any other directory is a
batch: each bag in it (``.bag``, ``.mcap``, ``.db3`` files and rosbag2 directories) is one
job, `rfc sim` on that bag alone in a new process with the same options, writing
``OUT/<bag's name>`` (a rosbag2 directory's output is ``.mcap``). The jobs run here one after
another, on a local Dask cluster (``--jobs J``) or on a running scheduler (``--cluster
ADDRESS``); each output is the bag the single run writes. A bag whose replay fails is named with
its error after the others' results, which are kept, and the command exits 1.
"""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from enum import Enum
from pathlib import Path
from typing import Any

import typer
from rich.console import Console
from rich.table import Table

from rfc.cli.progress import run_counted
from rfc.errors import RfcError

#: Suffixes of the bag files a batch directory is searched for.
BAG_SUFFIXES = (".bag", ".mcap", ".db3")
#: The options that say what the batch is, not how each bag is replayed.
_BATCH_PARAMETERS = {"spec", "bag", "out", "as_json", "jobs", "cluster"}


def is_batch(bag: Path) -> bool:
    """Whether `--bag` names a directory of bags rather than one bag."""
    return bag.is_dir() and not (bag / "metadata.yaml").exists()


def bags_in(directory: Path) -> list[Path]:
    """The bags of a batch directory, by name."""
    return sorted(
        path
        for path in directory.iterdir()
        if (path.is_file() and path.suffix in BAG_SUFFIXES)
        or (path.is_dir() and (path / "metadata.yaml").exists())
    )


def refuse_batch_options(jobs: int, cluster: str | None) -> None:
    """`--jobs` and `--cluster` spread a directory's bags: with one bag they are a mistake.

    Raises:
        RfcError: One of them is given.
    """
    if jobs != 1 or cluster is not None:
        raise RfcError(
            "--jobs and --cluster spread the bags of a directory over a cluster; --bag names "
            "one bag",
            hint="give --bag a directory of bags, or leave those options out",
        )


@dataclass(frozen=True)
class BagJob:
    """One bag's replay: the command that runs it, and where it writes."""

    bag: Path
    out: Path
    command: tuple[str, ...]


def replay(job: BagJob) -> dict[str, Any]:
    """Run one bag's `rfc sim` (a new process: simulators keep state per process).

    Raises:
        RfcError: The replay failed; its own error message is kept.
    """
    done = subprocess.run(job.command, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        lines = [line for line in done.stderr.splitlines() if line.strip()]
        errors = [line for line in lines if line.startswith("error:")]
        raise RfcError((errors or lines or [f"exit status {done.returncode}"])[-1])
    return {"bag": str(job.bag), **json.loads(done.stdout)}


def run_batch(
    ctx: typer.Context,
    spec: Path,
    directory: Path,
    out: Path,
    as_json: bool,
    jobs: int,
    cluster: str | None,
) -> None:
    """Replay every bag of `directory` into `out`, here or on a Dask cluster.

    Raises:
        RfcError: No bag in the directory, OUT is a file, or some replays failed.
    """
    bags = bags_in(directory)
    if not bags:
        raise RfcError(
            f"--bag '{directory}' holds no bag (.bag, .mcap, .db3 or a rosbag2 directory)",
            hint="give a bag, or a directory of bags",
        )
    if out.exists() and not out.is_dir():
        raise RfcError(
            f"--out '{out}' is a file; a directory of bags needs a directory of outputs",
            hint="name a directory (it is created); each output takes its bag's name",
        )
    out.mkdir(parents=True, exist_ok=True)
    options = _options(ctx)
    batch = [_job(spec, bag, out, options) for bag in bags]
    results, failures = run_counted(
        "replaying bags",
        replay,
        batch,
        lambda job: f"bag {job.bag.name}",
        workers=jobs,
        address=cluster,
        hidden=as_json,
    )
    accounts = [result for result in results if result is not None]
    if as_json:
        failed = [{"job": f.job, "error": f.error} for f in failures]
        print(json.dumps({"bags": accounts, "failed": failed}, indent=1))
    else:
        Console(highlight=False).print(_table(accounts))
    if failures:
        raise RfcError(
            f"{len(failures)} of {len(batch)} replays failed ({'; '.join(map(str, failures))}); "
            f"the others' outputs are in {out}",
            hint="replay a failed bag alone to see the whole account",
        )


def _job(spec: Path, bag: Path, out: Path, options: Sequence[str]) -> BagJob:
    name = bag.name if bag.is_file() else f"{bag.name}.mcap"
    target = out.resolve() / name
    command = (
        sys.executable, "-m", "rfc", "sim", str(spec.resolve()),
        "--bag", str(bag.resolve()), "--out", str(target), *options, "--json",
    )  # fmt: skip
    return BagJob(bag, target, command)


def _options(ctx: typer.Context) -> list[str]:
    """The options the user gave `rfc sim`, as each bag's command line repeats them."""
    words: list[str] = []
    for parameter in ctx.command.params:
        value = ctx.params.get(parameter.name)
        if parameter.name in _BATCH_PARAMETERS or value is None or value is False:
            continue
        flag = parameter.opts[0]
        if value is True:
            words.append(flag)
            continue
        for item in value if isinstance(value, list | tuple) else [value]:
            words += [flag, str(item.value if isinstance(item, Enum) else item)]
    return words


def _table(accounts: list[dict[str, Any]]) -> Table:
    table = Table(title="rfc sim over a directory of bags")
    for heading in ("bag", "output", "received", "published", "dropped"):
        table.add_column(heading, justify="left" if heading in ("bag", "output") else "right")
    for account in accounts:
        table.add_row(
            Path(account["bag"]).name,
            account["out"],
            str(sum(account["received"].values())),
            str(sum(account["published"].values())),
            str(len(account["dropped"])),
        )
    return table
