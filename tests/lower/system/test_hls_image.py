"""An HLS core whose input port carries two streams (header.frame_id and data), in the logic.

The stand-in of the core Vitis HLS would export for the paper's first image stage
(``examples/image_pipeline/rgb_to_gray.cpp``) reads its struct, then copies the frame's
``frame_id`` character by character, then turns each RGB pixel into its gray byte — in the
function's order, so it reads the whole ``frame_id`` before the first pixel. The wrapper starts
it at the first byte of ``data``, the port's last stream, and holds ``frame_id`` in a FIFO until
then. On buses of 8 and
64 bits the published images must be OpenCV's integer BT.601 luma of the inputs (NumPy, on
rosbags' messages) with their stamp and frame_id, and the function's own C simulation
(`rfc sim`) must agree byte for byte. The paper's three-stage HLS pipeline itself (a copy with
small maxima) passes `rfc check` and builds.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from rfc.driver import compile_spec
from rfc.hls.ports import input_holds
from rfc.messages.rosbags_adapter import message_types, write_bag
from tests.lower.system.hls_cores import (
    IMAGE_PIPELINE,
    c_simulated,
    replay_with_stand_in,
    shrink_images,
)
from tests.support.cli import run_rfc
from tests.support.vendor_check import check_vivado, run_script

ROOT = Path(__file__).resolve().parents[3]
HERE = Path(__file__).parent
SPEC = HERE / "hls_gray" / "gray.yaml"
#: The example's first stage, as gray.yaml names it.
GRAY_SOURCE = "../../../../examples/image_pipeline/rgb_to_gray.cpp"
IMAGE = "sensor_msgs/msg/Image"
#: (height, width, frame_id) of the RGB images replayed: odd sizes, an empty image, an empty
#: frame_id and one of the project's maximum (16 characters).
FRAMES = [(3, 4, "cam"), (2, 5, ""), (0, 0, "left"), (8, 8, "camera_left_0123"), (1, 1, "x")]
#: The struct's members the core copies, each 32 bits.
COPIED = ("header_stamp_sec", "header_stamp_nanosec", "height", "width")

STAND_IN = f"""library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity RgbToGray is
  port (
    ap_clk : in std_logic;
    ap_rst : in std_logic;
    ap_start : in std_logic;
    ap_done : out std_logic;
    ap_idle : out std_logic;
    ap_ready : out std_logic;
{"".join(f"    rgb_{m} : in std_logic_vector(31 downto 0);{chr(10)}" for m in COPIED)}\
    rgb_header_frame_id_length : in std_logic_vector(31 downto 0);
    rgb_data_length : in std_logic_vector(31 downto 0);
{
    "".join(
        f"    gray_{m} : out std_logic_vector(31 downto 0) := (others => '0');{chr(10)}"
        f"    gray_{m}_ap_vld : out std_logic := '0';{chr(10)}"
        for m in COPIED
    )
}\
    gray_header_frame_id_length : out std_logic_vector(31 downto 0);
    gray_header_frame_id_length_ap_vld : out std_logic;
    gray_data_length : out std_logic_vector(31 downto 0);
    gray_data_length_ap_vld : out std_logic;
    rgb_header_frame_id_dout : in std_logic_vector(7 downto 0);
    rgb_header_frame_id_empty_n : in std_logic;
    rgb_header_frame_id_read : out std_logic;
    rgb_data_dout : in std_logic_vector(7 downto 0);
    rgb_data_empty_n : in std_logic;
    rgb_data_read : out std_logic;
    gray_header_frame_id_din : out std_logic_vector(7 downto 0);
    gray_header_frame_id_full_n : in std_logic;
    gray_header_frame_id_write : out std_logic;
    gray_data_din : out std_logic_vector(7 downto 0);
    gray_data_full_n : in std_logic;
    gray_data_write : out std_logic
  );
end entity;

