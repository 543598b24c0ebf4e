"""The plane-strain field below a wavy contact: the complex potential of the surface tractions,
docs/theory/wavy.md (W36)-(W42).

With zeta = x + i z (z depth, x and z in units of the contact half-width a here) and
G(zeta) = (1/pi) int p(s)/(zeta - s) ds the Cauchy potential of the pressure (periodic surface: the
cot kernel), the stresses of the normal load are (W36)

    sigma_xx = Im G + z Re G',   sigma_zz = Im G - z Re G',   sigma_xz = -z Im G',

and those of a shear traction q with potential H = (1/pi) int q(s)/(zeta - s) ds (W41)

    sigma_xx = -2 Re H + z Im H',   sigma_zz = -z Im H',   sigma_xz = Im H + z Re H'.

G is evaluated without quadrature:

* non-periodic, (W38): p/p* = sum_m D_m sin((2m + 1) theta) = sqrt(1 - t^2) sum_m D_m U_2m(t) gives
  G = sum_m D_m omega^(2m + 1), omega = 1/(Z + sqrt(Z - 1) sqrt(Z + 1)), Z = zeta/a, |omega| < 1 in the
  body: the surface series of the same length, whose error bound holds unchanged (|omega| <= 1);
* periodic, (W37): G = -i S(w), w = e^{i zeta a} (lambda_1 = 2 pi), S(w) = p_inf + 2 sum_k p_k w^k with p_k
  the cosine coefficients of p; near the surface by the closed finite form
  S = F - sum_k f_{-k} (w^{-k} - w^k), F = X T/4 with X = sqrt(1 - w e^{-ia}) sqrt(1 - w e^{ia}) and
  T = sum_j B_j (w^j + w^{-j-1}) of (W30); at depth, where the poles' cancellation would cost digits,
  by the Taylor series of S, whose length is chosen a priori from a bound (W39).

Pure NumPy; coordinates broadcast with the table rows of ``contact``'s context.
"""
from __future__ import annotations

import numpy as np

from . import periodic as _periodic
from . import series

_U = 0.5 * series.EPS
#: longest Taylor series of S (periodic, at depth); beyond it the rows are flagged not converged
MAX_SERIES = 4096
#: pi in two parts (pi_hi the double nearest pi, pi_lo the rest), for angles taken into (-pi, pi] exactly
_PI_HI, _PI_LO = np.pi, 1.2246467991473532e-16


def _sqrt1m_coefficients(top):
    """h_m, m < top: sqrt(1 - u) = sum_m h_m u^m (h_0 = 1, h_m = -binom(2m, m)/(4^m (2m - 1)))."""
    g = _periodic._central(top)
    m = np.arange(top)
    return np.where(m == 0, 1.0, -g / np.where(m == 0, 1.0, 2.0 * m - 1.0))


