"""Record the sha256 of every VHDL file each example generates (tests/examples/hdl_digests.json).

tests/examples/test_hdl_digests.py builds every example and compares its VHDL with these
digests, byte for byte, so a refactoring proves it leaves the hardware unchanged. Run this
only when a change means to alter the generated hardware (a generator's new feature or fix, a
new example), review which files changed, and say why in the commit; a refactoring that
changes only the text (labels, a VHDL function for shared code) first proves each changed file
the same circuit with tools/check_hdl_equivalence.py.

Usage: .venv/bin/python tools/update_hdl_digests.py [SPEC...]   (default: every example)
"""

from __future__ import annotations

import argparse
import hashlib
import json
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
EXAMPLES = ROOT / "examples"
DIGESTS = ROOT / "tests" / "examples" / "hdl_digests.json"
#: Example specs without a hardware build of their own, and why.
NOT_BUILT = {
    "image_pipeline/ImagePipeline_hls.yaml": "for rfc sim: its buffers exceed the part's BRAM",
}


def example_specs() -> list[str]:
    """Every YAML spec of the examples that builds hardware, relative to examples/.

    A Python spec describes the same system as the YAML one beside it (the same IR), so the
    YAML forms stand for both.
    """
    specs = (p.relative_to(EXAMPLES).as_posix() for p in sorted(EXAMPLES.glob("*/*.yaml")))
    return [spec for spec in specs if spec not in NOT_BUILT]


def hdl_digests(spec: str) -> dict[str, str]:
    """Build `spec` in memory in this process; the sha256 of each VHDL file it makes."""
    from rfc.driver import compile_spec
    from rfc.lower import lower
    from rfc.lower.artifacts import BuildOptions
    from rfc.passes.pipeline import BUILD_PIPELINE

    path = EXAMPLES / spec
    design = compile_spec(str(path), pipeline=BUILD_PIPELINE)
    artifacts = lower(design, BuildOptions(), path.read_text(encoding="utf-8"))
    return {
        artifact.path: hashlib.sha256(artifact.text.encode("utf-8")).hexdigest()
        for artifact in artifacts
        if artifact.path.endswith(".vhd")
    }


def read_digests() -> dict[str, dict[str, str]]:
    """The committed digests: per example spec, per generated file."""
    recorded: dict[str, dict[str, str]] = json.loads(DIGESTS.read_text(encoding="utf-8"))
    return recorded


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("specs", nargs="*", help="specs relative to examples/ (default: all)")
    args = parser.parse_args()
    wanted = args.specs or example_specs()
    recorded = read_digests() if DIGESTS.exists() and args.specs else {}
    for spec in wanted:
        recorded[spec] = hdl_digests(spec)
        print(f"{spec}: {len(recorded[spec])} VHDL files")
    text = json.dumps(dict(sorted(recorded.items())), indent=1, sort_keys=True) + "\n"
    DIGESTS.write_text(text, encoding="utf-8")


if __name__ == "__main__":
    main()
