"""Products of one operator with many vectors, each rounded as it is alone.

A grid line applies the same row operators to all its solutions.  One matrix product
``X @ M.T`` would sum each entry in an order that depends on how many rows ``X`` has
(the BLAS blocks its loops by the sizes), so a point would get other numbers in a line
than alone.  A stack of matrix-vector products does not: each is the product it would
be alone, whatever the stack's length.
"""

from __future__ import annotations

import numpy as np

__all__ = ["stacked"]


def stacked(M, x):
    """``M @ x[j]`` for each row ``x[j]`` of ``x`` (m, n), as rows: shape (m, k).

    Parameters
    ----------
    M : ndarray, shape (k, n)
    x : array_like, shape (m, n)

    Returns
    -------
    ndarray, shape (m, k)
    """
    return np.matmul(M, np.asarray(x, dtype=float)[:, :, None])[:, :, 0]
