"""Shared fixtures of the pytest suite (run by ctest with PYTHONPATH=<build>/python)."""

import os
import shutil

import pytest

import proxima


@pytest.fixture(scope="session")
def cornell():
    """The built-in Cornell box, loaded once per test session."""
    return proxima.load_scene("cornell")


@pytest.fixture(scope="session")
def cli():
    """Path of this build's `proxima` command line (PROXIMA_CLI, set by ctest)."""
    path = os.environ.get("PROXIMA_CLI") or shutil.which("proxima")
    if not path:
        pytest.skip("PROXIMA_CLI not set and no proxima on PATH")
    return path
