"""An HLS core taking FrankaState as one struct, in the logic, simulated in GHDL.

Vitis HLS is not here, so a stand-in of the core Vitis HLS would export for
``hls_fold/fold.cpp`` takes its place: the ports the struct is disaggregated into
(``<argument>_<member>``, one per array element), ``ap_ctrl_hs`` (``ap_start`` sampled when
idle, ``ap_done``/``ap_ready`` for one cycle), inputs read over 16 cycles and outputs written
with one-cycle ``_ap_vld`` at different times, as UG1399 describes the protocol. The bytes
the system publishes must be the C function's, computed here with NumPy from rosbags' messages,
and the function's own C simulation (`rfc sim`) must agree.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from rfc.messages.codec import default_values
from rfc.messages.layout import flatten
from rfc.messages.rosbags_adapter import message_types, write_bag
from rfc.messages.values import values_to_message
from tests.lower.system.hls_cores import (
    built_with_vitis_run,
    c_simulated,
    replay_with_stand_in,
)
from tests.support.cli import run_rfc
from tests.support.vendor_check import check_vivado, run_script

ROOT = Path(__file__).resolve().parents[3]
SPEC = Path(__file__).parent / "hls_fold" / "fold.yaml"
FRANKA = "franka_msgs/msg/FrankaState"
POINT = "geometry_msgs/msg/PointStamped"
#: The arrays the function folds, with the rotation of their first element, per output.
FOLDS = {
    "x": {"q": (7, 0)},
    "y": {"q_d": (7, 0)},
    "z": {"O_T_EE": (16, 0), "O_T_EE_d": (16, 16), "F_T_EE": (16, 32)},
}


def stand_in() -> str:
    """VHDL of the core Vitis HLS would make of ``Fold``, with its disaggregated ports."""
    arrays = {name: size for fold in FOLDS.values() for name, (size, _) in fold.items()}
    inputs = [
        f"state_header_stamp_{s} : in std_logic_vector(31 downto 0);" for s in ("sec", "nanosec")
    ]
    inputs += [
        f"state_{name}_{i} : in std_logic_vector(63 downto 0);"
        for name, size in arrays.items()
        for i in range(size)
    ]
    outputs = [
        f"folded_{member} : out std_logic_vector({bits - 1} downto 0) := (others => '0');\n"
        f"    folded_{member}_ap_vld : out std_logic := '0';"
        for member, bits in [("header_stamp_sec", 32), ("header_stamp_nanosec", 32)]
    ]
    outputs += [
        f"folded_point_{axis} : out std_logic_vector(63 downto 0);\n"
        f"    folded_point_{axis}_ap_vld : out std_logic;"
        for axis in "xyz"
    ]
    words = "\n".join(
        f"  {name.lower()}({i}) <= unsigned(state_{name}_{i});"
        for name, size in arrays.items()
        for i in range(size)
    )
    signals = "\n".join(
        f"  signal {name.lower()} : words(0 to {size - 1});" for name, size in arrays.items()
    )
    steps = []
    for output, fold in FOLDS.items():
        for name, (size, shift) in fold.items():
            steps.append(
                f"        if step < {size} then\n"
                f"          acc_{output} := acc_{output} xor "
                f"rotate_left({name.lower()}(step), {shift} + step);\n"
                "        end if;"
            )
    return f"""library ieee;
use ieee.std_logic_1164.all;
use ieee.numeric_std.all;

entity Fold is
  port (
    ap_clk : in std_logic;
    ap_rst : in std_logic;
    ap_start : in std_logic;
    ap_done : out std_logic;
    ap_idle : out std_logic;
    ap_ready : out std_logic;
    {chr(10).join("    " + line for line in inputs).strip()}
    {chr(10).join("    " + line for line in outputs).strip().rstrip(";")}
  );
end entity;

architecture stand_in of Fold is
  type words is array (natural range <>) of unsigned(63 downto 0);
{signals}
  signal busy : std_logic := '0';
  signal last : std_logic;
  signal step : natural range 0 to 31 := 0;
  signal folds : words(0 to 2) := (others => (others => '0'));