class PeriodicPotential:
    """The periodic potential S(w) of every row of a closed-form table (W37), (W39).

    Per row: the principal-part coefficients f_{-k} (k = 1 .. K) of F at w = 0, the Taylor
    coefficients s_m of S (m < M), the depth z_switch (kernel units) below which the closed form is
    used and above which the series of M terms, and the bound ``err`` of the stresses (p* units)
    either way."""

    def __init__(self, table, dr, n, rtol):
        self.table = table
        a, N, K = table.a, table.N, table.K
        R = a.size
        B, errB = _periodic.closed_coefficients(a, dr, n, N, bound=True)
        B = B[:, : table.D.shape[1]]
        errB = errB[:, : table.D.shape[1]]
        Kmax = B.shape[1]
        absB = np.abs(B)
        sumB = series.row_sum(absB)
        # |s_m| = (1/pi)|int p cos(m s) ds| <= (2a/pi) max|p|, max|p| <= sin(a/2) sum|B_j| (W39)
        beta = 2.0 * a / np.pi * np.sin(0.5 * a) * sumB
        tol = 0.5 * rtol
        # closed-form rounding bound as a function of depth (kernel units), (W39)
        j = np.arange(Kmax)

        def closed_bound(Z, pole):
            # B_j w^{-j-1} by j + 1 products ((j + 2) u of its size |B_j| e^{(j+1)Z}), times X (|X| <= 2,
            # a few u) and, for z G', by its weight j + 1 and by z/|1 - w e^{-+ia}| <= 1 + Z (W39); the poles
            # likewise; the coefficients' own errors errB carried by the largest power
            with np.errstate(over="ignore"):      # +inf at great depth: the closed form is not taken there
                grow = (j + 2.0) * (j + 3.0) * np.exp((j + 1.0) * Z[:, None])
                return 2.0 * _U * (1.0 + Z) * (series.row_dot(absB * grow, np.ones(Kmax))
                                                + series.row_dot(np.abs(pole) * grow, np.ones(Kmax))) \
                    + 2.0 * series.row_sum(errB) * (1.0 + Z) * np.exp(K * Z)

        # the principal part needs x_k up to K; the Taylor coefficients up to M + K + 1
        h = _sqrt1m_coefficients(2 * Kmax + 2)
        x, ex = _periodic.cosine_sums(a, h)
        pole = np.zeros((R, Kmax))                    # pole[:, k - 1] = f_{-k}
        for jj in range(Kmax):
            for k in range(1, jj + 2):                # f_{-k} = 1/4 sum_{j >= k - 1} B_j x_{j + 1 - k}
                pole[:, k - 1] += 0.25 * B[:, jj] * x[:, jj + 1 - k]
        # the switch: the largest depth at which the closed form's bound is within tol (bisection)
        lo, hi = np.zeros(R), np.full(R, 40.0)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            ok = closed_bound(mid, pole) <= tol
            lo, hi = np.where(ok, mid, lo), np.where(ok, hi, mid)
        # where even the surface misses tol (rtol near rounding), the switch balances the closed form's
        # bound against that of the longest series, so neither is used where the other is better
        cap = lambda Z: beta * np.exp(-MAX_SERIES * Z) * (1.0 + Z * MAX_SERIES) / (1.0 - np.exp(-Z)) ** 2
        blo, bhi = np.full(R, 1e-6), np.full(R, 40.0)
        for _ in range(60):
            mid = 0.5 * (blo + bhi)
            closer = closed_bound(mid, pole) <= cap(mid)
            blo, bhi = np.where(closer, mid, blo), np.where(closer, bhi, mid)
        Zs = np.where(lo > 0.0, np.maximum(lo, 1e-6), blo)
        q = np.exp(-Zs)
        # series length: truncation of Im G plus z |G'| at Z >= Zs (decreasing there once M Zs >= 1)
        M = np.full(R, MAX_SERIES)
        Mgrid = np.arange(1, MAX_SERIES + 1)[None, :]
        with np.errstate(under="ignore", over="ignore", invalid="ignore"):
            qM = q[:, None] ** Mgrid
            trunc = beta[:, None] * qM * (1.0 / (1.0 - q[:, None])
                                          + Zs[:, None] * (Mgrid * (1.0 - q[:, None]) + q[:, None])
                                          / (1.0 - q[:, None]) ** 2)
        good = (trunc <= 0.5 * tol) & (Mgrid * Zs[:, None] >= 1.0)
        M = np.where(good.any(axis=1), 1 + np.argmax(good, axis=1), MAX_SERIES)
        self.M = M
        Mmax = int(M.max())
        h = _sqrt1m_coefficients(Mmax + 2 * Kmax + 2)
        x, ex = _periodic.cosine_sums(a, h)
        s = np.zeros((R, Mmax))
        for jj in range(Kmax):                        # f_m = 1/4 sum_j B_j (x_{m-j} + x_{m+j+1})
            mm = np.arange(Mmax)
            lo_ok = mm - jj >= 0
            s[:, lo_ok] += 0.25 * B[:, jj:jj + 1] * x[:, (mm - jj)[lo_ok]]
            s += 0.25 * B[:, jj:jj + 1] * x[:, mm + jj + 1]
        s[:, 1:Kmax + 1] += pole[:, : min(Kmax, Mmax - 1)] if Mmax > Kmax else pole[:, : Mmax - 1]
        s[np.arange(Mmax)[None, :] >= M[:, None]] = 0.0
        self.s, self.pole, self.B = s, pole, B
        # the constant of the closed primitive (W46): kappa_n, the constant terms at w = 0 of the ladder
        # I_n = int X w^n dw, from those of I_0 and I_-1 and of the right sides w^m X^3 (W47)
        cosa = np.cos(a)
        q3 = x[:, : Kmax + 2].copy()                   # q_k = [w^k] X^3 = x_k - 2 c x_(k-1) + x_(k-2)
        q3[:, 1:] -= 2.0 * cosa[:, None] * x[:, : Kmax + 1]
        q3[:, 2:] += x[:, : Kmax]
        log1mc = np.log(2.0) + 2.0 * np.log(np.sin(0.5 * a))        # log(1 - cos a) without cancellation
        k0 = 0.5 * (-cosa + np.sin(a) ** 2 * log1mc)
        km1 = 1.0 - cosa * log1mc - np.log(2.0)
        rhs = lambda m: np.full(R, 1.0) if m == 0 else (q3[:, -m] if m < 0 else np.zeros(R))
        up, down = _ladder(k0, km1, cosa, Kmax - 2, Kmax + 1, rhs)
        self.const = 0.25 * sum(B[:, jj] * (_rung(up, down, jj - 1) + _rung(up, down, -jj - 2))
                                for jj in range(Kmax))
        # rounding of the series: coefficients (x_k bound ex, B_j bound errB, 2K + 4 operations) and
        # Horner's (m + 2) u per term, at the switch depth where it is largest
        xmax = np.max(np.abs(x), axis=1)
        ds = 0.5 * (sumB * np.max(ex, axis=1) + series.row_sum(errB) * xmax) + (2 * K + 4) * _U * sumB * xmax
        mm = np.arange(Mmax)[None, :]
        with np.errstate(under="ignore"):
            qm = q[:, None] ** mm
        series_round = series.row_dot((ds[:, None] + 4.0 * _U * np.abs(s) * (mm + 2.0))
                                      * qm * (1.0 + Zs[:, None] * mm), np.ones(Mmax))
        trunc_M = np.take_along_axis(np.concatenate([trunc, trunc[:, -1:]], axis=1), (M - 1)[:, None], 1)[:, 0]
        self.z_switch = Zs
        self.err = np.maximum(closed_bound(Zs, pole), trunc_M + series_round)
        self.converged = self.err <= rtol
        # the displacements' bounds (W48): below the switch the series' bound of the stresses covers Psi and
        # z_s G (its coefficients s_m/m, its weights z_s (M (1 - q) + q)/(1 - q) >= z_s); z G beyond the switch:
        # the truncation part falls with depth (M z_s >= 1), the mean term's rounding does not (per depth)
        self.err_series = trunc_M + series_round
        # s_0 = p_inf = 1/4 sum_j B_j (x_-j + x_(j+1)) (x_-j = 0 but x_0): its own bound, which the depth multiplies
        x01 = np.abs(x[:, 1:Kmax + 1]) + np.where(np.arange(Kmax) == 0, np.abs(x[:, :1]), 0.0)
        e01 = ex[:, 1:Kmax + 1] + np.where(np.arange(Kmax) == 0, ex[:, :1], 0.0)
        self.err_mean = 0.25 * series.row_sum(errB * x01 + absB * e01) \
            + (Kmax + 10) * _U * 0.25 * series.row_sum(absB * x01)
        self._absB, self._abspole, self._sumerrB, self._log1mc = absB, np.abs(pole), series.row_sum(errB), log1mc

    def evaluate(self, row, t, zt):
        """(G, dG/dt, err) at x/a = t, z/a = zt > 0 for table rows ``row`` (1-D arrays of one length);
        dG/dt is the derivative along x/a (user units)."""
        G, Gt, _, _ = self._routed(row, t, zt, self._closed, self._series)
        return G, Gt, self.err[row]

    def _routed(self, row, t, zt, closed, deep_route):
        """Two complex values per point, by ``closed`` above the switch depth and ``deep_route`` below it (each
        called as route(row, t, folded kernel x, kernel depth) for one row at a time: its coefficients are then
        scalars, not gathered per point); also the kernel depth and which points are deep."""
        a = self.table.a[row]
        Xk, Z = _folded(t, a), a * zt
        deep = Z > self.z_switch[row]
        first = np.empty(t.shape, complex)
        second = np.empty(t.shape, complex)
        for r in np.unique(row):
            one = row == r
            for sel, route in ((one & ~deep, closed), (one & deep, deep_route)):
                if sel.any():
                    first[sel], second[sel] = route(int(r), t[sel], Xk[sel], Z[sel])
        return first, second, Z, deep

    def _closed(self, row, t, X, Z):
        """The closed finite form near the surface (W37): S = X T/4 - sum_k f_{-k} (w^{-k} - w^k), one row."""
        a = self.table.a[row]
        d1, d2, Xr, w, wi = _disk(t, X, Z, a)
        T = np.zeros(t.shape, complex)
        wT = np.zeros(t.shape, complex)         # w T'(w)
        Pole = np.zeros(t.shape, complex)
        wPole = np.zeros(t.shape, complex)      # w d/dw of the pole part
        wj, wij = np.ones(t.shape, complex), wi.copy()       # w^j, w^{-j-1}
        for j in range(int(self.table.K[row])):
            b = self.B[row, j]
            f = self.pole[row, j]               # f_{-(j+1)}
            T += b * (wj + wij)
            wT += b * (j * wj - (j + 1) * wij)
            wk = wj * w                         # w^{j+1}
            Pole += f * (wij - wk)
            wPole += f * (-(j + 1)) * (wij + wk)
            wj, wij = wk, wij * wi
        # w X'/X = -(1/2) [w e^{-ia}/(1 - w e^{-ia}) + w e^{ia}/(1 - w e^{ia})]
        we1 = 1.0 - d1
        we2 = 1.0 - d2
        wXp = -0.5 * Xr * (we1 / d1 + we2 / d2)
        S = 0.25 * Xr * T - Pole
        wS = 0.25 * (wXp * T + Xr * wT) - wPole
        return -1j * S, a * wS

    def primitive(self, row, t, zt):
        """(Psi, G, err) at x/a = t, z/a = zt >= 0 for table rows ``row``: the primitive of G in kernel units,
        Psi = -i p_inf zeta - sum_(m >= 1) s_m w^m/m, docs/theory/wavy.md (W46) (zeta with the unfolded x: the
        mean pressure's term is not periodic), the potential G, and a bound of Psi's error plus z times G's
        (kernel units), i.e. of both displacement components (W48).  Near the surface the closed primitive
        of X T/(4 w) by the ladder (W47); at depth the series of the same length as the stresses'."""
        Psi, G, Z, deep = self._routed(row, t, zt, self._closed_primitive, self._series_primitive)
        xu = self.table.a[row] * t
        # the bound of Psi and z G (W48): the closed form's at the point's depth, or the series' at the switch;
        # the unfolded mean-pressure term's rounding, 2 u p_inf |zeta|, and that of s_0 times the depth
        err = np.where(deep, self.err_series[row], self.closed_primitive_bound(row, Z)) \
            + Z * self.err_mean[row] + 2.0 * _U * np.abs(self.s[row, 0]) * np.hypot(xu, Z)
        return Psi, G, err

    def closed_primitive_bound(self, row, Z):
        """Bound of Psi's and z G's rounding by the closed form at depth Z (kernel units) for rows ``row``, (W48):
        e_Psi = 4 u sum_j (|B_j| + |f_-(j+1)|) (j + 2) e^((j+1) Z) + 8 u sum_j |B_j| (|log(1 - cos a)| + K + 3)
        + 2 sum_j e(B_j) (e^(K Z) + |log(1 - cos a)| + 2) (the ladder's rung I_-(j+2), of size up to e^((j+1) Z),
        is j + 2 steps from I_0, I_-1, each adding a few u of it; the logarithms and the constant; the
        coefficients' own errors), and z e_G with e_G = 2 u sum_j (|B_j| + |f_-(j+1)|)(j + 2) e^((j+1) Z)
        + 2 sum_j e(B_j) e^(K Z).  A model, not a worst case (the ladder's error modes oscillate): measured against
        a long series at depth and the surface displacement (W15) at z = 0, 28 cases, 1 to 11 harmonics,
        2a/lambda_1 = 1e-3 .. 0.999, max |error|/bound = 0.05 (docs/theory/wavy.md (W48))."""
        K = self._absB.shape[1]
        j = np.arange(K)
        with np.errstate(over="ignore"):
            grow = np.exp((j + 1.0) * Z[:, None])
            size = (self._absB[row] + self._abspole[row]) * grow
            eK = np.exp(self.table.K[row] * Z)
            logs = np.abs(self._log1mc[row])
            e_psi = 4.0 * _U * np.sum(size * (j + 2.0), axis=1) \
                + 8.0 * _U * np.sum(self._absB[row], axis=1) * (logs + self.table.K[row] + 3.0) \
                + 2.0 * self._sumerrB[row] * (eK + logs + 2.0)
            e_g = 2.0 * _U * np.sum(size * (j + 2.0), axis=1) + 2.0 * self._sumerrB[row] * eK
        return e_psi + Z * e_g

    def _closed_primitive(self, row, t, X, Z):
        """The closed primitive near the surface (W46), (W47), one row: with S = X T/4 - sum_k f_-k (w^-k - w^k),
        Psi = -(1/4) sum_j B_j (I_(j-1) + I_(-j-2)) - sum_k f_-k (w^-k + w^k)/k + const,
        I_0 = (u X + s^2 L_1)/2, I_-1 = X - c L_1 - L_2 + log w, u = w - c, L_1 = log(u + X),
        L_2 = log(1 - c w + X) (c = cos a, s = sin a), log w = -z + i x with the unfolded x."""
        a = float(self.table.a[row])
        c, sa = np.cos(a), np.sin(a)
        xu = self.table.a[row] * t                # the unfolded x (kernel units)
        d1, d2, Xr, w, wi = _disk(t, X, Z, a, consistent=True)
        # u = w - c and 1 - c w from the factors, accurate relative to themselves: next to an edge both are
        # small (c near +-1), and w - c would carry the rounding of w and c, amplified by 1/|u + X| in L_1
        u = -0.5 * ((c + 1j * sa) * d1 + (c - 1j * sa) * d2)
        one_cw = 0.5 * (d1 + d2)
        # L_1 = log(u + X): where Re u <= 0 as log(s^2/(X - u)) (Re X > 0 in the disk, so X - u has no
        # cancellation); u + X is never real and negative in the disk, so the principal log has no cut there
        left = u.real <= 0.0
        L1 = np.where(left, 2.0 * np.log(sa) - np.log(np.where(left, Xr - u, 1.0)),
                      np.log(np.where(left, 1.0, u + Xr)))
        L2 = np.log(one_cw + Xr)                  # Re(1 - c w) > 0 and Re X > 0: no cut in the disk
        logw = -Z + 1j * xu
        QX = d1 * d2 * Xr
        I0 = 0.5 * (u * Xr + sa * sa * L1)
        Im1 = Xr - c * L1 - L2 + logw
        K = int(self.table.K[row])

        def rhs(m):                               # w^m X^3
            return QX * (w ** m if m >= 0 else wi ** (-m))

        up, down = _ladder(I0, Im1, c, K - 2, K + 1, rhs)
        Psi = np.full(t.shape, self.const[row], complex)
        wj, wij = w.copy(), wi.copy()             # w^k, w^-k for k = j + 1
        for j in range(K):
            Psi -= 0.25 * self.B[row, j] * (_rung(up, down, j - 1) + _rung(up, down, -j - 2))
            Psi -= self.pole[row, j] * (wij + wj) / (j + 1.0)
            wj, wij = wj * w, wij * wi
        G, _ = self._closed(row, t, X, Z)
        return Psi, G

    def _series_primitive(self, row, t, X, Z):
        """The series of the primitive at depth (W46), Horner in w, one row."""
        xu = self.table.a[row] * t
        w = np.exp(-Z) * (np.cos(X) + 1j * np.sin(X))
        acc = np.zeros(X.shape, complex)
        for m in range(int(self.M[row]) - 1, 0, -1):
            acc = (acc + self.s[row, m] / m) * w
        Psi = -1j * self.s[row, 0] * (xu + 1j * Z) - acc
        G, _ = self._series(row, t, X, Z)
        return Psi, G

    def _series(self, row, t, X, Z):
        """The Taylor series of S at depth (W39), Horner in w, one row."""
        a = self.table.a[row]
        w = np.exp(-Z) * (np.cos(X) + 1j * np.sin(X))
        S = np.zeros(X.shape, complex)
        wS = np.zeros(X.shape, complex)
        for m in range(int(self.M[row]) - 1, -1, -1):
            c = self.s[row, m]
            S = S * w + c
            wS = wS * w + m * c
        return -1j * S, a * wS


