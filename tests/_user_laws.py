"""Laws written in Python for the tests of campaigns, files and the tuner (importable by name,
``_user_laws:pd``, as a scenario file names one)."""

import numpy as np


def pd(t, e, de, ref, drift, inertia, params, memory):
    """A PD law with model cancellation: q'' = -kp e - kd e'."""
    return ref.acceleration - drift - params["kp"] * e - params["kd"] * de


def integral_pd(t, e, de, ref, drift, inertia, params, memory):
    """PD with an integral of the error, the integral advanced by forward Euler over the period."""
    z = memory["z"]
    u = ref.acceleration - drift - params["kp"] * e - params["kd"] * de - params["ki"] * z
    return u, {"z": z + params["dt"] * e}, {"z": z}


def start_at_error(t, e, de, ref, drift, inertia, params):
    """An initial memory computed from the first inputs."""
    return {"z": np.zeros_like(e)}