architecture stand_in of RgbToGray is
  type state_t is (idle, head, naming, pixels, finish);
  signal state : state_t := idle;
  signal left : unsigned(31 downto 0) := (others => '0');
  signal channel : integer range 0 to 2 := 0;
  signal r, g : unsigned(31 downto 0) := (others => '0');
  signal luma : unsigned(63 downto 0);
  signal naming_move, pixel_move : std_logic;
begin
  ap_idle <= '1' when state = idle else '0';
  ap_done <= '1' when state = finish else '0';
  ap_ready <= '1' when state = finish else '0';
  gray_header_frame_id_length <= rgb_header_frame_id_length;
  gray_header_frame_id_length_ap_vld <= '1' when state = finish else '0';
  gray_data_length <= std_logic_vector(unsigned(rgb_data_length) / 3);
  gray_data_length_ap_vld <= '1' when state = finish else '0';
  naming_move <= '1' when state = naming and left /= 0 and rgb_header_frame_id_empty_n = '1'
                          and gray_header_frame_id_full_n = '1' else '0';
  rgb_header_frame_id_read <= naming_move;
  gray_header_frame_id_write <= naming_move;
  gray_header_frame_id_din <= rgb_header_frame_id_dout;
  pixel_move <= '1' when state = pixels and left /= 0 and rgb_data_empty_n = '1'
                         and (channel /= 2 or gray_data_full_n = '1') else '0';
  rgb_data_read <= pixel_move;
  gray_data_write <= pixel_move when channel = 2 else '0';
  luma <= r * 4899 + g * 9617 + resize(unsigned(rgb_data_dout), 32) * 1868 + 8192;
  gray_data_din <= std_logic_vector(luma(21 downto 14));

  run : process (ap_clk)
  begin
    if rising_edge(ap_clk) then
{"".join(f"      gray_{m}_ap_vld <= '0';{chr(10)}" for m in COPIED)}\
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
        f"            gray_{m} <= rgb_{m};{chr(10)}            gray_{m}_ap_vld <= '1';{chr(10)}"
        for m in COPIED
    )
}\
            left <= unsigned(rgb_header_frame_id_length);
            state <= naming;
          when naming =>
            if left = 0 then
              left <= unsigned(rgb_data_length);
              channel <= 0;
              state <= pixels;
            elsif naming_move = '1' then
              left <= left - 1;
            end if;
          when pixels =>
            if left = 0 then
              state <= finish;
            elsif pixel_move = '1' then
              left <= left - 1;
              if channel = 0 then
                r <= resize(unsigned(rgb_data_dout), 32);
                channel <= 1;
              elsif channel = 1 then
                g <= resize(unsigned(rgb_data_dout), 32);
                channel <= 2;
              else
                channel <= 0;
              end if;
            end if;
          when finish =>
            state <= idle;
        end case;
      end if;
    end if;
  end process;
