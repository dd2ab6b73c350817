"""The scripts of examples/python run and write their output."""

import os
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_sweep_plot_writes_png(tmp_path):
    pytest.importorskip("matplotlib")
    out = tmp_path / "sweep.png"
    subprocess.run([sys.executable, str(ROOT / "examples" / "python" / "sweep_plot.py"), "--out", str(out)],
                   check=True, env=dict(os.environ), stdout=subprocess.DEVNULL)
    data = out.read_bytes()
    assert data.startswith(b"\x89PNG\r\n\x1a\n") and len(data) > 10000
