"""Shared fixtures: the default plan (the paper's experiment) is made once per session; the
other tests plan a small scenario, three AUVs over a short window, in a fraction of a second."""

import pytest

import shoal

# Three AUVs, six steps of 100 s: a small window that plans quickly.
SMALL = {"team": {"auvs": 3}, "horizon": {"steps": 6}}


@pytest.fixture(scope="session")
def default_plan():
    return shoal.plan("default")


@pytest.fixture(scope="session")
def small_plan():
    return shoal.plan(SMALL)


def sloped_floor(spacing=50.0, half=6000.0):
    """A floor sloping east from −140 m to −100 m over the synthetic floor's extent, and its
    lattice."""
    import numpy as np

    x = np.arange(-half, half + spacing / 2, spacing)
    y = np.arange(-half, half + spacing / 2, spacing)
    xx, yy = np.meshgrid(x, y)  # rows along y (south first), columns along x
    z = -120.0 + 20.0 * xx / half + 0.0 * yy
    return z, {"x0": float(x[0]), "y0": float(y[0]), "dx": spacing}
