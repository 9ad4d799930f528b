"""The package's layers: each module of ``landing`` imports only from its own layer or the
ones below, function-level imports included, with no import circle; the only exceptions are
the optional extras (imported where they are used) and the one-line delegations up, named
here. And ``import landing`` leaves the heavy extras out."""

from __future__ import annotations

import ast
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

import landing

PACKAGE = Path(landing.__file__).resolve().parent

#: The layers, bottom first: a module belongs to the layer of the longest name it starts with.
LAYERS: list[tuple[str, ...]] = [
    ("landing._core", "landing.errors"),
    ("landing._internal",),
    ("landing.plants", "landing.controllers", "landing.gravity", "landing.reference", "landing.disturbances",
     "landing.dispersions", "landing.fuzzy", "landing.sensors"),  # the configuration vocabulary
    ("landing.results",),
    ("landing.simulation",),
    ("landing.optimal",),  # what it imports (the vocabulary, the runs) puts it right above the runs
    ("landing.scenarios",),
    ("landing.theory",),
    ("landing.campaign",),
    ("landing.tuning",),
    ("landing.plots",),
    ("landing.cli", "landing.__main__"),
    ("landing",),  # the package's __init__, which imports the public names of every layer
]

#: What a function may import: the optional extras, and tqdm (heavy to import, a dependency
#: only a progress bar needs); ruff's TID253 keeps them off module level.
EXTRAS = {"cma", "casadi", "distributed", "dask", "cloudpickle", "pyarrow", "zarr", "xarray", "pandas",
          "matplotlib", "SALib", "tqdm"}

#: The one-line delegations up (xarray's Dataset.to_zarr way): (module, function, target).
DELEGATIONS = {
    ("landing.scenarios._scenario", "Scenario.to_toml", "landing.scenarios.files"),
    ("landing.scenarios._scenario", "Scenario.load", "landing.scenarios._presets"),
    ("landing.scenarios._scenario", "Scenario.bounds", "landing.theory.bounds"),
}
#: Imports for annotations only (under TYPE_CHECKING) that go with a delegation's return type.
ANNOTATIONS = {("landing.scenarios._scenario", "landing.theory.bounds")}
#: Imported on demand, downward: the Dask runner, loaded for a cluster campaign only.
ON_DEMAND = {("landing.campaign.api", "monte_carlo", "landing.campaign.dask")}


@dataclass(frozen=True)
class Import:
    module: str  # the importing module
    scope: str  # "" at module level, else the function's qualified name
    target: str  # the imported module (a landing module, or an outside package's top name)
    type_checking: bool
    line: int


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


MODULES = {module_name(p): p for p in PACKAGE.rglob("*.py")}
MODULES["landing._core"] = PACKAGE / "_core.pyi"


def resolve(name: str, names: list[str]) -> list[str]:
    """The modules ``from name import names`` reads (a submodule when a name is one)."""
    if not name.startswith("landing"):
        return [name.split(".")[0]]
    out = [f"{name}.{n}" if f"{name}.{n}" in MODULES else name for n in names]
    return sorted(set(out))


class _Collector(ast.NodeVisitor):
    def __init__(self, module: str) -> None:
        self.module = module
        self.scope: list[str] = []
        self.in_type_checking = False
        self.found: list[Import] = []

    def _add(self, targets: list[str], node: ast.stmt) -> None:
        for t in targets:
            self.found.append(Import(self.module, ".".join(self.scope), t, self.in_type_checking, node.lineno))

    def visit_Import(self, node: ast.Import) -> None:
        self._add([a.name if a.name.startswith("landing") else a.name.split(".")[0] for a in node.names], node)

    def visit_ImportFrom(self, node: ast.ImportFrom) -> None:
        assert node.level == 0, f"{self.module}:{node.lineno}: relative import"
        self._add(resolve(node.module or "", [a.name for a in node.names]), node)

    def _scoped(self, node: ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef) -> None:
        self.scope.append(node.name)
        self.generic_visit(node)
        self.scope.pop()

    visit_FunctionDef = visit_AsyncFunctionDef = visit_ClassDef = _scoped

    def visit_If(self, node: ast.If) -> None:
        if isinstance(node.test, ast.Name) and node.test.id == "TYPE_CHECKING":
            self.in_type_checking = True
            for child in node.body:
                self.visit(child)
            self.in_type_checking = False
            for child in node.orelse:
                self.visit(child)
        else:
            self.generic_visit(node)


