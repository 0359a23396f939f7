"""docs/python-api.md documents every keyword of the Python spec's public calls."""

from __future__ import annotations

import inspect
import re
from pathlib import Path

import pytest

import rfc
from rfc.spec.python_project import Project

DOC = (Path(__file__).resolve().parents[2] / "docs" / "python-api.md").read_text()
CALLS = {
    "rfc.Project": Project.__init__,
    "rfc.accelerator": rfc.accelerator,
    "rfc.external_accelerator": rfc.external_accelerator,
    "rfc.port": rfc.port,
    "Project.accelerator": Project.accelerator,
    "Project.connect": Project.connect,
}
# subscriber/publisher take their timing as **keywords; the front-end lists what it accepts
CONVERTER_KEYWORDS = ("topic", "period", "deadline", "max_bytes")


def _documented(name: str) -> bool:
    return re.search(rf"`{re.escape(name)}`|\b{re.escape(name)}[,=)]", DOC) is not None


@pytest.mark.parametrize("call", sorted(CALLS))
def test_every_parameter_is_documented(call):
    parameters = [
        p.name for p in inspect.signature(CALLS[call]).parameters.values() if p.name != "self"
    ]
    assert call.split(".")[-1] in DOC
    assert [p for p in parameters if not _documented(p)] == []


def test_converter_keywords_are_the_ones_the_front_end_accepts(tmp_path):
    project = Project("Probe")
    with pytest.raises(rfc.errors.RfcError) as refused:
        project.subscriber("s", "geometry_msgs/Point", colour="red")
    for keyword in CONVERTER_KEYWORDS:
        assert keyword in str(refused.value)
        assert _documented(keyword)
