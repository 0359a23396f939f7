"""The franka_fk example's modules loaded from their files, and robot states to feed them."""

from __future__ import annotations

import importlib.util
import sys
from functools import cache
from types import ModuleType

import numpy as np

from rfc.lib.fixed import bits_to_float, float_to_bits
from tests.conftest import ROOT

FOLDER = ROOT / "examples" / "franka_fk"


@cache
def load(name: str) -> ModuleType:
    """examples/franka_fk/<name>.py as a module (examples are projects, not packages)."""
    spec = importlib.util.spec_from_file_location(f"franka_fk_{name}", FOLDER / f"{name}.py")
    assert spec is not None
    assert spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module
    spec.loader.exec_module(module)
    return module


def states(count: int, seed: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Random states within the Panda's joint limits, as franka_ros would publish them.

    F_T_EE is a random rigid transform (rotation about z, offset up to 0.2 m, like a hand);
    O_T_EE is the true end-effector pose perturbed by up to a millimetre.
    """
    reference = load("reference")
    rng = np.random.default_rng(seed)
    q = rng.uniform(reference.Q_MIN, reference.Q_MAX, (count, 7))
    turn = rng.uniform(-np.pi, np.pi, count)
    hand = np.zeros((count, 4, 4))
    hand[:, 0, 0] = hand[:, 1, 1] = np.cos(turn)
    hand[:, 0, 1], hand[:, 1, 0] = -np.sin(turn), np.sin(turn)
    hand[:, 2, 2] = hand[:, 3, 3] = 1.0
    hand[:, :3, 3] = rng.uniform(-0.2, 0.2, (count, 3))
    f_t_ee = reference.column_major(hand)
    frames = reference.joint_transforms(q)
    flange = np.eye(4)
    flange[2, 3] = reference.FLANGE
    end = frames[:, 6] @ flange @ hand
    end[:, :3, :] += rng.uniform(-1e-3, 1e-3, (count, 3, 4))
    return q, f_t_ee, reference.column_major(end)


to_bits = np.vectorize(float_to_bits, otypes=[object])
to_float = np.vectorize(bits_to_float, otypes=[float])