begin
{words}
  ap_idle <= not busy;
  -- as Vitis HLS's state machines do: done, ready and the last writes during the last state
  last <= '1' when busy = '1' and step = 16 else '0';
  ap_done <= last;
  ap_ready <= last;
  folded_point_x <= std_logic_vector(folds(0));
  folded_point_y <= std_logic_vector(folds(1));
  folded_point_z <= std_logic_vector(folds(2));
  folded_point_x_ap_vld <= last;
  folded_point_y_ap_vld <= last;
  folded_point_z_ap_vld <= last;

  run : process (ap_clk)
    variable acc_x, acc_y, acc_z : unsigned(63 downto 0);
  begin
    if rising_edge(ap_clk) then
      folded_header_stamp_sec_ap_vld <= '0';
      folded_header_stamp_nanosec_ap_vld <= '0';
      if ap_rst = '1' then
        busy <= '0';
      elsif busy = '0' then
        if ap_start = '1' then
          busy <= '1';
          step <= 0;
          folds <= (others => (others => '0'));
        end if;
      else
        step <= step + 1;
        acc_x := folds(0);
        acc_y := folds(1);
        acc_z := folds(2);
{chr(10).join(steps)}
        folds <= (acc_x, acc_y, acc_z);
        if step = 0 then
          folded_header_stamp_sec <= state_header_stamp_sec;
          folded_header_stamp_sec_ap_vld <= '1';
        elsif step = 9 then
          folded_header_stamp_nanosec <= state_header_stamp_nanosec;
          folded_header_stamp_nanosec_ap_vld <= '1';
        elsif step = 16 then
          busy <= '0';
        end if;
      end if;
    end if;
  end process;