def _disk(t, X, Z, a, consistent=False):
    """The factors of X at the points (x/a = t, folded kernel x X, kernel depth Z) of one row:
    (1 - w e^{-ia}, 1 - w e^{ia}, X, w, 1/w), X = sqrt(1 - w e^{-ia}) sqrt(1 - w e^{ia}) with principal roots (the
    cuts run outward from e^{+-ia}), each factor written without cancellation next to its edge.  ``consistent``:
    both angles x -+ a from the one rounded x (X - a is exact where it is small, Sterbenz), taken into
    (-pi, pi] with pi in two parts, ((X + pi_hi) + (pi_hi - a)) + 2 pi_lo, whose first two differences are
    exact: the two factors then belong to the same point to a few ulps of themselves, which the closed
    primitive needs where a is near pi (it pairs log(u + X) with log(1 - c w + X), and factors of two
    different points would differ by the rounding of x over sin a)."""
    if consistent:
        vm, vp = X - a, X + a
        vm = np.where(vm < -np.pi, ((X + _PI_HI) + (_PI_HI - a)) + 2.0 * _PI_LO, vm)
        vp = np.where(vp > np.pi, ((X - _PI_HI) + (a - _PI_HI)) - 2.0 * _PI_LO, vp)
    else:
        far = np.abs(t * a) > np.pi       # folded points: v = X -+ a from the folded X
        vm = np.where(far, X - a, a * (t - 1.0))
        vp = np.where(far, X + a, a * (t + 1.0))
    em = np.expm1(-Z)
    ez = np.exp(-Z)
    # 1 - w e^{-+ia} = -(e^{-Z + i v} - 1), written without cancellation next to the edges
    d1 = -(em * np.cos(vm) - 2.0 * np.sin(0.5 * vm) ** 2 + 1j * ez * np.sin(vm))
    d2 = -(em * np.cos(vp) - 2.0 * np.sin(0.5 * vp) ** 2 + 1j * ez * np.sin(vp))
    Xr = np.sqrt(d1) * np.sqrt(d2)
    w = ez * (np.cos(X) + 1j * np.sin(X))
    wi = np.exp(Z) * (np.cos(X) - 1j * np.sin(X))
    return d1, d2, Xr, w, wi