end architecture;
"""


def rgb_bag(path: Path) -> list[object]:
    """A ROS 2 bag of rgb8 images of `FRAMES` with random pixels; returns the messages."""
    types = message_types("ros2")
    rng = np.random.default_rng(5)
    images = []
    for index, (height, width, frame_id) in enumerate(FRAMES):
        tree = {
            "header": {"stamp": {"sec": 7 + index, "nanosec": 99 * index}, "frame_id": frame_id},
            "height": height,
            "width": width,
            "encoding": "rgb8",
            "step": width * 3,
            "data": rng.integers(0, 256, size=height * width * 3, dtype=np.uint8),
        }
        images.append(types.build(IMAGE, tree))
    data = [types.serialize(image, IMAGE) for image in images]
    write_bag(path, types, {"/image": IMAGE}, [("/image", 10 * i, d) for i, d in enumerate(data)])
    return images


def luma(data: np.ndarray) -> bytes:
    """OpenCV's integer BT.601 luma of rgb8 pixels, the function's definition."""
    r, g, b = (data.reshape(-1, 3)[:, k].astype(np.uint32) for k in range(3))
    return ((4899 * r + 9617 * g + 1868 * b + 8192) >> 14).astype(np.uint8).tobytes()


@pytest.mark.parametrize("width", [8, 64])
def test_an_hls_core_taking_a_header_and_an_image_stream_runs_in_the_logic(tmp_path, width):
    images = rgb_bag(tmp_path / "in.mcap")
    folder = tmp_path / "spec" / "hls_gray"
    shutil.copytree(SPEC.parent, folder)
    spec = folder / SPEC.name
    text = SPEC.read_text().replace("busWidth: 64", f"busWidth: {width}")
    spec.write_text(text.replace(GRAY_SOURCE, str((SPEC.parent / GRAY_SOURCE).resolve())))
    published = replay_with_stand_in(spec, STAND_IN, tmp_path / "in.mcap", "/image", tmp_path)
    types = message_types("ros2")
    assert [p.topic for p in published] == ["/gray"] * len(images)
    for image, sent in zip(images, published, strict=True):
        out = types.deserialize(sent.data, IMAGE)
        assert (out.header.stamp.sec, out.header.stamp.nanosec, out.header.frame_id) == (
            image.header.stamp.sec,
            image.header.stamp.nanosec,
            image.header.frame_id,
        )
        assert (out.height, out.width) == (image.height, image.width)
        assert out.data.tobytes() == luma(image.data)
    # the function itself, C-simulated by `rfc sim`, gives the same messages
    assert c_simulated(spec, tmp_path / "in.mcap", types, tmp_path) == [p.data for p in published]


@pytest.fixture
def small_pipeline(tmp_path: Path) -> Path:
    """The example's HLS image pipeline with small images, in a folder of its own."""
    folder = tmp_path / "image_pipeline"
    shutil.copytree(IMAGE_PIPELINE.parent, folder)
    shrink_images(folder / IMAGE_PIPELINE.name)
    return folder / IMAGE_PIPELINE.name


def test_the_papers_hls_image_pipeline_passes_the_checks_of_the_logic(small_pipeline):
    # every stage's function against its ports, the rule of the last stream, the block RAM
    result = run_rfc("check", small_pipeline, cwd=ROOT)
    assert result.returncode == 0, result.stderr


def test_the_papers_hls_image_pipeline_builds_into_logic_and_scripts_that_hold(
    tmp_path, small_pipeline
):
    out = tmp_path / "build"
    result = run_rfc("build", small_pipeline, "-o", out, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    cells = check_vivado(run_script(out / "vivado/build.tcl", tmp_path / "vivado.log"))
    # each stage: the Vitis core and rfc's ap_ctrl_hs wrapper around it
    for block in ("gray_acc", "downscale_acc", "integral_acc"):
        assert {f"{block}_core", f"{block}_control"} <= cells.keys()
    for stage, source in [("RgbToGray", "rgb_to_gray.cpp"), ("Downscale", "downscale.cpp")]:
        hls = run_script(out / "hls" / stage / "run.tcl", tmp_path / f"{stage}.log")
        assert hls.of("set_top") == [[[stage]]]
        (added,) = hls.of("add_files")
        assert Path(added[0][0]).name == source
        # the structs become <arg>_<member> ports, as rfc's wrapper names them
        assert [stage] in [names[0] for names in hls.of("set_directive_disaggregate")]


@pytest.mark.parametrize(("width", "beats"), [(8, 16), (64, 2)])
def test_the_wrapper_holds_frame_id_whole_at_the_projects_maxima(width, beats):
    design = compile_spec(str(SPEC))
    block = next(b for b in design.blocks if b.name == "Gray_acc")
    limits = design.project.maxima
    # maxima.string is 16 characters: as many bytes, in beats of the bus with their tkeep bits
    (port, held), *others = input_holds(block, width, limits)
    assert (others, port, held.path) == ([], "rgb", "header.frame_id")
    assert (held.words, held.bits) == (beats, width + width // 8)
