"""The guide's examples run when the site builds: each ``examples/guide/*.py`` is executed in
``_generated/guide/`` (so the figures it writes are there for its page to show); a script that
fails fails the build. Their printed output is in the pages as generated blocks, checked by
``tools/docs_numbers.py``."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path
from typing import Any

from sphinx.errors import ExtensionError


def _run(app: Any) -> None:
    root = Path(app.srcdir).parent
    out = Path(app.srcdir) / "_generated" / "guide"
    out.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, MPLBACKEND="Agg")
    for script in sorted((root / "examples" / "guide").glob("*.py")):
        done = subprocess.run([sys.executable, str(script)], cwd=out, env=env, capture_output=True, text=True)
        if done.returncode != 0:
            raise ExtensionError(f"{script.relative_to(root)} failed:\n{done.stderr[-2000:]}")


def setup(app: Any) -> dict[str, Any]:
    app.connect("builder-inited", _run)
    return {"parallel_read_safe": True}