def _ladder(I0, Im1, c, top, bottom, rhs):
    """The ladder of primitives I_n = int X w^n dw, X^2 = Q = 1 - 2 c w + w^2, docs/theory/wavy.md (W47): from
    d(w^m X^3)/dw = X [(m + 3) w^(m+1) - (2m + 3) c w^m + m w^(m-1)],

        (m + 3) I_(m+1) - (2m + 3) c I_m + m I_(m-1) = rhs(m)  (= w^m X^3, or its constant term at w = 0),

    upward from I_0 to I_top and downward from I_0, I_-1 to I_-bottom.  Both directions are stable: the
    homogeneous solutions shrink like |m|^(-3/2) (the product of the characteristic roots is m/(m + 3) upward,
    (|m| - 3)/|m| downward).  Returns ([I_0 .. I_top], [I_-1 .. I_-bottom])."""
    up, down = [I0], [Im1]
    prev = None
    for m in range(0, top):
        nxt = (rhs(m) + (2 * m + 3) * c * up[m]) / (m + 3.0)
        if m:
            nxt = nxt - m * up[m - 1] / (m + 3.0)
        up.append(nxt)
    prev, cur = I0, Im1                       # I_(m+1), I_m for m = -1
    for m in range(-1, -bottom, -1):
        nxt = (rhs(m) + (2 * m + 3) * c * cur - (m + 3) * prev) / m
        down.append(nxt)
        prev, cur = cur, nxt
    return up, down


