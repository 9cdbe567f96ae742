"""A discrete convolution in time whose input becomes known one step at a time.

``y[n] = sum_{m=1}^{n-1} A[m] x[n - m]`` (the history: lag 0 is the step's own, implicit
part), for channels and independent modes, at ``O(L log^2 L)`` for ``L`` steps instead
of ``O(L^2)`` (Hairer, Lubich and Schlichte, *Fast numerical solution of nonlinear
Volterra convolution equations*, SIAM J. Sci. Stat. Comput. 6, 1985, 532-541).

Each pair ``(i, n)``, ``i < n``, is added exactly once: at the step ``n* = k 2^q``
(``k`` odd), the number in ``(i, n]`` with the most factors 2, where ``i`` lies in
``[n* - 2^q, n*)`` and ``n`` in ``[n*, n* + 2^q)``.  So at the start of step ``n*`` the
inputs ``x[n* - 2^q : n*]`` (all known) are convolved by FFT with the lags
``A[1 : 2^(q+1)]`` into the accumulators of the next ``2^q`` outputs.
"""

from __future__ import annotations

import numpy as np

__all__ = ["OnlineConvolution"]


class OnlineConvolution:
    """``y[n] = sum_{m=1}^{n-1} einsum('oik,ik->ok', A[m], x[n-m])`` as the steps come.

    Parameters
    ----------
    kernel : ndarray, shape (L, outputs, inputs, modes)
        ``A[m]`` for lags ``m = 0 .. L - 1`` (``A[0]`` is not used here); real or
        complex.  Steps are numbered from 1; at most ``L`` of them.

    Notes
    -----
    Call :meth:`history` for step ``n`` (``n = 1, 2, ...``) before :meth:`push` of that
    step's input ``x[n]``; calling it again in the same step returns the same history,
    and a :meth:`push` without it is refused.  The FFT lengths are powers of two; the
    lags' transforms of the levels below ``2^8`` steps are kept.
    """

    def __init__(self, kernel):
        self.kernel = np.asarray(kernel)
        self.steps, self.outputs, self.inputs, self.modes = self.kernel.shape
        dtype = np.result_type(self.kernel.dtype, np.float64)
        self._x = np.zeros((self.steps + 1, self.inputs, self.modes), dtype=complex
                           if np.iscomplexobj(self.kernel) else float)
        self._acc = np.zeros((2 * self.steps + 2, self.outputs, self.modes),
                             dtype=np.result_type(dtype, self._x.dtype))
        self._n = 1
        self._ready = 0
        self._lags = {}

    def _lag_transform(self, q):
        got = self._lags.get(q)
        if got is None:
            B = 1 << q
            a = np.zeros((4 * B, self.outputs, self.inputs, self.modes), dtype=self.kernel.dtype)
            top = min(2 * B, self.steps)
            if top > 1:
                a[1:top] = self.kernel[1:top]
            got = np.fft.fft(a, axis=0)
            if q < 8:
                self._lags[q] = got
        return got

    def history(self, n=None):
        """The history ``y[n]`` of the next step (``n`` checks the order)."""
        if n is not None and n != self._n:
            raise ValueError(f"history of step {n} asked at step {self._n}")
        n = self._n
        if self._ready == n:
            return self._acc[n]
        q = (n & -n).bit_length() - 1
        B = 1 << q
        if n > 1:
            lo = n - B
            block = np.zeros((4 * B, self.inputs, self.modes), dtype=self._x.dtype)
            block[:B] = self._x[lo:n]
            prod = np.einsum("foik,fik->fok", self._lag_transform(q), np.fft.fft(block, axis=0))
            full = np.fft.ifft(prod, axis=0)
            # Entry j is sum over i of x[lo + i] A[j - i]: output n + t sits at j = B + t.
            if not np.iscomplexobj(self._acc):
                full = full.real
            self._acc[n:n + B] += full[B:2 * B]
        self._ready = n
        return self._acc[n]

    def push(self, x):
        """Record the input ``x[n]`` (shape ``(inputs, modes)``) of the current step."""
        if self._ready != self._n:
            raise ValueError(f"push of step {self._n} before its history")
        self._x[self._n] = x
        self._n += 1
