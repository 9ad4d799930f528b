"""SimulationResult's case selection and concatenation: one batch cut and put back together
gives the batch, bit for bit."""

import numpy as np
import pytest

import landing
from landing.errors import ParameterError, ParameterTypeError


def _same(a: np.ndarray, b: np.ndarray) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


def _same_result(a: landing.SimulationResult, b: landing.SimulationResult) -> None:
    assert _same(a.t, b.t) and _same(a.final_state, b.final_state)
    for name in ("states", "controls"):
        x, y = getattr(a, name), getattr(b, name)
        assert (x is None) == (y is None), name
        if x is not None:
            assert _same(x, y), name
    assert list(a.diagnostics) == list(b.diagnostics)
    assert all(_same(a.diagnostics[k], b.diagnostics[k]) for k in a.diagnostics)
    assert list(a.metrics) == list(b.metrics)
    assert all(_same(a.metrics[k], b.metrics[k]) for k in a.metrics), "metrics"
    assert (a.state_names, a.control_names, a.kernel) == (b.state_names, b.control_names, b.kernel)


@pytest.fixture(scope="module")
def batch() -> landing.SimulationResult:
    s = landing.scenarios.mars_monte_carlo(t_final=0.2, dt=1e-2, record_every=2)
    return s.simulate_batch(s.initial_states(7, seed=4), seed=4)


def test_a_range_of_cases_is_a_view_and_equals_the_cases_run_alone(batch):
    part = batch.cases(2, 5)
    assert part.n_cases == 3 and np.shares_memory(part.states, batch.states)
    s = landing.scenarios.mars_monte_carlo(t_final=0.2, dt=1e-2, record_every=2)
    alone = s.simulate_batch(s.initial_states(7, seed=4)[2:5], seed=4, first_case=2)
    _same_result(part, alone)
    # the metrics know the part's initial states for to_pandas
    assert np.array_equal(part.metrics.__dict__["_context"]["x0"], batch.states[2:5, 0, :])


def test_an_index_array_or_a_mask_selects_cases(batch):
    picked = batch.cases([6, 0, 3])
    assert _same(picked.final_state, batch.final_state[[6, 0, 3]])
    assert _same(picked.metrics["fuel_used"], batch.metrics["fuel_used"][[6, 0, 3]])
    mask = np.zeros(7, dtype=bool)
    mask[[1, 4]] = True
    _same_result(batch.cases(mask), batch.cases([1, 4]))
    assert batch.cases([]).n_cases == 0
    with pytest.raises(ParameterTypeError, match="cases takes"):
        batch.cases(1.5)
    with pytest.raises(TypeError, match="single case"):
        batch[0].cases(0, 1)


def test_one_case_drops_the_case_axis(batch):
    one = batch[3]
    assert one.states.shape == batch.states.shape[1:] and one.n_cases == 1
    assert one.metrics["fuel_used"] == batch.metrics["fuel_used"][3]


def test_concat_of_the_parts_is_the_batch(batch):
    _same_result(landing.SimulationResult.concat([batch.cases(0, 3), batch.cases(3, 4), batch.cases(4, 7)]), batch)
    with pytest.raises(ParameterError, match="part 1 differs"):
        landing.SimulationResult.concat([batch, batch.keeping(("states",))])
    with pytest.raises(ParameterTypeError, match="non-empty"):
        landing.SimulationResult.concat([])


def test_an_output_allocated_once_is_filled_in_any_order(batch):
    out = landing.SimulationResult.empty(7, like=batch.keeping(("controls",)))
    assert out.states is None and out.diagnostics == {} and out.controls.shape == batch.controls.shape
    for start, stop in ((4, 7), (0, 2), (2, 4)):
        out.put(start, batch.cases(start, stop))
    _same_result(out, batch.keeping(("controls",)))
    with pytest.raises(ParameterError, match="beyond"):
        out.put(6, batch.cases(0, 2))
    with pytest.raises(ParameterError, match="lacks controls"):
        out.put(0, batch.keeping(()).cases(0, 1))


def test_keeping_drops_the_signals_not_named(batch):
    kept = batch.keeping(("diagnostics",))
    assert kept.states is None and kept.controls is None and list(kept.diagnostics) == list(batch.diagnostics)
    assert kept.final_state is batch.final_state


def test_metrics_cases(batch):
    m = batch.metrics.cases(1, 3)
    assert isinstance(m, landing.Metrics) and list(m) == list(batch.metrics)
    assert _same(m["final_error"], batch.metrics["final_error"][1:3])


def test_metric_units_put_in_the_plants_coordinate_and_command_units():
    from landing.results import metric_units

    mars = metric_units(("rx", "ry", "rz", "vx", "vy", "vz", "m"), ("Fx", "Fy", "Fz"), 3)
    assert mars["final_error"] == "m" and mars["touchdown_velocity"] == "m/s" and mars["peak_command"] == "N"
    assert mars["iae"] == "m s" and mars["fuel_used"] == "kg" and "diverged" not in mars
    tether = metric_units(("phi", "theta", "phi_dot", "theta_dot"), ("thrust", "torque"), 2)
    assert tether["final_error"] == "rad" and tether["final_velocity_error"] == "rad/s"
    # thrust in N and torque in N m: the command's metrics have no one unit
    assert "peak_command" not in tether and "chattering_variation" not in tether
    assert tether["chattering_hf_share"] == "1" and tether["settle_time"] == "s"


def test_results_print_a_short_summary_not_their_arrays(tmp_path):
    # print(res) and print(mc) as xarray and pandas print: sizes, names, the metric table; the
    # length does not grow with the cases
    s = landing.scenarios.preset("mars_monte_carlo").replace(t_final=1.0)
    many = s.simulate_batch(s.initial_states(500, seed=1), record_every=10)
    text = repr(many)
    assert "array(" not in text and len(text.splitlines()) < 40
    assert text.startswith("<landing.SimulationResult: 500 cases, 101 instants recorded, 0 .. 1 s, every 0.01 s")
    assert "states       (500x101x7) rx ry rz vx vy vz m" in text and "diverged               0 of 500" in text
    assert repr(many[3]).startswith("<landing.SimulationResult: one case")
    mc = landing.monte_carlo(s, 50, seed=2, progress=False)
    text = str(mc)
    assert "array(" not in text and len(text.splitlines()) < 20
    assert text.splitlines()[0] == "<landing.MonteCarloResult: mars_monte_carlo, 50 cases, seed 2>"
    assert "dispersed: initial states" in text and "final_position_error" in text
