"""README.md: every Python block runs on its own as a file (a reader copies one, not the page),
and every figure of its gallery is in the repository."""

from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest

from _cases import ROOT

README = (ROOT / "README.md").read_text(encoding="utf-8")
BLOCKS = re.findall(r"```python\n(.*?)```", README, re.S)


def test_the_readme_has_python_blocks_and_a_gallery():
    assert len(BLOCKS) >= 2
    images = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", README)
    assert len(images) >= 4
    for image in images:
        assert (ROOT / image).is_file(), f"README shows {image}, which is not in the repository"


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_each_readme_block_runs_as_a_file(index, tmp_path):
    script = tmp_path / "block.py"
    script.write_text(BLOCKS[index], encoding="utf-8")
    done = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True, text=True,
                          env=dict(os.environ, MPLBACKEND="Agg"), timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
