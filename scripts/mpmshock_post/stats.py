"""Moments of a distribution of local values, to say how far it is from a Gaussian (paper Fig. 11)."""

import numpy as np


def moments(values):
    """Mean, population standard deviation, skewness and EXCESS kurtosis (0 for a Gaussian) of the
    finite values; skewness and kurtosis are NaN when all values are equal."""
    values = values[np.isfinite(values)]
    if values.size == 0:
        return np.nan, np.nan, np.nan, np.nan
    mean = values.mean()
    deviation = values - mean
    m2 = np.mean(deviation ** 2)
    if m2 == 0.0:
        return mean, 0.0, np.nan, np.nan
    skewness = np.mean(deviation ** 3) / m2 ** 1.5
    excess_kurtosis = np.mean(deviation ** 4) / m2 ** 2 - 3.0
    return mean, np.sqrt(m2), skewness, excess_kurtosis