end architecture;
"""


def franka_bag(path: Path, count: int) -> list[dict[str, np.ndarray]]:
    """A ROS 1 bag of FrankaState messages with random arrays; returns the arrays."""
    types = message_types("ros1", msg_paths=(str(ROOT / "examples/franka/msg"),))
    layout = flatten(types, FRANKA)
    rng = np.random.default_rng(5)
    states, data = [], []
    for index in range(count):
        values = default_values(layout)
        values.update({"header.stamp.sec": 100 + index, "header.stamp.nanosec": 7 * index})
        state = {
            name: rng.normal(scale=10.0 ** (index - 1), size=size)
            for fold in FOLDS.values()
            for name, (size, _) in fold.items()
        }
        for name, array in state.items():
            values.update({f"{name}[{i}]": float(v) for i, v in enumerate(array)})
        states.append(state)
        data.append(types.serialize(values_to_message(values, layout, types), FRANKA))
    write_bag(
        path,
        types,
        {"/franka_state": FRANKA},
        [("/franka_state", i + 1, d) for i, d in enumerate(data)],
    )
    return states


def expected_point(state: dict[str, np.ndarray]) -> bytes:
    """The function's three words, in NumPy: each element's bits rotated, exclusive-ored."""
    words = []
    for fold in FOLDS.values():
        word = np.uint64(0)
        for name, (_, shift) in fold.items():
            for i, bits in enumerate(state[name].astype("<f8").view("<u8")):
                turn = np.uint64(shift + i)
                rotated = (bits << turn) | (bits >> np.uint64(64) - turn) if shift + i else bits
                word ^= rotated
        words.append(word)
    return np.array(words, dtype="<u8").tobytes()


def test_an_hls_core_taking_franka_state_as_a_struct_runs_in_the_logic(tmp_path):
    states = franka_bag(tmp_path / "in.bag", 3)
    published = replay_with_stand_in(
        SPEC, stand_in(), tmp_path / "in.bag", "/franka_state", tmp_path
    )
    types = message_types("ros1")
    assert [p.topic for p in published] == ["/folded"] * len(states)
    for index, (state, sent) in enumerate(zip(states, published, strict=True)):
        message = types.deserialize(sent.data, POINT)
        assert (message.header.stamp.sec, message.header.stamp.nanosec) == (100 + index, 7 * index)
        assert message.header.frame_id == ""
        assert sent.data[-24:] == expected_point(state)
    # the function itself, C-simulated by `rfc sim`, gives the same messages
    assert c_simulated(SPEC, tmp_path / "in.bag", types, tmp_path) == [p.data for p in published]


def test_the_vitis_run_disaggregates_the_structs_and_partitions_their_arrays(tmp_path):
    out, hls = built_with_vitis_run(SPEC, "Fold", tmp_path)
    assert hls.of("set_directive_disaggregate") == [[["Fold"], ["state"]], [["Fold"], ["folded"]]]
    partitioned = [args[-1][0] for args in hls.of("set_directive_array_partition")]
    assert partitioned == [f"state.{a}" for a in ("q", "q_d", "O_T_EE", "O_T_EE_d", "F_T_EE")]
    assert [args[-2:] for args in hls.of("set_directive_interface")] == [
        [["Fold"], ["return"]],
        [["Fold"], ["state"]],
        [["Fold"], ["folded"]],
    ]
    (source,) = hls.of("add_files")
    assert Path(source[0][0]).read_text() == (SPEC.parent / "fold.cpp").read_text()
    cells = check_vivado(run_script(out / "vivado/build.tcl", tmp_path / "vivado.log"))
    core = next(ports for ports in cells.values() if "ap_start" in ports and "state_q_0" in ports)
    assert {"state_F_T_EE_15", "folded_point_z", "folded_point_z_ap_vld"} <= set(core)


def refused(tmp_path: Path, cpp: str, spec: Path = SPEC) -> str:
    """The error of `rfc build` on a copy of `spec` whose C++ source is `cpp`.

    `rfc check` must refuse it first, with the same error.
    """
    folder = tmp_path / "spec"
    folder.mkdir()
    text = spec.read_text().replace("../../../../examples", str(ROOT / "examples"))
    (folder / spec.name).write_text(text)
    source = "sums.cpp" if "sums" in spec.name else "fold.cpp"
    (folder / source).write_text(cpp)
    checked = run_rfc("check", folder / spec.name, cwd=ROOT)
    result = run_rfc("build", folder / spec.name, "-o", tmp_path / "b", cwd=ROOT)
    for run in (checked, result):
        assert run.returncode == 1
        assert "Traceback" not in run.stderr
    assert checked.stderr == result.stderr
    assert not (tmp_path / "b").exists()
    return result.stderr


def test_a_struct_of_another_port_is_refused_at_the_argument(tmp_path):
    cpp = '#include "Fold_messages.h"\n\nvoid Fold(folded_t state, folded_t *folded) {}\n'
    message = refused(tmp_path, cpp)
    assert "fold.cpp:3:11:" in message
    assert "argument 'state' of HLS top function Fold is a folded_t; expected state_t state" in (
        message
    )


def test_an_input_struct_by_pointer_is_refused_at_the_argument(tmp_path):
    cpp = '#include "Fold_messages.h"\n\nvoid Fold(state_t *state, folded_t *folded) {}\n'
    message = refused(tmp_path, cpp)
    assert "argument 'state' of HLS top function Fold is a pointer to state_t" in message


def test_structs_mixed_with_scalars_are_refused_naming_the_arguments_needed(tmp_path):
    cpp = '#include "Fold_messages.h"\n\nvoid Fold(state_t state, double *x) {}\n'
    message = refused(tmp_path, cpp)
    assert "fold.cpp:3:11:" in message
    assert "has 2 arguments; taking structs, it needs 2: state_t state, folded_t *folded" in (
        message
    )


def test_an_input_stream_before_a_field_the_core_reads_is_refused(tmp_path):
    # header.frame_id comes before q: the core would start before the subscriber has q
    sums = ROOT / "tests/runtime/systems/franka_hls/sums.yaml"
    message = refused(tmp_path, (sums.parent / "sums.cpp").read_text(), sums)
    assert "sums.yaml:" in message
    assert (
        "port 'state' selects 'q[0]' after its last string or sequence 'header.frame_id'" in message
    )
    assert "exclude 'q' or 'header.frame_id' from port 'state'" in message
