"""Reusing the work between damage blocks: preconditioned conjugate gradients (issue 15 part 2).

A damage block changes the stiffness factor ``1 - D`` of every element by
``Delta_N (dD/dN)_j``: a lot for the fastest few, a vanishing amount for the rest. The condensed
core stiffness ``K(f)`` (symmetric positive definite) of consecutive blocks is therefore almost
the same, and so are their displacements. :class:`BlockSolver` solves ``K(f) U = F`` (one column
per load position) by conjugate gradients on all columns at once (Hestenes & Stiefel 1952; the
preconditioned form of Saad, *Iterative Methods for Sparse Linear Systems*, 2nd ed., alg. 9.1),

* starting from the quadratic extrapolation of the last three well-converged solutions along
  the block index; when that start already meets the tolerance the block needs no iteration
  (most blocks before initiation: the damage grows smoothly);
* preconditioned by ``L D L^T``, the factorization of an earlier block's ``K`` (SuperLU,
  :func:`scipy.sparse.linalg.splu`, with diagonal pivots in symmetric mode: ``U = D L^T``, so
  ``L`` and ``D`` carry the whole factorization and the preconditioner is exactly symmetric);
  the preconditioned operator differs from the identity by the stiffness change since that
  factorization, so one or two iterations reach the tolerance;
* refactorized when a block needed more than ``refactor_after`` iterations, with the
  fill-reducing ordering of the first factorization (the pattern never changes).

The triangular solves and the sparse products run in compiled kernels (Numba) on row-major
blocks of the load columns; the dense block of ``K`` that the condensed outer region adds (half
of its stored entries) is multiplied through BLAS. Convergence: every column's residual below
``rtol`` times its load ``||F_j||``, whether the start was accepted or iterated; a solve that
does not converge within ``max_iter`` refactorizes at the current ``K`` and solves directly.

Measured (``benchmarks/bench_life.py``, docs/validation.md): blocks, cycles and the failed zone
the same as the direct solve of every block, the life to 1e-5.

Tried and not kept: a Sherman-Morrison-Woodbury update of the factorization for the elements
whose factor moved most (after the first failure only the two crack-tip elements change by more
than 1e-5 per block, but the residual of the many small changes elsewhere still needed one
iteration per block); single-precision factors (no faster); a Galerkin start on the span of the
last three changes (a third fewer triangular solves, paid back in the products it needs); a
looser tolerance after initiation (1e-3: still about one triangular solve per block there,
because the crack tip changes too fast for any extrapolation).
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
def _csr_matmat(indptr, indices, data, S, g, X, out, cols, G):  # pragma: no cover - compiled
    """``out[:, cols] = (A + E_g S E_g^T) @ X[:, cols]`` for CSR ``A`` (n, n), a dense block
    ``S`` (n_g, n_g) on the rows and columns ``g`` (the condensed outer region: a BLAS
    product), and row-major ``X`` (n, m); ``G`` (n, m) work space: the columns are gathered so
    the inner loops are contiguous."""
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
    ng = g.size
    if ng > 0:
        Xg = np.empty((ng, nc))
        for i in range(ng):
            for kk in range(nc):
                Xg[i, kk] = G[g[i], kk]
        Y = np.dot(S, Xg)
        for i in range(ng):
            for kk in range(nc):
                out[g[i], cols[kk]] += Y[i, kk]


@njit(cache=True)
def _ldl_solve(l_ptr, l_idx, l_val, d, perm, B, X, W, cols):  # pragma: no cover
    """``X[:, cols] = A^-1 B[:, cols]`` with the factors ``P A P^T = L D L^T`` of a symmetric
    ``A`` (``L`` strictly lower part, CSC, any order within a column; ``D`` diagonal ``d``;
    ``perm[i]`` the row of ``P A`` that row ``i`` of ``A`` becomes) for row-major ``B`` (n, m);
    ``W`` (n, m) work space (the columns gathered, so the inner loops are contiguous)."""
    n = B.shape[0]
    nc = cols.size
    for i in range(n):
        r = perm[i]
        for kk in range(nc):
            W[r, kk] = B[i, cols[kk]]
    for j in range(n):  # forward: L y = P b (column-oriented)
        for p in range(l_ptr[j], l_ptr[j + 1]):
            i = l_idx[p]
            v = l_val[p]
            for kk in range(nc):
                W[i, kk] -= v * W[j, kk]
    for j in range(n):  # D z = y
        dj = 1.0 / d[j]
        for kk in range(nc):
            W[j, kk] *= dj
    acc = np.empty(nc)
    for j in range(n - 1, -1, -1):  # backward: L^T w = z (row j of L^T is column j of L)
        for kk in range(nc):
            acc[kk] = W[j, kk]
        for p in range(l_ptr[j], l_ptr[j + 1]):
            i = l_idx[p]
            v = l_val[p]
            for kk in range(nc):
                acc[kk] -= v * W[i, kk]
        for kk in range(nc):
            W[j, kk] = acc[kk]
    for i in range(n):  # x = P^T w
        r = perm[i]
        for kk in range(nc):
            X[i, cols[kk]] = W[r, kk]


@njit(cache=True)
def _pcg(
    ip,
    ix,
    kd,
    S,
    g,
    l_ptr,
    l_idx,
    l_val,
    d,
    perm,
    F,
    X,
    accept,
    tol,
    max_iter,
    work,
):  # pragma: no cover
    """Preconditioned conjugate gradients on every column of ``K X = F`` (``K``: CSR
    ``(ip, ix, kd)`` plus the dense block ``S`` on ``g``, see :func:`_csr_matmat`; the
    ``L D L^T`` factors of an earlier ``K`` as preconditioner). ``X`` is accepted as it is when
    every column's residual 2-norm is ``<= accept[k]``; otherwise the columns above ``tol[k]``
    (``<= accept[k]``) iterate until they are below it, converged columns taking no further
    step. ``work`` (6, n, m): work space. Returns ``(iterations, triangular solves,
    converged)``; ``X`` holds the result."""
    n, m = F.shape
    R, Z, P, Q, W, G = work[0], work[1], work[2], work[3], work[4], work[5]
    rz = np.zeros(m)
    allc = np.arange(m)
    _csr_matmat(ip, ix, kd, S, g, X, Q, allc, G)
    act = np.zeros(m, dtype=np.bool_)
    good = True
    for k in range(m):
        s = 0.0
        for i in range(n):
            R[i, k] = F[i, k] - Q[i, k]
            s += R[i, k] * R[i, k]
        act[k] = np.sqrt(s) > tol[k]
        good = good and np.sqrt(s) <= accept[k]
    if good:  # also when no column is above tol (tol <= accept)
        return 0, 0, True
    cols = np.flatnonzero(act)
    _ldl_solve(l_ptr, l_idx, l_val, d, perm, R, Z, W, cols)
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
        _csr_matmat(ip, ix, kd, S, g, P, Q, cols, G)
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
        _ldl_solve(l_ptr, l_idx, l_val, d, perm, R, Z, W, cols)
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
            r2 = 0.0  # the largest squared Tresca shear; one square root per element
            for k in range(m):
                a, t, am, tm = A[e, k], T[e, k], A[me, k], T[me, k]
                r2 = max(r2, a * a + t * t, am * am + tm * tm)
            out[e] = np.sqrt(r2)
    return out


@dataclass
class _Factor:
    """``P K P^T = L D L^T`` of one symmetric positive definite stiffness, in the arrays the
    compiled solve reads: SuperLU with diagonal pivots in symmetric mode gives
    ``Pr K Pc = L U`` with ``Pr = Pc^T`` and ``U = D L^T`` (to round-off), so ``L`` and ``D``
    carry the whole factorization and the preconditioner is exactly symmetric."""

    l_ptr: NDArray[np.int32]
    l_idx: NDArray[np.int32]
    l_val: NDArray[np.float64]
    d: NDArray[np.float64]
    perm: NDArray[np.int32]

    @classmethod
    def factorize(cls, K, perm: NDArray[np.int32] | None = None) -> _Factor:
        """Factorize the CSC matrix ``K`` (fill-reducing ordering: minimum degree on
        ``K + K^T``), or, with ``perm``, the matrix ``P K P^T`` already permuted by that
        ordering (the symbolic work of a new ordering skipped). :class:`SolverError` if it is
        singular or not positive definite."""
        try:
            lu = splu(
                K,
                permc_spec="MMD_AT_PLUS_A" if perm is None else "NATURAL",
                diag_pivot_thresh=0.0,
                options={"SymmetricMode": True},
            )
        except RuntimeError as exc:  # singular factor
            raise SolverError(f"plane-strain FE: core stiffness is singular ({exc})") from exc
        d = np.ascontiguousarray(lu.U.diagonal())
        if not np.array_equal(lu.perm_r, lu.perm_c) or not np.all(d > 0.0):
            raise SolverError("plane-strain FE: core stiffness is not positive definite")
        # drop L's unit diagonal (the solve needs no order within a column)
        L = lu.L
        col = np.repeat(np.arange(L.shape[1], dtype=np.int32), np.diff(L.indptr))
        low = L.indices > col
        ptr = np.zeros(L.shape[1] + 1, dtype=np.int32)
        np.cumsum(np.bincount(col[low], minlength=L.shape[1]), out=ptr[1:])
        # row i of K is row perm[i] of P K P^T, which SuperLU's own postorder moves on
        p = lu.perm_r if perm is None else lu.perm_r[perm]
        return cls(ptr, L.indices[low], L.data[low], d, np.ascontiguousarray(p, dtype=np.int32))

    def args(self) -> tuple:
        """The arrays the compiled kernels take, in their order."""
        return (self.l_ptr, self.l_idx, self.l_val, self.d, self.perm)

    def solve(self, B: NDArray[np.float64]) -> NDArray[np.float64]:
        """``K^-1 B`` for row-major ``B`` (n, m)."""
        X = np.empty_like(B)
        cols = np.arange(B.shape[1])
        _ldl_solve(*self.args(), B, X, np.empty_like(B), cols)
        return X


class BlockSolver:
    """Solves ``K(f) U = F`` for a sequence of slowly changing element factors ``f``.

    ``K(f)`` is assembled as ``data = P f + s`` on a fixed symmetric CSR pattern: ``P`` maps
    the element factors to the stored entries (each column one element's stiffness at unit
    factor), ``s`` is a constant part (the condensed outer region).

    Each solve starts from the polynomial through the last ``n_anchors`` *anchors* (solutions
    converged to ``inner * rtol``), evaluated at the solve's index: quadratic extrapolation
    along the damage history. That start is accepted without a single iteration when every
    load column's residual is within ``rtol``; otherwise preconditioned conjugate gradients on
    all load columns at once (each column its own step lengths; preconditioner: the
    ``L D L^T`` factors of ``K`` at an earlier block) take the columns to ``inner * rtol``,
    and the result becomes an anchor. Converging the anchors ``1 / inner`` times further than
    asked keeps their round-off from spoiling the extrapolation, so several blocks in a row
    need no triangular solve. Refactorized when a solve needed more than ``refactor_after``
    iterations; a solve that does not converge in ``max_iter`` refactorizes and solves
    directly.

    Every returned solution meets the same criterion, whichever way it was reached.

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
        (default 1e-5: the 6206 damage life then agrees with the direct solve to < 1e-5,
        docs/validation.md; ``tests/test_block_solver.py`` checks a coarse case).
    inner : float
        Anchors are converged to ``inner * rtol`` [-], in (0, 1].
    n_anchors : int
        Anchors the start extrapolates from (1: the last solution; 3: quadratic) [-].
    refactor_after : int
        Refactorize when a solve needed more than this many iterations [-].
    max_iter : int
        Iterations before falling back on a refactorization and a direct solve [-].

    Attributes
    ----------
    n_factorizations, n_preconditioner, n_solves, n_iterations, n_accepted : int
        LU factorizations, triangular solves (each with the unconverged load columns),
        solves, PCG iterations and solves accepted at the extrapolated start so far [-].
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
        inner: float = 0.1,
        n_anchors: int = 3,
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
        if not (inner > 0.0 and inner <= 1.0):
            raise ValueError(f"inner = {inner!r} is invalid; valid range (0, 1]")
        if n_anchors not in (1, 2, 3):
            raise ValueError(f"n_anchors = {n_anchors!r} is invalid; valid values 1, 2, 3")
        self.rtol, self.inner, self.n_anchors = rtol, inner, n_anchors
        self.refactor_after, self.max_iter = refactor_after, max_iter
        self.n_factorizations = self.n_preconditioner = self.n_solves = self.n_iterations = 0
        self.n_accepted = 0
        self._fnorm = np.linalg.norm(self.loads, axis=0)
        self._work = np.empty((6, n, m))  # the PCG kernel's work space, allocated once
        self._split()
        self._factor: _Factor | None = None
        #: fill-reducing ordering of the first factorization: (perm, map, indptr, indices)
        self._ordering: tuple | None = None
        self._refactor = True
        #: (solve index, solution) of the last anchors, oldest first
        self._anchors: list[tuple[int, NDArray[np.float64]]] = []

    def _split(self) -> None:
        """The products in PCG: ``K = A(f) + E_g S E_g^T`` with ``A`` the element entries
        (sparse, ``P_A f`` on their own CSR pattern) and ``S`` the constant part as a dense
        block on the dofs ``g`` when it is one (the condensed outer region: a dense Schur
        complement, half the stored entries, multiplied through BLAS); otherwise all of ``K``
        is the sparse part and ``S`` is empty."""
        n = self.n
        row = np.repeat(np.arange(n), np.diff(self._indptr))
        sv = self._s != 0.0
        g = np.unique(row[sv])
        dense = g.size > 0 and sv.sum() >= 0.5 * g.size**2
        if dense:
            el = np.diff(self._P.indptr) > 0  # stored entries some element touches
            loc = np.full(n, -1, dtype=np.int64)
            loc[g] = np.arange(g.size)
            S = np.zeros((g.size, g.size))
            S[loc[row[sv]], loc[self._indices[sv]]] = self._s[sv]
            self._s_el = None  # all of the constant part is in S
        else:
            el = np.ones(row.size, dtype=bool)
            g, S = np.zeros(0, dtype=np.int64), np.zeros((0, 0))
            self._s_el = self._s
        ptr = np.zeros(n + 1, dtype=np.int32)
        np.cumsum(np.bincount(row[el], minlength=n), out=ptr[1:])
        self._P_el = self._P[np.flatnonzero(el)]
        self._el = (ptr, self._indices[el], np.ascontiguousarray(S), g.astype(np.int64))

    def _sparse_data(self, f: NDArray[np.float64]) -> NDArray[np.float64]:
        """Stored entries of the sparse part of ``K`` (:meth:`_split`) for element factors
        ``f`` [N/m]."""
        data = self._P_el @ f
        return data if self._s_el is None else data + self._s_el

    def _direct(self, data: NDArray[np.float64]) -> NDArray[np.float64]:
        """Factorize ``K`` (the next preconditioner) and solve with it (exact to round-off).
        The first factorization chooses the ordering; later ones reuse it (the pattern of
        ``K`` does not change), factorizing ``P K P^T`` assembled through a fixed map."""
        n = self.n
        if self._ordering is None:
            # K is symmetric: its CSR arrays read as CSC are K itself
            K = sp.csc_matrix((data, self._indices, self._indptr), shape=(n, n))
            self._factor = _Factor.factorize(K)
            perm = self._factor.perm.copy()
            q = np.argsort(perm)  # row q[i] of K becomes row i of P K P^T
            ids = np.arange(1, data.size + 1, dtype=float)
            Kp = sp.csc_matrix((ids, self._indices, self._indptr), shape=(n, n))[q][:, q]
            Kp = Kp.tocsc()
            Kp.sort_indices()  # canonical: splu would sort these shared arrays in place
            self._ordering = (perm, Kp.data.astype(np.int64) - 1, Kp.indptr, Kp.indices)
        else:
            perm, take, ptr, idx = self._ordering
            Kp = sp.csc_matrix((data[take], idx, ptr), shape=(n, n))
            self._factor = _Factor.factorize(Kp, perm)
        self.n_factorizations += 1
        self._refactor = False
        return self._factor.solve(self.loads)

    def _start(self, t: int) -> NDArray[np.float64]:
        """The Lagrange polynomial through the anchors, evaluated at solve index ``t``."""
        ts = [a for a, _ in self._anchors]
        X = np.zeros_like(self._anchors[-1][1])
        for i, (ti, Ui) in enumerate(self._anchors):
            w = 1.0
            for j, tj in enumerate(ts):
                if j != i:
                    w *= (t - tj) / (ti - tj)
            X += w * Ui
        return X

    def solve(self, factor: NDArray[np.float64]) -> NDArray[np.float64]:
        """Displacements ``U`` (n_dofs, n_loads) [m] for element factors ``f`` [-] (a new
        array, owned by the caller)."""
        self.n_solves += 1
        t = self.n_solves
        f = np.asarray(factor, dtype=float)
        anchor = True
        if not self._anchors or self._refactor:
            X = self._direct(self._P @ f + self._s)
        else:
            X, anchor = self._pcg(f, self._start(t))
        if not np.all(np.isfinite(X)):
            raise SolverError("plane-strain FE: non-finite displacements (stiffness too degraded)")
        if anchor:
            self._anchors = [*self._anchors, (t, X)][-self.n_anchors :]
        return X.copy()

    def _pcg(self, f: NDArray[np.float64], X: NDArray[np.float64]):
        """PCG from ``X`` for element factors ``f``; returns the solution and whether it is
        an anchor."""
        ptr, idx, S, g = self._el
        it, n_tri, ok = _pcg(
            ptr,
            idx,
            self._sparse_data(f),
            S,
            g,
            *self._factor.args(),
            self.loads,
            X,
            self.rtol * self._fnorm,
            self.inner * self.rtol * self._fnorm,
            self.max_iter,
            self._work,
        )
        self.n_preconditioner += n_tri
        self.n_iterations += it
        if not ok:  # not converged in max_iter: refactorize, solve directly
            return self._direct(self._P @ f + self._s), True
        if it == 0:
            self.n_accepted += 1
            return X, False
        if it > self.refactor_after:
            self._refactor = True
        return X, True
