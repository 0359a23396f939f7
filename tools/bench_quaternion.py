"""Benchmark: the quaternion system's cycles per message, back to back, in a plain testbench.

Builds each variant of examples/quaternion_to_euler (`rfc build`), then runs its generated
logic in GHDL under a VHDL testbench without Python: the DMA side offers chunks of random unit
quaternions back to back (`tvalid` always high) and always takes the results (`tready` always
high). The testbench prints each output beat and the cycle it left on; this script checks that
every result equals the accelerator's bit-accurate reference and reports the cycles per message
in the steady state (first to last result, over the results between) and the latency of the
first message (its first input beat to its last output beat).

Usage: .venv/bin/python tools/bench_quaternion.py [--messages N] [--variants pipelined ...]
"""

from __future__ import annotations

import argparse
import os
import struct
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "quaternion_to_euler"
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(EXAMPLE))

from quat_to_euler import ITERATIVE, PIPELINED, reference  # noqa: E402

from rfc.lib.fixed import float_to_bits  # noqa: E402
from rfc.messages.rosbags_adapter import message_types  # noqa: E402
from rfc.toolchain.ghdl import simulate  # noqa: E402

SPECS = {"pipelined": "project.yaml", "iterative": "project_iterative.yaml"}
PRECISIONS = {"pipelined": PIPELINED, "iterative": ITERATIVE}
QUATERNION, POINT = "geometry_msgs/msg/Quaternion", "geometry_msgs/msg/Point"
START_END = 3
BEAT = 8


@dataclass(frozen=True)
class Beat:
    """One 64-bit AXI-Stream transfer."""

    data: int
    keep: int
    last: bool


def chunk_beats(payload: bytes, ident: int = 0) -> list[Beat]:
    """A whole-message chunk (docs/protocol.md) as beats: header, then the payload."""
    chunk = struct.pack("<HHI", ident, START_END, len(payload)) + payload
    beats = []
    for start in range(0, len(chunk), BEAT):
        part = chunk[start : start + BEAT]
        keep = (1 << len(part)) - 1
        data = int.from_bytes(part.ljust(BEAT, b"\0"), "little")
        beats.append(Beat(data, keep, start + BEAT >= len(chunk)))
    return beats


def testbench(beats: list[Beat], messages: int, top: str, limit: int) -> str:
    """A VHDL testbench streaming `beats` into `top` and printing every output beat.

    It stops after `messages` results, and fails after `limit` cycles.
    """
    rom = ",\n".join(f'    (x"{b.data:016x}", x"{b.keep:02x}", \'{int(b.last)}\')' for b in beats)
    return f"""library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;
use std.textio.all;

entity bench is
end entity bench;

architecture plain of bench is
  type beat_t is record
    data : std_logic_vector(63 downto 0);
    keep : std_logic_vector(7 downto 0);
    last : std_logic;
  end record;
  type beats_t is array (natural range <>) of beat_t;
  constant input : beats_t(0 to {len(beats) - 1}) := (
{rom});
  signal aclk : std_logic := '0';
  signal aresetn : std_logic := '0';
  signal s_tdata, m_tdata : std_logic_vector(63 downto 0);
  signal s_tkeep, m_tkeep : std_logic_vector(7 downto 0);
  signal s_tvalid, s_tready, s_tlast, m_tvalid, m_tlast : std_logic;
  signal index : natural := 0;
  signal cycle : natural := 0;
  signal done : boolean := false;
begin
  aclk <= not aclk after 5 ns when not done;
  dut : entity work.{top}
    port map (
      aclk => aclk, aresetn => aresetn,
      s_axis_mm2s_tdata => s_tdata, s_axis_mm2s_tkeep => s_tkeep,
      s_axis_mm2s_tvalid => s_tvalid, s_axis_mm2s_tready => s_tready,
      s_axis_mm2s_tlast => s_tlast,
      m_axis_s2mm_tdata => m_tdata, m_axis_s2mm_tkeep => m_tkeep,
      m_axis_s2mm_tvalid => m_tvalid, m_axis_s2mm_tready => '1', m_axis_s2mm_tlast => m_tlast,
      status_sub0_truncated => open, status_sub0_maximum => open,
      status_sub0_trailing => open, status_sub0_encoding => open);
  s_tvalid <= '1' when aresetn = '1' and index < input'length else '0';
  s_tdata <= input(index).data when index < input'length else (others => '0');
  s_tkeep <= input(index).keep when index < input'length else (others => '0');
  s_tlast <= input(index).last when index < input'length else '0';

  drive : process (aclk)
    variable line_out : line;
    variable results : natural := 0;
  begin
    if rising_edge(aclk) then
      cycle <= cycle + 1;
      if cycle = 4 then
        aresetn <= '1';
      end if;
      if s_tvalid = '1' and s_tready = '1' then
        if index = 0 then
          write(line_out, string'("FIRST_IN "));
          write(line_out, cycle);
          writeline(output, line_out);
        end if;
        index <= index + 1;
      end if;
      if m_tvalid = '1' then
        write(line_out, string'("OUT "));
        write(line_out, cycle);
        write(line_out, string'(" "));
        hwrite(line_out, m_tdata);
        write(line_out, string'(" "));
        hwrite(line_out, m_tkeep);
        write(line_out, string'(" "));
        write(line_out, m_tlast);
        writeline(output, line_out);
        if m_tlast = '1' then
          results := results + 1;
          if results = {messages} then
            done <= true;
          end if;
        end if;
      end if;
      assert cycle < {limit} report "the system stopped" severity failure;
    end if;
  end process;
end architecture plain;
"""


