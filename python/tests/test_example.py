"""The notebook-style example runs from start to end and draws a real figure."""

import os
import pathlib
import subprocess
import sys

EXAMPLE = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python" / "plan_and_plot.py"


def test_the_example_plans_checks_and_plots(tmp_path):
    png = tmp_path / "plan_and_plot.png"
    env = {**os.environ, "MPLBACKEND": "Agg"}
    run = subprocess.run([sys.executable, str(EXAMPLE), str(png)], cwd=tmp_path, env=env,
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert "check: every constraint holds" in run.stdout, run.stdout
    data = png.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert len(data) > 50_000, len(data)  # a drawn figure, not an empty canvas
