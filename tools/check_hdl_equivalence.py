"""Prove that a refactoring left the examples' circuits as they were where their VHDL changed.

tests/examples/test_hdl_digests.py says *whether* a generated VHDL file changed, byte for byte.
A refactoring that shares code inside a MyHDL process (a VHDL function instead of inline code)
or replaces one small block by an equal one (another process label) changes the text but must
not change the circuit. For every example, this builds the VHDL at a base revision and in the
working tree, and for each file whose text differs it synthesizes both with GHDL
(``ghdl --synth``) and asks Yosys to prove them equivalent: registers matched by name
(``equiv_make``; GHDL's numbered nets are not matched) or, when a block around them was
renamed, by being driven alike (``equiv_struct``); every matched signal proved by SAT
over the logic between registers (``equiv_simple``) and by induction over the registers
(``equiv_induct``); ``equiv_status -assert`` fails on anything unproven. A file whose entity
appears or disappears is reported as such, not proved.

Usage: .venv/bin/python tools/check_hdl_equivalence.py --base REV [SPEC...]
       (SPEC relative to examples/, default: every example that builds hardware)
Exit status: 0 when every changed file is proved, 1 otherwise.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tools"))

from package_tree import build_package_tree  # noqa: E402
from update_hdl_digests import EXAMPLES, example_specs  # noqa: E402

#: The package MyHDL writes beside every design; the entities need it to analyse.
MYHDL_PACKAGE = re.compile(r"pck_myhdl_\d+\.vhd$")
#: Cycles of history `equiv_simple` and `equiv_induct` may use.
SEQUENCE_DEPTH = 4


@dataclass(frozen=True)
class Verdict:
    """What the check found for one generated VHDL file of one example."""

    spec: str
    file: str
    proved: bool
    detail: str


def dump_vhdl(path: Path, out: Path) -> None:
    """Build the spec at `path` in this process; write its VHDL files under `out` (in a child)."""
    from rfc.driver import compile_spec
    from rfc.lower import lower
    from rfc.lower.artifacts import BuildOptions
    from rfc.passes.pipeline import BUILD_PIPELINE

    design = compile_spec(str(path), pipeline=BUILD_PIPELINE)
    for artifact in lower(design, BuildOptions(), path.read_text(encoding="utf-8")):
        if artifact.path.endswith(".vhd"):
            target = out / Path(artifact.path).name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_text(artifact.text, encoding="utf-8")


def build_at(tree: Path, examples: Path, specs: list[str], out: Path) -> None:
    """Write each spec of `examples` as VHDL under out/<spec>/, with rfc from the package `tree`.

    Each side builds its own checkout's examples: a refactoring may move code out of them.
    """
    environment = dict(os.environ, PYTHONPATH=str(tree))
    for spec in specs:
        subprocess.run(
            [sys.executable, __file__, "--dump", str(examples / spec), str(out / spec)],
            env=environment,
            check=True,
        )


def base_checkout(revision: str, scratch: Path) -> Path:
    """A detached worktree of `revision` under `scratch`."""
    checkout = scratch / "base"
    subprocess.run(
        ["git", "-C", str(ROOT), "worktree", "add", "--detach", "-q", str(checkout), revision],
        check=True,
    )
    return checkout


def synthesize(files: list[Path], top: str, workdir: Path) -> Path:
    """`ghdl --synth` of `top` to a Verilog netlist file (rfc's own GHDL call)."""
    from rfc.toolchain.ghdl import synthesize_verilog

    netlist = workdir / f"{top}.v"
    netlist.write_text(synthesize_verilog(files, top, workdir), encoding="utf-8")
    return netlist


def entity_of(vhdl: Path) -> str | None:
    """The entity a MyHDL-written file declares (one a file), or None for a package."""
    found = re.search(r"^entity\s+(\w+)\s+is", vhdl.read_text(encoding="utf-8"), re.M | re.I)
    return found[1] if found else None


def prove(gold: Path, gate: Path, top: str, workdir: Path) -> tuple[bool, str]:
    """Ask Yosys whether netlists `gold` and `gate` of module `top` are the same circuit.

    First with the registers paired by name; where that leaves signals unproved (a register
    moved under another block has another name), again with cells paired by how they are
    driven. Either way every pairing is a claim Yosys proves, never an assumption.
    """
    by_name = _run_equivalence(gold, gate, top, workdir / f"{top}.equiv.log", pair_cells="")
    if by_name is None:
        return True, "equivalent"
    structural = workdir / f"{top}.struct.log"
    if _run_equivalence(gold, gate, top, structural, "equiv_struct -icells; ") is None:
        return True, "equivalent (registers paired by structure)"
    return False, by_name


def _run_equivalence(gold: Path, gate: Path, top: str, log: Path, pair_cells: str) -> str | None:
    """Run one equivalence proof; None when it holds, else why not."""
    script = (
        f"read_verilog {gold}; rename {top} gold; read_verilog {gate}; rename {top} gate; "
        # GHDL numbers its own nets (n12_o, n12_q); the numbers shift with any edit, so two
        # nets of one name are not the same signal: only the design's own names are matched.
        "proc; memory -nomap; opt_clean; rename -hide w:n*_o w:n*_q w:n*_n; async2sync; "
        f"equiv_make gold gate equiv; hierarchy -top equiv; {pair_cells}"
        f"equiv_simple -seq {SEQUENCE_DEPTH}; equiv_induct -seq {SEQUENCE_DEPTH}; "
        "equiv_status -assert"
    )
    result = subprocess.run(
        ["yosys", "-q", "-l", str(log), "-p", script], capture_output=True, text=True, check=False
    )
    if result.returncode == 0:
        return None
    unproved = re.findall(r"Found (\d+) unproven \$equiv cells", result.stdout + result.stderr)
    return f"{unproved[0]} signals unproved" if unproved else result.stderr.strip()[-400:]


def compare(spec: str, before: Path, after: Path, scratch: Path) -> list[Verdict]:
    """A verdict for each VHDL file of `spec` whose text differs between the two builds."""
    verdicts = []
    names = sorted({p.name for p in before.iterdir()} | {p.name for p in after.iterdir()})
    packages = {
        side: [p for p in folder.iterdir() if MYHDL_PACKAGE.search(p.name)]
        for side, folder in (("gold", before), ("gate", after))
    }
    for name in names:
        old, new = before / name, after / name
        if MYHDL_PACKAGE.search(name):
            continue
        if not (old.is_file() and new.is_file()):
            verdicts.append(Verdict(spec, name, False, "file only on one side"))
            continue
        if old.read_bytes() == new.read_bytes():
            continue
        top = entity_of(new)
        if top is None or top != entity_of(old):
            verdicts.append(Verdict(spec, name, False, "entity renamed or missing"))
            continue
        work = scratch / "equiv" / spec / top
        try:
            # The top level instantiates the others: synthesize each side with all its files.
            gold = synthesize([*packages["gold"], *_others(before, old), old], top, work / "gold")
            gate = synthesize([*packages["gate"], *_others(after, new), new], top, work / "gate")
        except RuntimeError as error:  # GhdlError: GHDL refused one side
            verdicts.append(Verdict(spec, name, False, str(error)[-400:]))
            continue
        proved, detail = prove(gold, gate, top, work)
        verdicts.append(Verdict(spec, name, proved, detail))
    return verdicts


def _others(folder: Path, file: Path) -> list[Path]:
    """The design's other entities, for a top level that instantiates them."""
    return [
        p
        for p in sorted(folder.iterdir())
        if p != file and p.suffix == ".vhd" and not MYHDL_PACKAGE.search(p.name)
    ]


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("specs", nargs="*", help="specs relative to examples/ (default: all)")
    parser.add_argument("--base", default="main", help="the revision to compare with")
    parser.add_argument("--dump", nargs=2, metavar=("SPEC", "DIR"), help=argparse.SUPPRESS)
    parser.add_argument("--json", type=Path, help="also write the verdicts here")
    parser.add_argument(
        "--keep", action="store_true", help="keep the builds, netlists and Yosys logs (says where)"
    )
    args = parser.parse_args()
    if args.dump:
        dump_vhdl(Path(args.dump[0]), Path(args.dump[1]))
        return 0
    specs = args.specs or example_specs()
    # a kill (SIGTERM) unwinds like Ctrl-C, so the base worktree is unregistered below
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    scratch = Path(tempfile.mkdtemp(prefix="rfc-equiv-"))
    try:
        base = base_checkout(args.base, scratch)
        before = build_package_tree(base, scratch / "base-tree")
        build_at(before, base / "examples", specs, scratch / "before")
        build_at(build_package_tree(ROOT, scratch / "tree"), EXAMPLES, specs, scratch / "after")
        verdicts = [
            v
            for spec in specs
            for v in compare(spec, scratch / "before" / spec, scratch / "after" / spec, scratch)
        ]
    finally:
        subprocess.run(
            ["git", "-C", str(ROOT), "worktree", "remove", "--force", str(scratch / "base")],
            check=False,
            capture_output=True,
        )
        if args.keep:
            print(f"kept in {scratch}")
        else:
            shutil.rmtree(scratch, ignore_errors=True)
    for v in verdicts:
        print(f"{'proved  ' if v.proved else 'UNPROVED'} {v.spec}: {v.file}: {v.detail}")
    unproved = [v for v in verdicts if not v.proved]
    print(
        f"{len(specs)} examples, {len(verdicts)} changed files, "
        f"{len(verdicts) - len(unproved)} proved equivalent, {len(unproved)} not"
    )
    if args.json:
        args.json.write_text(json.dumps([v.__dict__ for v in verdicts], indent=1) + "\n")
    return 1 if unproved else 0


if __name__ == "__main__":
    sys.exit(main())