def quaternions(count: int) -> np.ndarray:
    rng = np.random.default_rng(count)
    q = rng.normal(size=(count, 4))
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def measure(variant: str, count: int, work: Path) -> None:
    build = work / variant
    built = subprocess.run(
        [sys.executable, "-m", "rfc", "build", str(EXAMPLE / SPECS[variant]), "-o", str(build)],
        capture_output=True,
        text=True,
        cwd=ROOT,
        # converting the pipelined core takes tens of seconds, more on a loaded machine
        env={"RFC_USER_CODE_TIMEOUT": "600", **os.environ},
    )
    if built.returncode != 0:
        raise SystemExit(f"rfc build {SPECS[variant]} failed:\n{built.stderr}")
    files = [build / "hw" / name for name in (build / "hw" / "files.txt").read_text().split()]
    top = files[-1].stem
    types = message_types("ros2")
    rows = quaternions(count)
    beats = [
        beat
        for q in rows
        for beat in chunk_beats(
            types.serialize(
                types.build(QUATERNION, dict(zip("xyzw", map(float, q), strict=True))),
                QUATERNION,
            )
        )
    ]
    source = work / f"bench_{variant}.vhd"
    source.write_text(testbench(beats, count, top, 200 * count + 2000))
    output = simulate([*files, source], "bench", work / f"ghdl_{variant}")
    first_in = next(int(line.split()[1]) for line in output.splitlines() if "FIRST_IN" in line)
    chunks, ends, current = [], [], b""
    for line in output.splitlines():
        if not line.startswith("OUT "):
            continue
        _, cycle, data, keep, last = line.split()
        current += int(data, 16).to_bytes(BEAT, "little")[: bin(int(keep, 16)).count("1")]
        if last == "1":
            chunks.append(current)
            ends.append(int(cycle))
            current = b""
    points = [types.deserialize(chunk[8:], POINT) for chunk in chunks]
    got = [tuple(float_to_bits(v) for v in (p.x, p.y, p.z)) for p in points]
    want = [reference(*(float_to_bits(float(c)) for c in q), PRECISIONS[variant]) for q in rows]
    equal = got == want
    per_message = (ends[-1] - ends[0]) / (len(ends) - 1)
    print(
        f"| {variant} | {count} | {per_message:.2f} | {ends[0] - first_in} | "
        f"{'all equal' if equal else 'MISMATCH'} |",
        flush=True,
    )
    if not equal:
        raise SystemExit(f"{variant}: results differ from the reference")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--messages", type=int, default=100, help="quaternions back to back")
    parser.add_argument("--variants", nargs="+", default=list(SPECS), choices=list(SPECS))
    args = parser.parse_args()
    print("| variant | messages | cycles per message | first message latency | results |")
    print("|---|---:|---:|---:|---|")
    with tempfile.TemporaryDirectory(prefix="rfc-bench-quaternion-") as scratch:
        for variant in args.variants:
            measure(variant, args.messages, Path(scratch))


if __name__ == "__main__":
    main()
