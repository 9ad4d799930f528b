"""An optional extra whose import is interrupted (Ctrl-C during ``import cma``) can be imported
again: the half-initialised modules are forgotten."""

from __future__ import annotations

import sys

import pytest

from landing._internal.extras import import_extra


def test_an_interrupted_import_leaves_the_module_importable(tmp_path, monkeypatch):
    pkg = tmp_path / "slow_extra"
    pkg.mkdir()
    (pkg / "__init__.py").write_text(
        "from slow_extra import part\n"
        "import pathlib\n"
        "flag = pathlib.Path(__file__).with_name('interrupt')\n"
        "if flag.exists():\n"
        "    flag.unlink()\n"
        "    raise KeyboardInterrupt\n"
        "READY = True\n")
    (pkg / "part.py").write_text("VALUE = 1\n")
    (pkg / "interrupt").write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    with pytest.raises(KeyboardInterrupt):
        import_extra("slow_extra", "pip install slow_extra")
    assert "slow_extra" not in sys.modules and "slow_extra.part" not in sys.modules
    module = import_extra("slow_extra", "pip install slow_extra")
    assert module.READY and module.part.VALUE == 1
    with pytest.raises(ImportError, match="pip install nothing_here"):
        import_extra("no_such_extra_module", "pip install nothing_here")
