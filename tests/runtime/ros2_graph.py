"""Run a generated node on a real ROS 2 graph (rclpy and Fast DDS from pip) for the tests.

Each run gets its own ROS domain, localhost only; every wait is bounded and the node is always
killed, with whatever it started.
"""

from __future__ import annotations

import contextlib
import itertools
import json
import os
import signal
import subprocess
import sys
from collections.abc import Sequence
from pathlib import Path

PEER = Path(__file__).with_name("ros2_peer.py")
# Four domains per test process, 1 to 100 (the ids whose ports Linux never hands out otherwise).
_DOMAINS = itertools.cycle(range(1 + os.getpid() % 25 * 4, 5 + os.getpid() % 25 * 4))


def graph_environment() -> dict[str, str]:
    """The environment of one test's graph: a domain of its own, discovery on localhost."""
    return {
        **os.environ,
        "ROS_DOMAIN_ID": str(next(_DOMAINS)),
        "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
        "RMW_IMPLEMENTATION": "rmw_fastrtps_cpp",
    }


def exchange(
    node: Path,
    node_arguments: Sequence[str],
    job: dict,
    workdir: Path,
    *,
    interpreter: Sequence[str] = (sys.executable,),
    env: dict[str, str] | None = None,
    exits: bool = False,
) -> list[bytes | None]:
    """Start the node, let a separate rclpy process talk to it, and return the answers.

    Args:
        node: The generated ``sw/<project>_node.py``.
        node_arguments: Its options (``--device sim``).
        job: What the peer publishes and listens to (`ros2_peer`), ``timeout`` in seconds.
        workdir: Where the job and the node's log go.
        interpreter: The command that runs the node's Python.
        env: The node's environment (default: the graph's).
        exits: The node is to end by itself (its exit status goes to ``node.status`` in
            `workdir`); else it is interrupted once the peer is done.
    """
    graph = graph_environment()
    job_file = workdir / "peer.json"
    job_file.write_text(json.dumps(job))
    log = (workdir / "node.log").open("wb")
    process = subprocess.Popen(
        [*interpreter, str(node), *node_arguments],
        env={**graph, **(env or {}), "ROS_DOMAIN_ID": graph["ROS_DOMAIN_ID"]},
        stdout=log,
        stderr=subprocess.STDOUT,
        start_new_session=True,
    )
    try:
        peer = subprocess.run(
            [sys.executable, str(PEER), str(job_file)],
            env=graph,
            capture_output=True,
            text=True,
            timeout=job["timeout"] + 30,
            check=False,
        )
    finally:
        if exits:
            with contextlib.suppress(subprocess.TimeoutExpired):
                (workdir / "node.status").write_text(str(process.wait(30)))
        with contextlib.suppress(ProcessLookupError):  # the node and what it started
            os.killpg(process.pid, signal.SIGINT)
        try:
            process.wait(15)
        except subprocess.TimeoutExpired:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(process.pid, signal.SIGKILL)
            process.wait()
        log.close()
    assert peer.returncode == 0, peer.stderr + (workdir / "node.log").read_text()
    answers = json.loads(peer.stdout.strip().splitlines()[-1])
    return [None if a is None else bytes.fromhex(a) for a in answers]
