"""Shared fixtures: where the test volumes and the CLI are (set by tests/python/CMakeLists.txt)."""
import os
import pathlib

import numpy as np
import pytest

DATA = pathlib.Path(os.environ.get("ISODEL_TEST_DATA", pathlib.Path(__file__).parent.parent / "data"))


@pytest.fixture
def data():
    return DATA


@pytest.fixture
def cli():
    path = os.environ.get("ISODEL_CLI", "")
    if not path or not os.path.exists(path):
        pytest.skip("ISODEL_CLI does not name the built isodel command line")
    return path


def blobs(shape=(20, 24, 28)):
    """A smooth field with two bumps of different sizes, not symmetric in any axis, so a swapped
    axis order would give a different mesh."""
    z, y, x = np.meshgrid(*[np.arange(n, dtype=np.float64) for n in shape], indexing="ij")
    a = np.exp(-((x - 9) ** 2 + (y - 10) ** 2 + (z - 8) ** 2) / 18.0)
    b = np.exp(-((x - 19) ** 2 + (y - 14) ** 2 + (z - 11) ** 2) / 10.0)
    return (a + 0.8 * b).astype(np.float32)
