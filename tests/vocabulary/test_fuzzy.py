"""The Mamdani engine against scikit-fuzzy (an independent implementation).

Both take the centroid of the aggregated membership, linear between samples of the output
universe. scikit-fuzzy also inserts the points where each rule's cut crosses its set; the core
keeps the fixed grid, so the two agree to O(h^2) in the grid step h, which the tests check."""

import numpy as np
import pytest

from landing.fuzzy import SET_NAMES_5, SET_NAMES_7, Mamdani, Variable, variable_rate_system

skfuzzy = pytest.importorskip("skfuzzy")

pytestmark = pytest.mark.fuzzy_reference
from skfuzzy import control as ctrl  # noqa: E402


def skfuzzy_system(system: Mamdani):
    """Rebuild a landing Mamdani system in scikit-fuzzy's control API."""
    def universe(v, n):
        return np.linspace(v.universe[0], v.universe[1], n)

    ants = []
    for i, v in enumerate(system.inputs):
        a = ctrl.Antecedent(universe(v, 1001), f"in{i}")
        for name, spec in v.sets.items():
            shape = skfuzzy.trimf if spec[0] == "triangle" else skfuzzy.trapmf
            a[name] = shape(a.universe, list(spec[1:]))
        ants.append(a)
    out = ctrl.Consequent(universe(system.output, system.resolution), "out", defuzzify_method="centroid")
    for name, spec in system.output.sets.items():
        shape = skfuzzy.trimf if spec[0] == "triangle" else skfuzzy.trapmf
        out[name] = shape(out.universe, list(spec[1:]))
    rules = []
    for antecedent, consequent in system.rules:
        term = ants[0][antecedent[0]]
        for a, name in zip(ants[1:], antecedent[1:]):
            term = term & a[name]
        rules.append(ctrl.Rule(term, out[consequent]))
    return ctrl.ControlSystemSimulation(ctrl.ControlSystem(rules))


def compare(system: Mamdani, points: np.ndarray) -> float:
    sim = skfuzzy_system(system)
    theirs = []
    for p in points:
        for i, v in enumerate(p):
            sim.input[f"in{i}"] = v
        sim.compute()
        theirs.append(sim.output["out"])
    return float(np.abs(system.evaluate(points) - np.array(theirs)).max())


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
@pytest.mark.slow
def test_the_seed_system_matches_scikit_fuzzy_on_a_grid():
    grid = np.array([(s, ds) for s in np.linspace(-5, 5, 21) for ds in np.linspace(-5, 5, 21)])
    assert compare(variable_rate_system(resolution=801), grid) < 2e-5
    assert np.ptp(variable_rate_system().evaluate(grid)) > 6  # the grid spans the output range


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_the_difference_is_the_sampling_and_vanishes_as_h_squared():
    grid = np.array([(s, ds) for s in np.linspace(-5, 5, 6) for ds in np.linspace(-4.5, 4.5, 5)])
    coarse = compare(variable_rate_system(resolution=201), grid)
    fine = compare(variable_rate_system(resolution=801), grid)
    assert 12 < coarse / fine < 20, (coarse, fine)


@pytest.mark.filterwarnings("ignore::DeprecationWarning")
def test_a_general_system_with_trapezoids_matches_scikit_fuzzy():
    temp = Variable((0, 40), {"cold": ("trapezoid", 0, 0, 10, 20), "warm": ("triangle", 10, 20, 30),
                              "hot": ("trapezoid", 20, 30, 40, 40)})
    hum = Variable((0, 100), {"dry": ("triangle", 0, 0, 60), "wet": ("triangle", 40, 100, 100)})
    fan = Variable((0, 10), {"low": ("triangle", 0, 0, 5), "mid": ("triangle", 2, 5, 8),
                             "high": ("triangle", 5, 10, 10)})
    rules = [(("cold", "dry"), "low"), (("cold", "wet"), "low"), (("warm", "dry"), "mid"),
             (("warm", "wet"), "high"), (("hot", "dry"), "high"), (("hot", "wet"), "high")]
    system = Mamdani([temp, hum], fan, rules, resolution=1001)
    rng = np.random.default_rng(0)
    pts = np.column_stack([rng.uniform(0, 40, 200), rng.uniform(0, 100, 200)])
    assert compare(system, pts) < 1e-4


def test_the_seed_rule_table():
    """Table 1 of seed 002, read back from the core's system."""
    system = variable_rate_system()
    table = {antecedent: c for antecedent, c in system.rules}
    printed = [["NB", "NM", "NM", "PS", "ZR"], ["NM", "NS", "NS", "ZR", "PM"], ["NS", "NS", "ZR", "PS", "PS"],
               ["PM", "ZR", "PS", "PM", "PM"], ["ZR", "PM", "PM", "PM", "PB"]]
    for i, s in enumerate(SET_NAMES_5):
        for j, ds in enumerate(SET_NAMES_5):
            assert table[(s, ds)] == printed[i][j]
    assert list(system.output.sets) == list(SET_NAMES_7)
    assert system.inputs[0].universe == (-5.0, 5.0) and system.output.universe == (-4.0, 4.0)


def test_inputs_are_clipped_to_the_universe():
    system = variable_rate_system()
    np.testing.assert_array_equal(system.evaluate([[50.0, -80.0]]), system.evaluate([[5.0, -5.0]]))


def test_bad_systems_are_refused():
    v = Variable((-1, 1), {"a": ("triangle", -1, 0, 1)})
    with pytest.raises(ValueError, match="no fuzzy set 'b'"):
        Mamdani([v], v, [(("b",), "a")])
    with pytest.raises(ValueError, match="corners in non-decreasing order"):
        Mamdani([Variable((-1, 1), {"a": ("triangle", 1, 0, -1)})], v, [(("a",), "a")])
    with pytest.raises(ValueError, match="rule names 2 input sets for 1 inputs"):
        Mamdani([v], v, [(("a", "a"), "a")])
    with pytest.raises(ValueError, match=r"inputs has shape"):
        variable_rate_system().evaluate([[1.0, 2.0, 3.0]][0])