def _rung(up, down, n):
    """I_n of a ladder (``_ladder``'s two lists)."""
    return up[n] if n >= 0 else down[-n - 1]


def _folded(t, a):
    """x in kernel units folded into one period where |x| > pi (as ``contact._reduced``), signed."""
    X = t * a
    k = np.round(X / (2.0 * np.pi))
    return np.where(np.abs(X) > np.pi, X - k * (2.0 * np.pi), X)


def nonperiodic_potential(table, row, t, zt):
    """(G, dG/dt, err_G, err_zG') of the single indenter at x/a = t, z/a = zt > 0, (W38):
    G = sum_m D_m omega^(2m + 1), dG/dt = -(1/r) sum_m (2m + 1) D_m omega^(2m + 1), r = sqrt(Z - 1) sqrt(Z + 1)
    (factorised principal roots: no cut in the body), omega = 1/(Z + r) (no cancellation as |Z| grows).
    Errors: the surface series' bounds, since |omega| <= 1 and z/|r| <= 1."""
    Z1 = (t - 1.0) + 1j * zt
    Z2 = (t + 1.0) + 1j * zt
    r = np.sqrt(Z1) * np.sqrt(Z2)
    om = 1.0 / ((t + 1j * zt) + r)
    om2 = om * om
    G = np.zeros(t.shape, complex)
    Gw = np.zeros(t.shape, complex)
    for one in np.unique(row):                # one row at a time: scalar coefficients, its own length
        sel = row == one
        g, gw, o2 = np.zeros(sel.sum(), complex), np.zeros(sel.sum(), complex), om2[sel]
        for m in range(int(table.K[one]) - 1, -1, -1):
            c = table.D[one, m]
            g = g * o2 + c
            gw = gw * o2 + (2.0 * m + 1.0) * c
        G[sel], Gw[sel] = g, gw
    return G * om, -(Gw * om) / r, table.err[row], table.err_shape[row]


