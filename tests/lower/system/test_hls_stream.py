"""An HLS core taking an image as a struct and an hls::stream, in the logic, simulated in GHDL.

The stand-in of the core Vitis HLS would export for ``hls_invert/invert.cpp`` reads the
struct one cycle after ``ap_start``, moves the bytes through its ``ap_fifo`` ports whenever the
input is not empty and the output not full, and sets ``data_length`` (with its ``_ap_vld``)
only after the last byte — as Vitis HLS may schedule it. The core starts at the image's first
byte, before the subscriber has the rest of the frame; an empty image starts it with the
message. On buses of 8, 32 and 64 bits, the published images must be the inputs' with every
byte inverted (NumPy, on rosbags' messages), and the function's own C simulation (`rfc sim`)
must agree byte for byte.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from rfc.messages.rosbags_adapter import message_types, write_bag
from tests.lower.system.hls_cores import (
    built_with_vitis_run,
    c_simulated,
    replay_with_stand_in,
)
from tests.support.vendor_check import check_vivado, run_script

ROOT = Path(__file__).resolve().parents[3]
SPEC = Path(__file__).parent / "hls_invert" / "invert.yaml"
IMAGE = "sensor_msgs/msg/Image"
#: (height, width, bytes per pixel) of the images replayed: odd sizes, and an empty one.
SHAPES = [(3, 4, 3), (2, 5, 1), (0, 0, 1), (7, 9, 3), (1, 1, 1)]
#: The struct's members the core copies, each 32 bits.
COPIED = ("header_stamp_sec", "header_stamp_nanosec", "height", "width", "step")

STAND_IN = f"""library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity Invert is
  port (
    ap_clk : in std_logic;
    ap_rst : in std_logic;
    ap_start : in std_logic;
    ap_done : out std_logic;
    ap_idle : out std_logic;
    ap_ready : out std_logic;
{"".join(f"    image_{m} : in std_logic_vector(31 downto 0);{chr(10)}" for m in COPIED)}\
    image_data_length : in std_logic_vector(31 downto 0);
{
    "".join(
        f"    inverted_{m} : out std_logic_vector(31 downto 0) := (others => '0');{chr(10)}"
        f"    inverted_{m}_ap_vld : out std_logic := '0';{chr(10)}"
        for m in COPIED
    )
}\
    inverted_data_length : out std_logic_vector(31 downto 0);
    inverted_data_length_ap_vld : out std_logic;
    image_data_dout : in std_logic_vector(7 downto 0);
    image_data_empty_n : in std_logic;
    image_data_read : out std_logic;
    inverted_data_din : out std_logic_vector(7 downto 0);
    inverted_data_full_n : in std_logic;
    inverted_data_write : out std_logic
  );
end entity;

architecture stand_in of Invert is
  type state_t is (idle, head, copying, finish);
  signal state : state_t := idle;
  signal left : unsigned(31 downto 0) := (others => '0');
  signal moving : std_logic;
begin
  ap_idle <= '1' when state = idle else '0';
  -- as Vitis HLS's state machines do: done, ready and the last write during the last state
  ap_done <= '1' when state = finish else '0';
  ap_ready <= '1' when state = finish else '0';
  inverted_data_length <= image_data_length;
  inverted_data_length_ap_vld <= '1' when state = finish else '0';
  moving <= '1' when state = copying and left /= 0 and image_data_empty_n = '1'
                     and inverted_data_full_n = '1' else '0';
  image_data_read <= moving;
  inverted_data_write <= moving;
  inverted_data_din <= std_logic_vector(255 - unsigned(image_data_dout));

  run : process (ap_clk)
  begin
    if rising_edge(ap_clk) then
{"".join(f"      inverted_{m}_ap_vld <= '0';{chr(10)}" for m in COPIED)}\
      if ap_rst = '1' then
        state <= idle;
      else
        case state is
          when idle =>
            if ap_start = '1' then
              state <= head;
            end if;
          when head =>
{
    "".join(
        f"            inverted_{m} <= image_{m};{chr(10)}"
        f"            inverted_{m}_ap_vld <= '1';{chr(10)}"
        for m in COPIED
    )
}\
            left <= unsigned(image_data_length);
            state <= copying;
          when copying =>
            if left = 0 then
              state <= finish;
            elsif moving = '1' then
              left <= left - 1;
            end if;
          when finish =>
            state <= idle;
        end case;
      end if;
    end if;
  end process;
end architecture;
"""


def image_bag(path: Path) -> list[object]:
    """A ROS 2 bag of images of `SHAPES` with random bytes; returns the messages."""
    types = message_types("ros2")
    rng = np.random.default_rng(3)
    images = []
    for index, (height, width, depth) in enumerate(SHAPES):
        tree = {
            "header": {"stamp": {"sec": 40 + index, "nanosec": 1000 * index}, "frame_id": "cam"},
            "height": height,
            "width": width,
            "encoding": "rgb8" if depth == 3 else "mono8",
            "step": width * depth,
            "data": rng.integers(0, 256, size=height * width * depth, dtype=np.uint8),
        }
        images.append(types.build(IMAGE, tree))
    data = [types.serialize(image, IMAGE) for image in images]
    write_bag(path, types, {"/image": IMAGE}, [("/image", 10 * i, d) for i, d in enumerate(data)])
    return images


@pytest.mark.parametrize("width", [8, 32, 64])
def test_an_hls_core_taking_an_image_stream_runs_in_the_logic(tmp_path, width):
    images = image_bag(tmp_path / "in.mcap")
    spec = tmp_path / "spec" / SPEC.name
    shutil.copytree(SPEC.parent, spec.parent)
    spec.write_text(SPEC.read_text().replace("busWidth: 64", f"busWidth: {width}"))
    published = replay_with_stand_in(spec, STAND_IN, tmp_path / "in.mcap", "/image", tmp_path)
    types = message_types("ros2")
    assert [p.topic for p in published] == ["/inverted"] * len(images)
    for image, sent in zip(images, published, strict=True):
        out = types.deserialize(sent.data, IMAGE)
        assert (out.header.stamp.sec, out.header.stamp.nanosec) == (
            image.header.stamp.sec,
            image.header.stamp.nanosec,
        )
        assert (out.height, out.width, out.step) == (image.height, image.width, image.step)
        assert (out.header.frame_id, out.encoding) == ("", "")  # not selected: defaults
        assert out.data.tobytes() == (255 - image.data).astype(np.uint8).tobytes()
    # the function itself, C-simulated by `rfc sim`, gives the same messages
    assert c_simulated(spec, tmp_path / "in.mcap", types, tmp_path) == [p.data for p in published]


def test_the_vitis_run_gives_the_streams_ap_fifo(tmp_path):
    out, hls = built_with_vitis_run(SPEC, "Invert", tmp_path)
    modes = {args[-1][0]: args[1][0] for args in hls.of("set_directive_interface")}
    assert modes == {
        "return": "ap_ctrl_hs",
        "image": "ap_none",
        "image_data": "ap_fifo",
        "inverted": "ap_vld",
        "inverted_data": "ap_fifo",
    }
    cells = check_vivado(run_script(out / "vivado/build.tcl", tmp_path / "vivado.log"))
    core = next(ports for ports in cells.values() if "image_data_dout" in ports)
    assert {"image_data_empty_n", "image_data_read", "inverted_data_din"} <= set(core)
    assert {"inverted_data_full_n", "inverted_data_write", "image_data_length"} <= set(core)
