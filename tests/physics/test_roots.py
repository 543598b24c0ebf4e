"""The vectorised bisection against closed-form roots."""
import numpy as np

from stressfields.physics.roots import bisect


def test_bisection_finds_each_elements_root():
    target = np.array([0.0, 0.1, 0.5, 0.999, 1.0])
    x = bisect(lambda s: s ** 3 < target, 0.0, 1.0, 60)
    assert np.allclose(x, np.cbrt(target), rtol=4e-16, atol=1e-18)   # 2^-60 bracket, cube rounding


def test_geometric_bisection_spans_decades():
    target = np.array([1e-9, 1e-3, 1.0, 1e5])
    x = bisect(lambda s: np.log(s) < np.log(target), 1e-12, 1e8, 64, geometric=True)
    assert np.allclose(x, target, rtol=1e-14, atol=0)


def test_decreasing_functions_take_the_negated_test():
    c = bisect(lambda s: 1.0 - s ** 2 > 0.75, np.zeros(3), np.ones(3), 56)
    assert np.allclose(c, 0.5, rtol=0, atol=1e-15)
