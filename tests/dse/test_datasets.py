"""Datasets as docs/dse.md defines them: parameters, seeding, distributions."""

from __future__ import annotations

import numpy as np
import pytest

from rfc.dse.datasets import DATASETS, SIZES, dataset, draw
from rfc.errors import RfcError


def test_the_paper_parameters():
    assert SIZES == (2, 4, 8, 16, 32, 64, 128, 256)
    assert {n: (d.transfer_mean, d.idle_mean, d.sigma) for n, d in DATASETS.items()} == {
        "large": (100, 100, 50),
        "cc1": (20, 20, 10),
        "cc2": (20, 180, 10),
        "cc3": (180, 20, 10),
        "cc4": (180, 180, 10),
    }
    assert DATASETS["large"].cycles == 10_000
    assert DATASETS["large"].replicates == 200
    assert all(DATASETS[f"cc{i}"].cycles == 50_000 for i in range(1, 5))
    assert all(DATASETS[f"cc{i}"].replicates == 10 for i in range(1, 5))


def test_draws_are_seeded_and_replicates_do_not_depend_on_their_count():
    few = draw(DATASETS["cc2"], 16, 3)
    many = draw(DATASETS["cc2"], 16, 8)
    assert np.array_equal(few.transfer, many.transfer[:3])
    assert np.array_equal(few.idle, many.idle[:3])
    assert not np.array_equal(draw(DATASETS["cc2"], 16, 3, seed=1).transfer, few.transfer)
    assert not np.array_equal(draw(DATASETS["cc3"], 16, 3).transfer, few.transfer)


def test_normal_draws_rounded_clipped_and_implicit_deadlines():
    traffic = draw(DATASETS["large"], 256, 40)
    for values, mean in ((traffic.transfer, 100), (traffic.idle, 100)):
        assert values.min() >= 1
        assert abs(values.mean() - mean) < 2
        # clipping at 1 trims the lower tail (2.3 % of draws lie below 1 at sigma 50)
        assert 47 < values.std() < 51
    assert np.array_equal(traffic.deadline, traffic.transfer + traffic.idle)
    assert (traffic.transfer == 1).any()


def test_an_unknown_dataset_suggests_the_closest():
    with pytest.raises(RfcError) as caught:
        dataset("lagre")
    assert "unknown dataset 'lagre'; expected one of large, cc1, cc2, cc3, cc4" in str(caught.value)
    assert "'large'" in str(caught.value.hint)