def imports() -> list[Import]:
    found: list[Import] = []
    for name, path in MODULES.items():
        if path.suffix == ".py":
            c = _Collector(name)
            c.visit(ast.parse(path.read_text(encoding="utf-8")))
            found += c.found
    return found


def layer(module: str) -> int:
    best, level = -1, None
    for i, prefixes in enumerate(LAYERS):
        for p in prefixes:
            if (module == p or module.startswith(p + ".")) and len(p) > best:
                best, level = len(p), i
    assert level is not None, f"{module} is in no layer"
    return level


def internal(edges: list[Import]) -> list[Import]:
    return [e for e in edges if e.target.startswith("landing") and e.target != e.module]


def is_exception(e: Import) -> bool:
    """A named delegation up, its annotation import, or the on-demand Dask runner."""
    return ((e.module, e.scope, e.target) in DELEGATIONS | ON_DEMAND
            or (e.type_checking and (e.module, e.target) in ANNOTATIONS))


def test_every_module_is_in_a_layer():
    for name in MODULES:
        layer(name)


def test_a_function_imports_only_an_extra_or_a_named_delegation():
    wrong = [e for e in imports() if e.scope and not e.type_checking
             and e.target not in EXTRAS and not is_exception(e)]
    assert not wrong, "function-level imports that are neither an optional extra nor allowed:\n" + "\n".join(
        f"  {e.module}:{e.line} ({e.scope}) imports {e.target}" for e in wrong)


def test_no_module_imports_a_layer_above_its_own():
    up = [e for e in internal(imports()) if layer(e.target) > layer(e.module) and not is_exception(e)]
    assert not up, "imports up the layers:\n" + "\n".join(
        f"  {e.module}:{e.line} imports {e.target} ({LAYERS[layer(e.target)][0]} is above "
        f"{LAYERS[layer(e.module)][0]})" for e in up)


def test_there_is_no_import_circle():
    graph: dict[str, set[str]] = {m: set() for m in MODULES}
    for e in internal(imports()):
        if not is_exception(e):
            graph[e.module].add(e.target)
    # Tarjan's strongly connected components: a circle is a component of two or more modules
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    circles: list[list[str]] = []

    def visit(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                circles.append(sorted(component))

    sys.setrecursionlimit(max(sys.getrecursionlimit(), 10 * len(graph)))
    for v in sorted(graph):
        if v not in index:
            visit(v)
    assert not circles, f"import circles: {circles}"


def test_the_delegations_are_one_line_and_each_is_used():
    found = {(e.module, e.scope, e.target) for e in imports() if (e.module, e.scope, e.target) in DELEGATIONS}
    assert found == DELEGATIONS, f"allowed but not found (remove them from the list): {DELEGATIONS - found}"
    for module, scope, _ in DELEGATIONS:
        tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
        cls_name, fn_name = scope.split(".")
        cls = next(n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == cls_name)
        fn = next(n for n in cls.body if isinstance(n, ast.FunctionDef) and n.name == fn_name)
        body = [s for s in fn.body if not (isinstance(s, ast.Expr) and isinstance(s.value, ast.Constant))]
        assert len(body) == 2 and isinstance(body[0], ast.ImportFrom) and isinstance(body[1], ast.Return), (
            f"{module}.{scope} is not a one-line delegation: an import and a return")
    on_demand = {(e.module, e.scope, e.target) for e in imports()} & ON_DEMAND
    assert on_demand == ON_DEMAND


def test_import_landing_leaves_the_heavy_extras_out():
    code = ("import sys, landing; "
            "print(sorted({m.split('.')[0] for m in sys.modules} & {'matplotlib', 'cma', 'casadi', 'distributed'}))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"
    # and the figures and the optimiser are there on first use
    code = "import landing; print(landing.plots.save_all.__module__, landing.optimal.fuel_optimal.__module__)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.split() == ["landing.plots.standard", "landing.optimal"], out.stderr