def normal_stresses(G, Gt, zt):
    """sigma_xx, sigma_zz, sigma_xz of the normal pressure from its potential (W36)."""
    E = zt * Gt
    return G.imag + E.real, G.imag - E.real, -E.imag


def shear_stresses(H, Ht, zt):
    """sigma_xx, sigma_zz, sigma_xz of a shear traction q (along +x on the body) from its potential
    H = (1/pi) int q/(zeta - s) ds, (W41)."""
    E = zt * Ht
    return -2.0 * H.real + E.imag, -E.imag, H.imag + E.real


def plane_strain_invariants(sxx, szz, sxz, nu):
    """sigma_yy = nu (sigma_xx + sigma_zz) and, from the in-plane principal stresses
    c +- hypot((sxx - szz)/2, sxz) and sigma_yy: sigma_1 >= sigma_2 >= sigma_3, tau_max = (sigma_1 - sigma_3)/2
    and von Mises sqrt(3 J2) (docs/theory/wavy.md (W36))."""
    syy = nu * (sxx + szz)
    c = 0.5 * (sxx + szz)
    R = np.hypot(0.5 * (sxx - szz), sxz)
    hi, lo = c + R, c - R
    s1 = np.maximum(hi, syy)
    s3 = np.minimum(lo, syy)
    s2 = np.maximum(np.minimum(hi, syy), lo)
    vm = np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxz * sxz)
    return syy, s1, s2, s3, 0.5 * (s1 - s3), vm


