"""Small specs for the system lowering tests, written into a test's folder."""

from __future__ import annotations

from pathlib import Path

PASS_THROUGH = "from rfc.lib.passthrough import pass_through\n"


def write_spec(folder: Path, text: str, **files: str) -> Path:
    """Write `text` as folder/spec.yaml and each keyword as a file beside it (``_`` → ``.``)."""
    for name, content in files.items():
        (folder / name.replace("__", ".")).write_text(content)
    spec = folder / "spec.yaml"
    spec.write_text(text)
    return spec


def fan_out(kind: str = "MyHDL", top: str = "pass_through", source: str = "pass.py") -> str:
    """One Twist subscriber feeding two pass-through accelerators, each to its publisher."""
    return f"""
project: {{name: FanOut, middleware: ROS2, busWidth: 32, scheduler: LST}}
accelerators:
  - name: PassTwist
    type: {kind}
    sources: ./{source}
    top: {top}
    interface:
      input: [{{message: geometry_msgs/Twist}}]
      output: [{{message: geometry_msgs/Twist}}]
blocks:
  - {{name: twist_sub, type: ROS>accelerator, message: geometry_msgs/Twist, topic: /cmd,
     outgoing: [{{name: first}}, {{name: second}}]}}
  - {{name: first, type: PassTwist, outgoing: [{{name: first_pub}}]}}
  - {{name: second, type: PassTwist, outgoing: [{{name: second_pub}}]}}
  - {{name: first_pub, type: accelerator>ROS, message: geometry_msgs/Twist, topic: /a}}
  - {{name: second_pub, type: accelerator>ROS, message: geometry_msgs/Twist, topic: /b}}
"""


def point_vhdl(name: str = "pass_point", x_bits: int = 64) -> str:
    """A VHDL Point → Point pass-through; `x_bits` other than 64 breaks the convention."""
    return f"""library ieee;
use ieee.std_logic_1164.all;

entity {name} is
  port (
    clk : in std_logic;
    rst : in std_logic;
    in0_valid : in std_logic;
    in0_ready : out std_logic;
    in0_x : in std_logic_vector({x_bits - 1} downto 0);
    in0_y : in std_logic_vector(63 downto 0);
    in0_z : in std_logic_vector(63 downto 0);
    out0_valid : out std_logic;
    out0_ready : in std_logic;
    out0_x : out std_logic_vector(63 downto 0);
    out0_y : out std_logic_vector(63 downto 0);
    out0_z : out std_logic_vector(63 downto 0)
  );
end entity {name};

architecture rtl of {name} is
begin
  out0_valid <= in0_valid;
  in0_ready <= out0_ready;
  out0_x <= (others => '0');
  out0_x({x_bits - 1} downto 0) <= in0_x;
  out0_y <= in0_y;
  out0_z <= in0_z;
end architecture rtl;
"""


def point_system(kind: str, source: str, top: str) -> str:
    """Point subscriber → one accelerator → Point publisher."""
    return f"""
project: {{name: PointSystem, middleware: ROS2, busWidth: 64, scheduler: PFP}}
accelerators:
  - name: PassPoint
    type: {kind}
    sources: ./{source}
    top: {top}
    interface:
      input: [{{message: geometry_msgs/Point}}]
      output: [{{message: geometry_msgs/Point}}]
blocks:
  - {{name: point_sub, type: ROS>accelerator, message: geometry_msgs/Point, topic: /p,
     outgoing: [{{name: acc}}]}}
  - {{name: acc, type: PassPoint, outgoing: [{{name: point_pub}}]}}
  - {{name: point_pub, type: accelerator>ROS, message: geometry_msgs/Point, topic: /q}}
"""
