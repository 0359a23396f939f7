"""Compare the Euler angles of `rfc sim` with the references: exact and within tolerance.

    python compare.py orientations.mcap euler.mcap [--iterative]

The angles must equal the accelerator's bit-accurate Python reference exactly (the pipelined
core of project.yaml, or with --iterative the core of project_iterative.yaml), and be within
1e-9 rad of NumPy's double-precision angles (1e-5 rad when pitch is within 1e-3 rad of ±π/2,
where the formulas lose precision in any arithmetic; at exact gimbal lock only pitch is
defined). Exit status 1 when they are not.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np
from quat_to_euler import ITERATIVE, PIPELINED, numpy_reference, reference

from rfc.lib.fixed import bits_to_float, float_to_bits
from rfc.messages.rosbags_adapter import message_types, read_bag


def rows(bag: str, fields: str) -> np.ndarray:
    """The named fields of every message of a ROS 2 bag, one row each."""
    types = message_types("ros2")
    messages = [types.deserialize(m.data, m.type_name) for m in read_bag(bag, types)]
    return np.array([[getattr(m, f) for f in fields] for m in messages], dtype=np.float64)


def main() -> int:
    """Print the comparison; return the exit status."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("orientations", help="the bag replayed")
    parser.add_argument("euler", help="the bag rfc sim wrote")
    parser.add_argument("--iterative", action="store_true", help="the iterative core's results")
    args = parser.parse_args()
    precision = ITERATIVE if args.iterative else PIPELINED
    quaternions, euler = rows(args.orientations, "xyzw"), rows(args.euler, "xyz")
    if len(quaternions) != len(euler):
        print(f"{len(quaternions)} orientations in, {len(euler)} angles out")
        return 1
    exact = np.array(
        [
            [bits_to_float(b) for b in reference(*map(float_to_bits, q), precision)]
            for q in quaternions
        ]
    )
    same = np.array_equal(exact.view(np.uint64), euler.view(np.uint64))
    want = numpy_reference(quaternions)
    error = np.abs(np.remainder(euler - want + np.pi, 2 * np.pi) - np.pi)
    locked = np.abs(want[:, 1]) > np.pi / 2 - 1e-9
    error[locked, 0] = error[locked, 2] = 0.0
    near = np.abs(want[:, 1]) > np.pi / 2 - 1e-3
    within = bool(np.all(error.max(axis=1) <= np.where(near, 1e-5, 1e-9)))
    print(
        f"{len(euler)} orientations: equal to the bit-accurate reference: {same}; "
        f"largest difference to NumPy {error.max():.2e} rad (within tolerance: {within})"
    )
    return 0 if same and within else 1


if __name__ == "__main__":
    sys.exit(main())