def nonperiodic_primitive(table, row, t, zt, a):
    """(Psi, err_Psi) of the single indenter at x/a = t, z/a = zt >= 0: the primitive of G in kernel units,
    Psi(zeta) = (1/pi) int p(s) [log(zeta - s) - i pi/2] ds, docs/theory/wavy.md (W45).

    With Z = zeta/a = (omega + 1/omega)/2, dZ = (1 - omega^-2) d omega/2, so
    int omega^n dZ = I_n = [omega^(n+1)/(n+1) - omega^(n-1)/(n-1)]/2 (n >= 3), I_1 = [omega^2/2 + log(Z + r)]/2,
    and Psi = a sum_m D_m I_(2m+1) - (a D_0/2) log(2/a) - i pi a D_0/4: the constant makes Psi - (P/pi) log zeta
    vanish at infinity (P = pi a D_0/2, the load in kernel units: the log datum of (W15)) and the imaginary
    one makes Im Psi odd in x. log(Z + r) is principal: Z + r = 1/omega lies in the upper half-plane.
    Error: |I_n| <= 1/2 for n >= 3 (|omega| <= 1), so the series tail bound of G, times a/2, plus rounding of
    a few ulps of the largest term."""
    Z1 = (t - 1.0) + 1j * zt
    Z2 = (t + 1.0) + 1j * zt
    r = np.sqrt(Z1) * np.sqrt(Z2)
    inv = (t + 1j * zt) + r                   # 1/omega, no cancellation in the upper half-plane
    om = 1.0 / inv
    om2 = om * om
    Psi = np.zeros(t.shape, complex)
    for one in np.unique(row):                # one row at a time: scalar coefficients, its own length
        sel = row == one
        o2 = om2[sel]
        # sum_{m >= 1} D_m/2 [o2^(m+1)/(2m+2) - o2^m/(2m)] = o2/2 sum_{m >= 1} D_m o2^(m-1) [o2/(2m+2) - 1/(2m)]
        acc = np.zeros(sel.sum(), complex)
        for m in range(int(table.K[one]) - 1, 0, -1):
            c = table.D[one, m]
            acc = acc * o2 + c * (o2 / (2.0 * m + 2.0) - 1.0 / (2.0 * m))
        D0 = table.D[one, 0]
        Psi[sel] = 0.5 * o2 * acc + 0.5 * D0 * (0.5 * o2 + np.log(inv[sel]))
    D0 = table.D[row, 0]
    Psi = a * Psi - 0.5 * a * D0 * np.log(2.0 / a) - 0.25j * np.pi * a * D0
    sumD = np.sum(np.abs(table.D), axis=1)[row]
    rounding = 8.0 * _U * a * (sumD * (1.0 + table.K[row]) + np.abs(D0) * (np.abs(np.log(np.abs(inv)))
                                                                           + abs(np.log(2.0 / a)) + np.pi))
    return Psi, 0.5 * a * table.err[row] + rounding


def normal_displacements(Psi, G, zk, nu):
    """u_x/Delta_1, u_z/Delta_1 of the normal pressure from its potential G and primitive Psi (kernel units,
    p in p* = E* Delta_1/2 units, zk the depth in kernel units), docs/theory/wavy.md (W45):
    2 mu u_x = (1 - 2 nu) Im Psi + z Re G,  2 mu u_z = -2 (1 - nu) Re Psi - z Im G,  2 mu = E* (1 - nu)."""
    k = 0.5 / (1.0 - nu)
    return k * ((1.0 - 2.0 * nu) * Psi.imag + zk * G.real), -Psi.real - k * zk * G.imag


def shear_displacements(Phi, H, zk, nu):
    """u_x/Delta_1, u_z/Delta_1 of a shear traction q (along +x on the body) from its potential H and primitive
    Phi (units as ``normal_displacements``), docs/theory/wavy.md (W45):
    2 mu u_x = -2 (1 - nu) Re Phi + z Im H,  2 mu u_z = -(1 - 2 nu) Im Phi + z Re H."""
    k = 0.5 / (1.0 - nu)
    return -Phi.real + k * zk * H.imag, k * (-(1.0 - 2.0 * nu) * Phi.imag + zk * H.real)
