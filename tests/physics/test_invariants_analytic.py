"""The analytic principal stresses (trigonometric root + 2 x 2 deflation) against LAPACK's eigvalsh
(backward stable: its eigenvalues are within a few ulps of the Frobenius norm of the exact ones)
and against tensors built from known eigenvalues, Q diag(l) Q^T with a random orthogonal Q (the
rounding of the product moves the eigenvalues by a few ulps of the norm, Weyl's inequality).

Bound: every eigenvalue within 1e-13 of the tensor's Frobenius norm, on random tensors and on the
families where the trigonometric formula alone loses digits: repeated eigenvalues, near-repeated
ones (off-diagonal 1e-8), a huge dynamic range, one huge component, a large mean stress."""
import functools

import numpy as np
import pytest

from stressfields.physics.invariants import principal_stresses, von_mises

BOUND = 1e-13
RNG = np.random.default_rng(20261125)


def _components(m):
    """(n, 3, 3) -> the six components xx, yy, zz, xy, xz, yz."""
    return m[:, 0, 0], m[:, 1, 1], m[:, 2, 2], m[:, 0, 1], m[:, 0, 2], m[:, 1, 2]


def _symmetric(comps):
    xx, yy, zz, xy, xz, yz = comps
    return np.stack([np.stack([xx, xy, xz], -1), np.stack([xy, yy, yz], -1), np.stack([xz, yz, zz], -1)], -2)


def _rotations(n):
    q, r = np.linalg.qr(RNG.standard_normal((n, 3, 3)))
    return q * np.sign(np.diagonal(r, axis1=1, axis2=2))[:, None, :]


def _from_eigenvalues(lam):
    """Q diag(lam) Q^T, symmetrised exactly (components taken from the upper triangle)."""
    q = _rotations(lam.shape[0])
    return _symmetric(_components(np.einsum("nij,nj,nkj->nik", q, lam, q)))


def _worst(m, expected=None):
    """Worst |error| / Frobenius norm against eigvalsh (and ``expected``, descending), and the
    computed eigenvalues (n, 3)."""
    got = np.stack(principal_stresses(*_components(m)), axis=1)
    big = np.max(np.abs(m.reshape(-1, 9)), axis=1)      # the norm without under/overflow
    norm = big * np.linalg.norm(m.reshape(-1, 9) / big[:, None], axis=1)
    refs = [np.linalg.eigvalsh(m)[:, ::-1]] + ([] if expected is None else [np.sort(expected, axis=1)[:, ::-1]])
    return max(float(np.max(np.abs(got - ref).max(axis=1) / norm)) for ref in refs), got


@functools.lru_cache(maxsize=None)
def _families(n):
    """name -> (tensors (n, 3, 3), exact eigenvalues or None)."""
    one = np.ones(n)
    a, b = RNG.standard_normal(n), RNG.standard_normal(n)
    diag = RNG.standard_normal((n, 3))
    tiny = 1e-8 * RNG.standard_normal((n, 3))
    spread = np.sign(RNG.standard_normal((n, 3))) * 10.0 ** RNG.uniform(-12.0, 0.0, (n, 3))
    huge = RNG.standard_normal((n, 6))
    huge[:, 0] = 1e8 * np.sign(huge[:, 0])
    two = np.stack([a, a, b], 1)
    near = np.stack([a, a + 1e-8 * b, b], 1)
    return {
        "random": (_symmetric(RNG.standard_normal((6, n))), None),
        "diagonal": (_symmetric([*diag.T, 0 * one, 0 * one, 0 * one]), diag),
        "two equal": (_from_eigenvalues(two), two),
        "two equal, unrotated": (_symmetric([a, a, b, 0 * one, 0 * one, 0 * one]), two),
        "three equal": (_from_eigenvalues(np.stack([a, a, a], 1)), np.stack([a, a, a], 1)),
        "equal plus 1e-8 off-diagonal": (_symmetric([a, a, a, *tiny.T]), None),
        "near-repeated by 1e-8": (_from_eigenvalues(near), near),
        "dynamic range 1e-12..1": (_from_eigenvalues(spread), spread),
        "one huge component": (_symmetric(huge.T), None),
        "large mean stress": (_from_eigenvalues(1e6 + RNG.standard_normal((n, 3))), None),
        "pure shear": (_symmetric([0 * one, 0 * one, 0 * one, a, 0 * one, 0 * one]), np.stack([a, 0 * one, -a], 1)),
    }


