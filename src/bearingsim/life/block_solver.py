"""Reusing the work between damage blocks: preconditioned conjugate gradients (issue 15 part 2).

A damage block changes the stiffness factor ``1 - D`` of every element by
``Delta_N (dD/dN)_j``: a lot for the fastest few, a vanishing amount for the rest. The condensed
core stiffness ``K(f)`` (symmetric positive definite) of consecutive blocks is therefore almost
the same, and so are their displacements. :class:`BlockSolver` solves ``K(f) U = F`` (one column
per load position) by conjugate gradients on all columns at once (Hestenes & Stiefel 1952; the
preconditioned form of Saad, *Iterative Methods for Sparse Linear Systems*, 2nd ed., alg. 9.1),

* starting from the previous blocks' solutions, extrapolated along their change;
* preconditioned by the exact LU factorization (SuperLU, :func:`scipy.sparse.linalg.splu`) of an
  earlier block's ``K``: the preconditioned operator differs from the identity by the stiffness
  change since that factorization, so one or two iterations reach the tolerance;
* refactorized when a block needed more than ``refactor_after`` iterations.

The triangular solves with the factors and the sparse products run in compiled kernels
(Numba) on row-major blocks of the load columns. Convergence: every column's residual below
``rtol`` times its load ``||F_j||``; a solve that does not converge within ``max_iter``
refactorizes at the current ``K`` and solves directly (exact).

Measured (``benchmarks/bench_life.py``, docs/validation.md): the default full run 2.6 x faster
than the direct solve, the same blocks and cycles to 6e-6, about 1.6 triangular solves per block;
the triangular solve (436 k factor entries) dominates and costs about as much for 8 load columns
as for 32 (its time goes into the scattered row accesses, not the arithmetic).

Tried and not kept: a Sherman-Morrison-Woodbury update of the factorization for the elements
whose factor moved most (after the first failure only the two crack-tip elements change by more
than 1e-5 per block, but the residual of the many small changes elsewhere still needed one
iteration per block); single-precision factors (no faster); a Galerkin start on the span of the
last three changes (a third fewer triangular solves, paid back in the products it needs).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from numba import njit
from numpy.typing import NDArray
from scipy.sparse.linalg import splu

from ..errors import SolverError

__all__ = ["BlockSolver"]


@njit(cache=True)
def _csr_matmat(indptr, indices, data, X, out, cols, G):  # pragma: no cover - compiled
    """``out[:, cols] = A @ X[:, cols]`` for CSR ``A`` (n, n) and row-major ``X`` (n, m);
    ``G`` (n, m) work space: the columns are gathered so the inner loops are contiguous."""
    n = X.shape[0]
    nc = cols.size
    for i in range(n):
        for kk in range(nc):
            G[i, kk] = X[i, cols[kk]]
    acc = np.empty(nc)
    for i in range(n):
        acc[:] = 0.0
        for p in range(indptr[i], indptr[i + 1]):
            a = data[p]
            j = indices[p]
            for kk in range(nc):
                acc[kk] += a * G[j, kk]
        for kk in range(nc):
            out[i, cols[kk]] = acc[kk]


@njit(cache=True)
def _lu_solve(
    l_ptr, l_idx, l_val, u_ptr, u_idx, u_val, u_diag, perm_r, perm_c, B, X, W, cols
):  # pragma: no cover
    """``X[:, cols] = A^-1 B[:, cols]`` with SuperLU factors ``Pr A Pc = L U`` (``L`` unit
    lower, CSC; ``U`` upper, CSC, diagonal ``u_diag``; values) for row-major ``B`` (n, m);
    ``W`` (n, m) work space (the columns gathered, so the inner loops are contiguous)."""
    n = B.shape[0]
    nc = cols.size
    for i in range(n):
        r = perm_r[i]
        for kk in range(nc):
            W[r, kk] = B[i, cols[kk]]
    for j in range(n):  # forward: L y = Pr b
        for p in range(l_ptr[j], l_ptr[j + 1]):
            i = l_idx[p]
            if i > j:
                v = l_val[p]
                for kk in range(nc):
                    W[i, kk] -= v * W[j, kk]
    for j in range(n - 1, -1, -1):  # backward: U z = y
        d = 1.0 / u_diag[j]
        for kk in range(nc):
            W[j, kk] *= d
        for p in range(u_ptr[j], u_ptr[j + 1]):
            i = u_idx[p]
            if i < j:
                v = u_val[p]
                for kk in range(nc):
                    W[i, kk] -= v * W[j, kk]
    for i in range(n):  # x = Pc z
        c = perm_c[i]
        for kk in range(nc):
            X[i, cols[kk]] = W[c, kk]


@njit(cache=True)
def _pcg(
    ip,
    ix,
    kd,
    l_ptr,
    l_idx,
    l_val,
    u_ptr,
    u_idx,
    u_val,
    u_diag,
    perm_r,
    perm_c,
    F,
    X,
    tol,
    max_iter,
):  # pragma: no cover
    """Preconditioned conjugate gradients on every column of ``K X = F`` (CSR ``K``; the LU
    factors of an earlier ``K`` as preconditioner), from ``X``, until each column's residual
    2-norm is ``<= tol[k]``; converged columns take no further step. Returns
    ``(iterations, triangular solves, converged)``; ``X`` holds the result."""
    n, m = F.shape
    R = np.empty((n, m))
    Z = np.empty((n, m))
    P = np.empty((n, m))
    Q = np.empty((n, m))
    W = np.empty((n, m), dtype=l_val.dtype)
    G = np.empty((n, m))
    rz = np.zeros(m)
    allc = np.arange(m)
    _csr_matmat(ip, ix, kd, X, Q, allc, G)
    act = np.zeros(m, dtype=np.bool_)
    for k in range(m):
        s = 0.0
        for i in range(n):
            R[i, k] = F[i, k] - Q[i, k]
            s += R[i, k] * R[i, k]
        act[k] = np.sqrt(s) > tol[k]
    cols = np.flatnonzero(act)
    if cols.size == 0:
        return 0, 0, True
    _lu_solve(l_ptr, l_idx, l_val, u_ptr, u_idx, u_val, u_diag, perm_r, perm_c, R, Z, W, cols)
    n_tri = 1
    for kk in range(cols.size):
        k = cols[kk]
        s = 0.0
        for i in range(n):
            P[i, k] = Z[i, k]
            s += R[i, k] * Z[i, k]
        rz[k] = s
    it = 0
    while it < max_iter:
        it += 1
        _csr_matmat(ip, ix, kd, P, Q, cols, G)
        for kk in range(cols.size):
            k = cols[kk]
            pq = 0.0
            for i in range(n):
                pq += P[i, k] * Q[i, k]
            alpha = rz[k] / pq if pq > 0.0 else 0.0
            s = 0.0
            for i in range(n):
                X[i, k] += alpha * P[i, k]
                R[i, k] -= alpha * Q[i, k]
                s += R[i, k] * R[i, k]
            act[k] = np.sqrt(s) > tol[k]
        cols = np.flatnonzero(act)
        if cols.size == 0:
            return it, n_tri, True
        _lu_solve(l_ptr, l_idx, l_val, u_ptr, u_idx, u_val, u_diag, perm_r, perm_c, R, Z, W, cols)
        n_tri += 1
        for kk in range(cols.size):
            k = cols[kk]
            s = 0.0
            for i in range(n):
                s += R[i, k] * Z[i, k]
            beta = s / rz[k] if rz[k] > 0.0 else 0.0
            rz[k] = s
            for i in range(n):
                P[i, k] = Z[i, k] + beta * P[i, k]
    return it, n_tri, False


@njit(cache=True)
def _shear_range(b_ptr, b_idx, bxx, byy, gxy, U, f, mu, mirror, orthogonal):  # pragma: no cover
    """``Delta_tau`` per element [Pa] straight from the displacements ``U`` (n_dofs, m) [m]:
    element-average strains from the operators (one CSR pattern, three value arrays), plane-
    strain stresses scaled by the element factor ``f``, then the range over the pass including
    the unloaded state (:meth:`bearingsim.life.fe.SectionStresses.shear_range`): the largest
    Tresca shear (``orthogonal`` False) or ``max(max tau_xz, 0) - min(min tau_xz, 0)`` (True).
    ``mirror[e]`` is the element whose columns are ``e``'s mirrored positions (``tau_xz`` of
    opposite sign); an empty ``mirror`` when ``U`` holds every position."""
    n_el = f.size
    m = U.shape[1]
    A = np.empty((n_el, m))
    T = np.empty((n_el, m))
    exx = np.empty(m)
    eyy = np.empty(m)
    exy = np.empty(m)
    for e in range(n_el):
        exx[:] = 0.0
        eyy[:] = 0.0
        exy[:] = 0.0
        for p in range(b_ptr[e], b_ptr[e + 1]):
            j = b_idx[p]
            vx, vy, vg = bxx[p], byy[p], gxy[p]
            for k in range(m):
                u = U[j, k]
                exx[k] += vx * u
                eyy[k] += vy * u
                exy[k] += vg * u
        fe = f[e]
        for k in range(m):
            # (sigma_x - sigma_z) / 2 = mu (eps_xx - eps_zz); tau_xz = -mu gamma_xy (y = -z)
            A[e, k] = fe * mu * (exx[k] - eyy[k])
            T[e, k] = -fe * mu * exy[k]
    out = np.empty(n_el)
    half = mirror.size > 0
    for e in range(n_el):
        me = mirror[e] if half else e
        if orthogonal:
            hi = 0.0
            lo = 0.0
            for k in range(m):
                t = T[e, k]
                hi = max(hi, t)
                lo = min(lo, t)
                if half:
                    t = -T[me, k]
                    hi = max(hi, t)
                    lo = min(lo, t)
            out[e] = hi - lo
        else:
            r = 0.0
            for k in range(m):
                r = max(r, np.hypot(A[e, k], T[e, k]), np.hypot(A[me, k], T[me, k]))
            out[e] = r
    return out


@dataclass
class _Factor:
    """SuperLU factors of one stiffness, in the arrays the compiled solve reads."""

    l_ptr: NDArray[np.int32]
    l_idx: NDArray[np.int32]
    l_val: NDArray[np.float64]
    u_ptr: NDArray[np.int32]
    u_idx: NDArray[np.int32]
    u_val: NDArray[np.float64]
    u_diag: NDArray[np.float64]
    perm_r: NDArray[np.int32]
    perm_c: NDArray[np.int32]

    @classmethod
    def of(cls, lu) -> _Factor:
        """From a :class:`scipy.sparse.linalg.SuperLU` object."""
        L, U = lu.L.tocsc(), lu.U.tocsc()
        L.sort_indices()
        U.sort_indices()
        return cls(
            L.indptr,
            L.indices,
            L.data,
            U.indptr,
            U.indices,
            U.data,
            np.ascontiguousarray(U.diagonal()),
            lu.perm_r,
            lu.perm_c,
        )

    def args(self) -> tuple:
        """The arrays the compiled kernels take, in their order."""
        return (
            self.l_ptr,
            self.l_idx,
            self.l_val,
            self.u_ptr,
            self.u_idx,
            self.u_val,
            self.u_diag,
            self.perm_r,
            self.perm_c,
        )


class BlockSolver:
    """Solves ``K(f) U = F`` for a sequence of slowly changing element factors ``f``.

    ``K(f)`` is assembled as ``data = P f + s`` on a fixed symmetric CSR pattern: ``P`` maps
    the element factors to the stored entries (each column one element's stiffness at unit
    factor), ``s`` is a constant part (the condensed outer region). Preconditioned conjugate
    gradients on all load columns at once (each column its own step lengths), from the last
    solution extrapolated along the last change (``2 U_k-1 - U_k-2``), preconditioned by the
    LU factors of ``K`` at an earlier block; a column whose residual is below the tolerance
    takes no further step. Refactorized when a solve needed more than ``refactor_after``
    iterations; a solve that does not converge in ``max_iter`` refactorizes and solves
    directly.

    Parameters
    ----------
    P : scipy.sparse matrix, shape (nnz, n_elements)
        Stored entries of ``K`` per unit element factor [N/m].
    s : ndarray, shape (nnz,)
        Constant stored entries [N/m].
    indptr, indices : ndarray
        The symmetric CSR pattern of ``K``.
    loads : ndarray, shape (n_dofs, n_loads)
        Load vectors [N].
    rtol : float
        Convergence: every column's residual ``||F_j - K U_j||_2 <= rtol ||F_j||_2`` [-]
        (default 1e-5: the 6206 damage life then agrees with the direct solve to 6e-6,
        docs/validation.md; ``tests/test_block_solver.py`` checks a coarse case).
    refactor_after : int
        Refactorize when a solve needed more than this many iterations [-].
    max_iter : int
        Iterations before falling back on a refactorization and a direct solve [-].

    Attributes
    ----------
    n_factorizations, n_preconditioner, n_solves, n_iterations : int
        LU factorizations, triangular solves (each with the unconverged load columns),
        solves and PCG iterations so far [-].
    """

    def __init__(
        self,
        P,
        s,
        indptr,
        indices,
        loads,
        *,
        rtol: float = 1e-5,
        refactor_after: int = 2,
        max_iter: int = 50,
    ) -> None:
        self._P = sp.csr_matrix(P)
        self._s = np.asarray(s, dtype=float)
        self._indptr = np.asarray(indptr, dtype=np.int32)
        self._indices = np.asarray(indices, dtype=np.int32)
        self.loads = np.ascontiguousarray(loads, dtype=float)
        n, m = self.loads.shape
        self.n = n
        if not (rtol > 0.0 and rtol < 1.0):
            raise ValueError(f"rtol = {rtol!r} is invalid; valid range (0, 1)")
        self.rtol, self.refactor_after, self.max_iter = rtol, refactor_after, max_iter
        self.n_factorizations = self.n_preconditioner = self.n_solves = self.n_iterations = 0
        self._fnorm = np.linalg.norm(self.loads, axis=0)
        self._factor: _Factor | None = None
        self._refactor = True
        self._U: NDArray[np.float64] | None = None
        self._U_old: NDArray[np.float64] | None = None

    def _direct(self, data: NDArray[np.float64]) -> NDArray[np.float64]:
        """Factorize ``K`` (the next preconditioner) and solve with it: SuperLU's own solve
        in double precision, so the result is exact."""
        # K is symmetric: its CSR arrays read as CSC are K itself
        K = sp.csc_matrix((data, self._indices, self._indptr), shape=(self.n,) * 2)
        try:
            lu = splu(K, permc_spec="MMD_AT_PLUS_A")
        except RuntimeError as exc:  # singular factor
            raise SolverError(f"plane-strain FE: core stiffness is singular ({exc})") from exc
        self._factor = _Factor.of(lu)
        self.n_factorizations += 1
        self._refactor = False
        return np.ascontiguousarray(lu.solve(self.loads))

    def solve(self, factor: NDArray[np.float64]) -> NDArray[np.float64]:
        """Displacements ``U`` (n_dofs, n_loads) [m] for element factors ``f`` [-] (a new
        array, owned by the caller)."""
        self.n_solves += 1
        data = self._P @ np.asarray(factor, dtype=float) + self._s
        if self._U is None or self._refactor:
            X = self._direct(data)
        else:
            X = self._pcg(data)
        if not np.all(np.isfinite(X)):
            raise SolverError("plane-strain FE: non-finite displacements (stiffness too degraded)")
        self._U_old, self._U = self._U, X
        return X.copy()

    def _pcg(self, data: NDArray[np.float64]) -> NDArray[np.float64]:
        # start from the last solution, extrapolated along the last change
        X = self._U.copy() if self._U_old is None else 2.0 * self._U - self._U_old
        it, n_tri, ok = _pcg(
            self._indptr,
            self._indices,
            data,
            *self._factor.args(),
            self.loads,
            X,
            self.rtol * self._fnorm,
            self.max_iter,
        )
        self.n_preconditioner += n_tri
        self.n_iterations += it
        if not ok:  # not converged in max_iter: refactorize, solve directly
            return self._direct(data)
        if it > self.refactor_after:
            self._refactor = True
        return X
