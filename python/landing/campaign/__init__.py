"""Monte Carlo campaigns: :func:`monte_carlo` runs one (in this process or on a Dask cluster,
into a store or not), :func:`load` reads a stored one back, bit for bit.

:mod:`landing.campaign.store` is the store's directory layout, :mod:`landing.campaign.dask`
the cluster runner (docs/cluster.md), :mod:`landing.campaign.verify` the verification of a
requirement with a confidence (:meth:`MonteCarloResult.verify`, :func:`samples_needed`),
:mod:`landing.campaign.sensitivity` what drives the metrics (:meth:`MonteCarloResult.sensitivity`,
:func:`sobol`).
"""

from landing.campaign.api import load, monte_carlo
from landing.campaign.result import Bands, MonteCarloResult, Summary
from landing.campaign.sensitivity import RankCorrelations, SobolIndices, sobol
from landing.campaign.verify import Verification, samples_needed

__all__ = ["Bands", "MonteCarloResult", "RankCorrelations", "SobolIndices", "Summary", "Verification", "load",
           "monte_carlo", "samples_needed", "sobol"]