def test_random_tensors_one_million():
    worst, got = _worst(_symmetric(RNG.standard_normal((6, 1_000_000))))
    assert worst <= BOUND, worst
    assert np.all(got[:, 0] >= got[:, 1]) and np.all(got[:, 1] >= got[:, 2])


@pytest.mark.parametrize("name", list(_families(2)))
def test_degenerate_families(name):
    m, exact = _families(100_000)[name]
    worst, got = _worst(m, exact)
    assert worst <= BOUND, (name, worst)
    assert np.all(got[:, 0] >= got[:, 1]) and np.all(got[:, 1] >= got[:, 2]), name


def test_scales_without_overflow_or_underflow():
    m = _symmetric(RNG.standard_normal((6, 10_000)))
    for scale in (1e-300, 1e-150, 1e150, 1e300):
        worst, _ = _worst(m * scale)
        assert worst <= BOUND, (scale, worst)


def test_invariants_trace_j2_and_rotation():
    """Trace = s1 + s2 + s3, 3 J2 (von Mises squared) from the principal values, and the same
    eigenvalues for Q A Q^T, all to 1e-13 of the norm."""
    m = _symmetric(RNG.standard_normal((6, 100_000)))
    norm = np.linalg.norm(m.reshape(-1, 9), axis=1)
    s1, s2, s3 = principal_stresses(*_components(m))
    trace = np.trace(m, axis1=1, axis2=2)
    assert np.max(np.abs(s1 + s2 + s3 - trace) / norm) <= BOUND
    vm = von_mises(*_components(m))
    vm_p = np.sqrt(0.5 * ((s1 - s2) ** 2 + (s2 - s3) ** 2 + (s3 - s1) ** 2))
    assert np.max(np.abs(vm - vm_p) / norm) <= BOUND
    q = _rotations(m.shape[0])
    rotated = _symmetric(_components(q @ m @ q.transpose(0, 2, 1)))
    r1, r2, r3 = principal_stresses(*_components(rotated))
    assert np.max(np.abs(np.stack([r1 - s1, r2 - s2, r3 - s3])) / norm) <= BOUND


def test_exact_values():
    # hydrostatic, uniaxial, zero
    assert [float(v) for v in principal_stresses(-3.0, -3.0, -3.0, 0, 0, 0)] == [-3.0, -3.0, -3.0]
    assert [float(v) for v in principal_stresses(0.0, 0.0, 0.0, 0, 0, 0)] == [0.0, 0.0, 0.0]
    s = [float(v) for v in principal_stresses(0.0, 2.0, 0.0, 0, 0, 0)]
    assert s == pytest.approx([2.0, 0.0, 0.0], abs=4e-16)
    # a principal axis along x, y or z (its two shears exactly 0, as on the surface outside the
    # contact): the zero normal stress stays an exact 0 as in LAPACK, in any units
    rng = np.random.default_rng(3)
    sxx, syy, sxy = rng.standard_normal((3, 1000))
    for unit in (1.0, 0.3, 5.1e11):
        s1, s2, s3 = principal_stresses(sxx * unit, -sxx * unit, 0.0, 0.0, 0.0, 0.0)
        assert np.all(s2 == 0.0) and np.all(s1 == np.abs(sxx * unit))
        for comps in ((0.0, sxx, syy, 0.0, 0.0, sxy), (sxx, 0.0, syy, 0.0, sxy, 0.0),
                      (sxx, syy, 0.0, sxy, 0.0, 0.0)):
            out = np.stack(principal_stresses(*(np.asarray(c) * unit for c in comps)))
            assert np.all(np.any(out == 0.0, axis=0)), (unit, comps)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_nonfinite_component_gives_nan(bad):
    for k in range(6):
        comps = [np.array([1.0, 0.5]) for _ in range(6)]
        comps[k] = np.array([bad, 0.5])
        out = principal_stresses(*comps)
        assert all(np.isnan(o[0]) and np.isfinite(o[1]) for o in out), (k, bad)
