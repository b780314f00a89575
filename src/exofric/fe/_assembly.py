"""Sparse assembly: element blocks into the reduced (free-dof) matrix, and its banded solve.

The sparsity pattern and each block entry's slot are computed once (:class:`Assembler`), so an
assembly is one ``np.bincount``; the solve reorders to a narrow band (reverse Cuthill-McKee or a
given order) and uses LAPACK's banded Cholesky or LU, with dofs that couple to every node (the
axial stretch) kept out of the band by a Schur complement.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
import scipy.sparse as sp
from scipy.linalg import LinAlgError
from scipy.linalg.lapack import dgbtrf, dgbtrs, dpbtrf, dpbtrs
from scipy.sparse.csgraph import reverse_cuthill_mckee
from scipy.sparse.linalg import splu

__all__ = ["Assembler", "Factorization"]


class Assembler:
    """Assembles element blocks into a reduced (free-dof) sparse matrix.

    The sparsity pattern, the map of every block entry to its slot in the CSC
    data array, and the reduction to free dofs are computed once; each
    assembly is then one ``np.bincount``.

    Parameters
    ----------
    n_dofs : int
        Number of dofs of the full system.
    free : ndarray of bool (n_dofs,)
        True for unknown dofs.
    patterns : sequence of (rows, cols)
        Index arrays of the blocks that will be assembled, in call order.
    orders : sequence of ndarray of int, optional
        Candidate orderings of the dofs (each a permutation of ``range(n_dofs)``, e.g. a
        structured mesh's line-by-line order) tried besides reverse Cuthill-McKee; the one
        with the narrowest band is used. Candidates that are not permutations are ignored.
    border : sequence of int, optional
        Free dofs coupled to many others (e.g. a tube's axial stretch): kept out of the band
        and eliminated by their Schur complement in :meth:`solve`.

    Examples
    --------
    >>> import numpy as np
    >>> a = Assembler(2, np.array([True, True]), [(np.array([0, 1]), np.array([0, 1]))])
    >>> K = a.matrix([np.array([4.0, 16.0])])  # diag(4, 16)
    >>> a.solve(K, np.array([4.0, 8.0])).tolist()
    [1.0, 0.5]
    """

    def __init__(
        self, n_dofs: int, free: np.ndarray, patterns: Sequence[tuple[np.ndarray, np.ndarray]],
        orders: Sequence[np.ndarray] = (), border: Sequence[int] = (),
    ) -> None:
        self.n_dofs = n_dofs
        self.free = np.asarray(free, dtype=bool)
        self.red = np.full(n_dofs, -1)
        self.red[self.free] = np.arange(int(self.free.sum()))
        self.nf = int(self.free.sum())
        rr = np.concatenate([self.red[np.asarray(r).ravel()] for r, _ in patterns])
        cc = np.concatenate([self.red[np.asarray(c).ravel()] for _, c in patterns])
        self.sizes = [np.asarray(r).size for r, _ in patterns]
        self.keep = (rr >= 0) & (cc >= 0)
        self._slots: list[np.ndarray] | None = None  # per pattern: CSC slot of each entry
        lin = cc[self.keep].astype(np.int64) * self.nf + rr[self.keep]
        uniq, self.inv = np.unique(lin, return_inverse=True)
        self.nnz = uniq.size
        self.indices = (uniq % self.nf).astype(np.int32)
        cols = uniq // self.nf
        self.indptr = np.searchsorted(cols, np.arange(self.nf + 1)).astype(np.int32)

        # Border dofs (e.g. a tube's axial stretch, coupled to every node) would make the band
        # as wide as the system: they are kept out of it and eliminated by a Schur complement
        # in :meth:`solve` (``ints``: the reduced ids of the other, interior, dofs).
        bred = self.red[np.asarray(border, dtype=np.int64)]
        if np.any(bred < 0):
            raise ValueError("border dofs must be free")
        isb = np.zeros(self.nf, dtype=bool)
        isb[bred] = True
        self.border = bred
        self.ints = np.flatnonzero(~isb)
        ni = self.ints.size
        ii = np.full(self.nf, -1)
        ii[self.ints] = np.arange(ni)
        col_of = np.repeat(np.arange(self.nf), np.diff(self.indptr))
        row_i, col_i = ii[self.indices], ii[col_of]
        self.e_ii = (row_i >= 0) & (col_i >= 0)
        if bred.size:
            bpos = np.full(self.nf, -1)
            bpos[bred] = np.arange(bred.size)
            e_ib = (row_i >= 0) & (col_i < 0)
            e_bi = (row_i < 0) & (col_i >= 0)
            e_bb = (row_i < 0) & (col_i < 0)
            self._ib = (e_ib, row_i[e_ib], bpos[col_of[e_ib]])
            self._bi = (e_bi, bpos[self.indices[e_bi]], col_i[e_bi])
            self._bb = (e_bb, bpos[self.indices[e_bb]], bpos[col_of[e_bb]])

        # Banded storage after a bandwidth-reducing ordering: the thin structured meshes of
        # the tube then have a narrow band, and LAPACK's banded solvers beat SuperLU's general
        # sparse LU (by ~2x for the banded LU) at these sizes (a few hundred to ~20000 dofs).
        # The candidates are reverse Cuthill-McKee of the pattern and the problem's own
        # ``orders`` (for the tube: angle-major, one radial line after the other; an element
        # spans three lines of 2 n_radial + 1 nodes, so the band is 4 (2 n_radial + 1) + 5
        # dofs for quad9, against RCM's diagonal fronts 73 vs 127 at 8 x 128: a third of the
        # Cholesky work, which grows as n band^2). The narrowest band
        # wins. This is the whole symbolic analysis: the ordering and each CSC slot's place in
        # the band are computed once here and reused by every factorisation.
        ri, ci = row_i[self.e_ii], col_i[self.e_ii]
        pattern = sp.csc_matrix((np.ones(ri.size), (ri, ci)), shape=(ni, ni))
        candidates = [np.asarray(reverse_cuthill_mckee(pattern.tocsr(), symmetric_mode=True))]
        for order in orders:
            r = self.red[np.asarray(order, dtype=np.int64)]
            r = ii[r[r >= 0]]
            r = r[r >= 0]
            if r.size == ni and np.array_equal(np.sort(r), np.arange(ni)):
                candidates.append(r)
        best = None
        for perm in candidates:
            iperm = np.empty_like(perm)
            iperm[perm] = np.arange(ni)
            rows, colsp = iperm[ri], iperm[ci]
            band = int(np.max(np.abs(rows - colsp))) if ri.size else 0
            if best is None or band < best[0]:
                best = (band, perm, rows, colsp)
        assert best is not None
        self.band, self.perm, rows, colsp = best
        # LAPACK's band storage, column-major (Fortran order, so that LAPACK works in place):
        # entry (i, j) of the permuted matrix sits at flat index j * ldab + (row in the band).
        # gbsv (LU, partial pivoting) takes ldab = 3 band + 1 (band extra rows on top for the
        # pivoting's fill-in), entry (i, j) on row 2 band + i - j. Tangents of energy-based
        # problems are symmetric and, near a stable equilibrium, positive definite: pbsv
        # (Cholesky) on the upper band, ldab = band + 1, entry (i <= j) on row band + i - j,
        # then does a quarter of the LU's work on a third of its storage. ``transpose_slot``
        # is the CSC slot of each entry's transpose (None for a non-symmetric pattern).
        b = self.band
        self.lu_slot = colsp.astype(np.int64) * (3 * b + 1) + (2 * b + rows - colsp)
        self.upper = rows <= colsp
        self.chol_slot = (colsp.astype(np.int64) * (b + 1) + (b + rows - colsp))[self.upper]
        tkey = self.indices.astype(np.int64) * self.nf + cols
        tpos = np.minimum(np.searchsorted(uniq, tkey), max(self.nnz - 1, 0))
        self.transpose_slot = tpos if self.nnz and np.array_equal(uniq[tpos], tkey) else None

    def solve(self, K: sp.csc_matrix, rhs: np.ndarray) -> np.ndarray:
        """Solve ``K x = rhs`` for a matrix from :meth:`matrix` (banded solver after RCM).

        One :meth:`factorize` and one :meth:`Factorization.solve`; see there.

        Parameters
        ----------
        K : scipy.sparse.csc_matrix (nf, nf)
            Matrix of the free dofs, as returned by :meth:`matrix` (same pattern).
        rhs : ndarray (nf,)
            Right-hand side over the free dofs.

        Returns
        -------
        ndarray (nf,)
        """
        return self.factorize(K).solve(rhs)

    def factorize(self, K: sp.csc_matrix) -> Factorization:
        """Factorise ``K`` (a matrix from :meth:`matrix`) for repeated solves.

        A matrix that is symmetric to round-off (1e-12 of its largest entry) is first given
        to LAPACK's banded Cholesky (pbtrf); if it is not positive definite (or not
        symmetric), the banded LU with partial pivoting (gbtrf) factorises it. Falls back to
        SuperLU when the band is wider than 1/4 of the system. Border dofs (``border``) are
        eliminated by their Schur complement: the interior factor is applied to the border
        columns once here, so that each solve is two banded triangular sweeps. Raises
        ``LinAlgError`` for a singular matrix.

        Parameters
        ----------
        K : scipy.sparse.csc_matrix (nf, nf)
            Matrix of the free dofs, as returned by :meth:`matrix` (same pattern).

        Returns
        -------
        Factorization

        Examples
        --------
        >>> import numpy as np
        >>> a = Assembler(2, np.array([True, True]), [(np.array([0, 1]), np.array([0, 1]))])
        >>> f = a.factorize(a.matrix([np.array([4.0, 16.0])]))
        >>> f.solve(np.array([4.0, 8.0])).tolist(), f.solve(np.array([8.0, 16.0])).tolist()
        ([1.0, 0.5], [2.0, 1.0])
        """
        ni = self.ints.size
        if 4 * self.band > ni:
            return Factorization(self, splu(K.tocsc()), None, None)
        data = K.data
        sym = self.transpose_slot is not None and np.max(
            np.abs(data - data[self.transpose_slot])) <= 1e-12 * np.max(np.abs(data))
        band = _BandFactor(self, data[self.e_ii], sym)
        nb = self.border.size
        if not nb:
            return Factorization(self, band, None, None)
        kib = np.zeros((ni, nb))
        e, r, c = self._ib
        kib[r, c] = data[e]
        kbi, kbb = np.zeros((nb, ni)), np.zeros((nb, nb))
        e, r, c = self._bi
        kbi[r, c] = data[e]
        e, r, c = self._bb
        kbb[r, c] = data[e]
        y = band.solve(kib)  # K_ii^-1 K_ib
        schur = kbb - kbi @ y
        if not np.all(np.isfinite(schur)):
            raise LinAlgError("singular matrix")
        return Factorization(self, band, (kbi, y), np.linalg.inv(schur))  # LinAlgError if singular

    def add(self, K: sp.csc_matrix, pattern: int, values: np.ndarray) -> sp.csc_matrix:
        """``K`` plus values on the entries of one pattern (a new matrix; ``K`` is kept).

        Parameters
        ----------
        K : scipy.sparse.csc_matrix (nf, nf)
            A matrix from :meth:`matrix`.
        pattern : int
            Index of the pattern (in the ``patterns`` given to the constructor).
        values : ndarray
            Values in that pattern's order and shape; entries on fixed dofs are dropped.

        Returns
        -------
        scipy.sparse.csc_matrix (nf, nf)

        Examples
        --------
        >>> import numpy as np
        >>> a = Assembler(2, np.array([True, True]), [(np.array([0, 1]), np.array([0, 1]))])
        >>> a.add(a.matrix([np.array([4.0, 16.0])]), 0, np.array([1.0, 0.0])).toarray().tolist()
        [[5.0, 0.0], [0.0, 16.0]]
        """
        if self._slots is None:
            full = np.full(self.keep.size, -1, dtype=np.int64)
            full[self.keep] = self.inv
            ends = np.cumsum([0, *self.sizes])
            self._slots = [full[a:b] for a, b in zip(ends[:-1], ends[1:], strict=True)]
        slots = self._slots[pattern]
        ok = slots >= 0
        data = K.data + np.bincount(slots[ok], weights=np.asarray(values, dtype=float).ravel()[ok],
                                    minlength=self.nnz)
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(self.nf, self.nf))

    def matrix(self, blocks: Sequence[np.ndarray]) -> sp.csc_matrix:
        """CSC matrix of the free dofs from block values given in pattern order.

        Parameters
        ----------
        blocks : sequence of ndarray
            Values of each pattern's entries, in the order and shapes of ``patterns``;
            entries on fixed dofs are dropped, repeated entries summed.

        Returns
        -------
        scipy.sparse.csc_matrix (nf, nf)
        """
        vals = np.concatenate([np.asarray(b).ravel() for b in blocks])[self.keep]
        data = np.bincount(self.inv, weights=vals, minlength=self.nnz)
        return sp.csc_matrix((data, self.indices, self.indptr), shape=(self.nf, self.nf))


class _BandFactor:
    """Banded Cholesky (pbtrf) or, failing that, LU (gbtrf) of an Assembler's interior block."""

    def __init__(self, asm: Assembler, data: np.ndarray, sym: bool) -> None:
        ni, b = asm.ints.size, asm.band
        self.perm = asm.perm
        self.chol = False
        if sym:
            ab = np.zeros((ni, b + 1))  # the transpose of the Fortran-ordered band
            ab.ravel()[asm.chol_slot] = data[asm.upper]
            c, info = dpbtrf(ab.T, lower=0, overwrite_ab=1)
            if info == 0:
                self.chol, self.ab = True, c
                return
        ab = np.zeros((ni, 3 * b + 1))
        ab.ravel()[asm.lu_slot] = data
        lu, piv, info = dgbtrf(ab.T, b, b, overwrite_ab=1)
        if info > 0:
            raise LinAlgError("singular matrix")
        if info < 0:
            raise ValueError(f"illegal value in argument {-info} of gbtrf")
        self.ab, self.piv, self.b = lu, piv, b

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve for the columns of ``rhs`` (ni, k) or a vector (ni,)."""
        rp = np.ascontiguousarray(rhs[self.perm], dtype=float)
        if self.chol:
            xp, info = dpbtrs(self.ab, rp, lower=0)
        else:
            xp, info = dgbtrs(self.ab, self.b, self.b, rp, self.piv)
        if info != 0:
            raise ValueError(f"illegal value in argument {-info} of the banded solve")
        x = np.empty_like(xp)
        x[self.perm] = xp
        return x


class Factorization:
    """A factorised matrix of an :class:`Assembler` (from :meth:`Assembler.factorize`).

    Solves reuse the factors: a Newton iteration whose tangent barely changed (the chord
    steps of :func:`exofric.fe.solve_path`) costs two triangular sweeps instead of an
    assembly and a factorisation.

    Examples
    --------
    >>> import numpy as np
    >>> a = Assembler(2, np.array([True, True]), [(np.array([0, 1]), np.array([0, 1]))])
    >>> a.factorize(a.matrix([np.array([4.0, 16.0])])).solve(np.array([4.0, 8.0])).tolist()
    [1.0, 0.5]
    """

    def __init__(self, asm: Assembler, inner: _BandFactor | Any,
                 border: tuple[np.ndarray, np.ndarray] | None,
                 schur_inv: np.ndarray | None) -> None:
        self._asm = asm
        self._inner = inner
        self._border = border  # (K_bi, K_ii^-1 K_ib)
        self._schur_inv = schur_inv

    def solve(self, rhs: np.ndarray) -> np.ndarray:
        """Solve ``K x = rhs`` with the stored factors.

        Parameters
        ----------
        rhs : ndarray (nf,) or (nf, k)
            Right-hand side(s) over the free dofs (k columns: one sweep for all).

        Returns
        -------
        ndarray (nf,) or (nf, k)
        """
        a = self._asm
        rhs = np.asarray(rhs, dtype=float)
        if not isinstance(self._inner, _BandFactor):  # SuperLU (wide band)
            return np.asarray(self._inner.solve(rhs))
        y = self._inner.solve(rhs[a.ints])
        if self._border is None or self._schur_inv is None:
            x = np.empty(rhs.shape)
            x[a.ints] = y
            return x
        kbi, kib_y = self._border
        xb = self._schur_inv @ (rhs[a.border] - kbi @ y)
        x = np.empty(rhs.shape)
        x[a.ints] = y - kib_y @ xb
        x[a.border] = xb
        return x
