"""Second-order jets in two variables: exact first and second derivatives of surface code.

A `Jet` carries a value and its derivatives with respect to the surface parameters (u, v):
f, f_u, f_v, f_uu, f_uv, f_vv, each a numpy array. Surface formulas are written once with
plain numpy functions (np.sin, np.sqrt, np.arctan2, ...); evaluated on jets they return the
point together with its exact derivatives (forward-mode automatic differentiation, truncated
after the second order), so no derivative is ever typed twice or approximated by differences.
"""

from __future__ import annotations

import numpy as np

_FIELDS = ("f", "u", "v", "uu", "uv", "vv")


class Jet:
    """f(u, v) with its first and second partial derivatives (numpy arrays, broadcastable)."""

    __slots__ = _FIELDS
    __array_priority__ = 100

    def __init__(self, f, u=0.0, v=0.0, uu=0.0, uv=0.0, vv=0.0):
        self.f, self.u, self.v, self.uu, self.uv, self.vv = (
            np.asarray(x, dtype=float) for x in (f, u, v, uu, uv, vv))

    @classmethod
    def variables(cls, u, v, order: int = 2) -> tuple[Jet, Jet]:
        """The surface parameters themselves: u (du/du = 1) and v (dv/dv = 1). With order 1
        the second derivatives are not carried (None): about half the work, for searches
        that need only tangents."""
        u, v = np.broadcast_arrays(np.asarray(u, float), np.asarray(v, float))
        # constant derivatives as 0-d arrays: they broadcast, and cost nothing to multiply
        zero, one = np.array(0.0), np.array(1.0)
        second = (zero, zero, zero) if order == 2 else (None, None, None)
        return _new(u, one, zero, *second), _new(v, zero, one, *second)

    @property
    def first_order(self) -> bool:
        return self.uu is None

    # --- composition with a scalar function: phi(f) given phi, phi', phi'' at f ---------
    def _chain(self, p0, p1, p2) -> Jet:
        if self.uu is None:
            return _new(p0, p1 * self.u, p1 * self.v, None, None, None)
        return _new(p0, p1 * self.u, p1 * self.v, p2 * self.u * self.u + p1 * self.uu,
                    p2 * self.u * self.v + p1 * self.uv, p2 * self.v * self.v + p1 * self.vv)

    # --- arithmetic (a plain number or array operand is a constant: cheaper rules) --------
    def __add__(self, other):
        if not isinstance(other, Jet):
            return _new(self.f + other, self.u, self.v, self.uu, self.uv, self.vv)
        if self.uu is None or other.uu is None:
            return _new(self.f + other.f, self.u + other.u, self.v + other.v, None, None, None)
        return _new(self.f + other.f, self.u + other.u, self.v + other.v, self.uu + other.uu,
                    self.uv + other.uv, self.vv + other.vv)

    __radd__ = __add__

    def __neg__(self):
        if self.uu is None:
            return _new(-self.f, -self.u, -self.v, None, None, None)
        return _new(-self.f, -self.u, -self.v, -self.uu, -self.uv, -self.vv)

    def __sub__(self, other):
        return self + (-other)

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, other):
        if not isinstance(other, Jet):
            c = other
            if self.uu is None:
                return _new(self.f * c, self.u * c, self.v * c, None, None, None)
            return _new(self.f * c, self.u * c, self.v * c, self.uu * c, self.uv * c, self.vv * c)
        o = other
        if self.uu is None or o.uu is None:
            return _new(self.f * o.f, self.u * o.f + self.f * o.u, self.v * o.f + self.f * o.v,
                        None, None, None)
        return _new(self.f * o.f, self.u * o.f + self.f * o.u, self.v * o.f + self.f * o.v,
                    self.uu * o.f + 2 * self.u * o.u + self.f * o.uu,
                    self.uv * o.f + self.u * o.v + self.v * o.u + self.f * o.uv,
                    self.vv * o.f + 2 * self.v * o.v + self.f * o.vv)

    __rmul__ = __mul__

    def reciprocal(self) -> Jet:
        r = 1.0 / self.f
        return self._chain(r, -r * r, 2 * r * r * r)

    def __truediv__(self, other):
        if not isinstance(other, Jet):
            return self * (1.0 / np.asarray(other, float))
        return self * other.reciprocal()

    def __rtruediv__(self, other):
        return _lift(other) * self.reciprocal()

    def __pow__(self, exponent: float):
        if isinstance(exponent, Jet):
            return np.exp(exponent * np.log(self))
        p = float(exponent)
        return self._chain(self.f**p, p * self.f ** (p - 1), p * (p - 1) * self.f ** (p - 2))

    def cos_sin(self) -> tuple[Jet, Jet]:
        c, s = np.cos(self.f), np.sin(self.f)
        return _sin_cos(self, c, -s), _sin_cos(self, s, c)

    # --- numpy functions on jets ----------------------------------------------------------
    def __array_ufunc__(self, ufunc, method, *inputs, **kwargs):
        return dispatch_ufunc(ufunc, method, inputs, kwargs, _UNARY, _BINARY, _lift)


def dispatch_ufunc(ufunc, method, inputs, kwargs, unary: dict, binary: dict, lift):
    """numpy's ufunc protocol for a Taylor-number class: plain calls of the ufuncs in its
    `unary` and `binary` tables, operands lifted to the class; anything else declined."""
    if method != "__call__" or kwargs:
        return NotImplemented
    if ufunc in binary:
        return binary[ufunc](*(lift(x) for x in inputs))
    if ufunc in unary:
        return unary[ufunc](lift(inputs[0]))
    return NotImplemented


def _lift(x) -> Jet:
    return x if isinstance(x, Jet) else Jet(x)


def _new(f, u, v, uu, uv, vv) -> Jet:
    """A jet from arrays already computed (no conversion: the hot path of every operation)."""
    jet = object.__new__(Jet)
    jet.f, jet.u, jet.v, jet.uu, jet.uv, jet.vv = f, u, v, uu, uv, vv
    return jet


def _arctan2(y: Jet, x: Jet) -> Jet:
    if y.uu is None or x.uu is None:
        r2 = x.f * x.f + y.f * y.f
        return _new(np.arctan2(y.f, x.f), (x.f * y.u - y.f * x.u) / r2,
                    (x.f * y.v - y.f * x.v) / r2, None, None, None)
    r2 = x * x + y * y
    # d atan2 = (x dy - y dx)/r², built from jets so the second derivatives follow
    du = (x * Jet(y.u, y.uu, y.uv) - y * Jet(x.u, x.uu, x.uv)) / r2
    dv = (x * Jet(y.v, y.uv, y.vv) - y * Jet(x.v, x.uv, x.vv)) / r2
    return Jet(np.arctan2(y.f, x.f), du.f, dv.f, du.u, du.v, dv.v)


def _sin_cos(a: Jet, value, slope) -> Jet:
    """sin or cos of a jet from its value and slope (the curvature is -value)."""
    return a._chain(value, slope, None if a.uu is None else -value)


def cos_sin(a):
    """(cos a, sin a) of a plain array or a Taylor number (a class with a `cos_sin` method),
    each transcendental evaluated once."""
    own = getattr(a, "cos_sin", None)
    return own() if own is not None else (np.cos(a), np.sin(a))


_UNARY = {
    np.negative: lambda a: -a,
    np.sin: lambda a: a.cos_sin()[1],
    np.cos: lambda a: a.cos_sin()[0],
    np.tan: lambda a: a._chain(np.tan(a.f), 1 + np.tan(a.f) ** 2,
                               2 * np.tan(a.f) * (1 + np.tan(a.f) ** 2)),
    np.arctan: lambda a: a._chain(np.arctan(a.f), 1 / (1 + a.f**2), -2 * a.f / (1 + a.f**2) ** 2),
    np.arcsin: lambda a: a._chain(np.arcsin(a.f), (1 - a.f**2) ** -0.5, a.f * (1 - a.f**2) ** -1.5),
    np.arccos: lambda a: a._chain(np.arccos(a.f), -(1 - a.f**2) ** -0.5, -a.f * (1 - a.f**2) ** -1.5),
    np.sqrt: lambda a: a._chain(np.sqrt(a.f), 0.5 / np.sqrt(a.f), -0.25 * a.f ** -1.5),
    np.exp: lambda a: a._chain(np.exp(a.f), np.exp(a.f), np.exp(a.f)),
    np.log: lambda a: a._chain(np.log(a.f), 1 / a.f, -1 / a.f**2),
    np.square: lambda a: a * a,
}

#: the binary ufuncs any Taylor-number class maps onto its own operators
ARITHMETIC = {
    np.add: lambda a, b: a + b,
    np.subtract: lambda a, b: a - b,
    np.multiply: lambda a, b: a * b,
    np.true_divide: lambda a, b: a / b,
}

_BINARY = {**ARITHMETIC, np.arctan2: _arctan2}


def value(x):
    """The plain value of a jet, or x itself."""
    return x.f if isinstance(x, Jet) else np.asarray(x, float)


def where(condition, a, b):
    """np.where for jets: picks value and derivatives together (plain arrays stay plain)."""
    if not isinstance(a, Jet) and not isinstance(b, Jet):
        return np.where(condition, a, b)
    a, b = _lift(a), _lift(b)
    fields = _FIELDS[:3] if a.uu is None or b.uu is None else _FIELDS
    picked = [np.where(condition, getattr(a, k), getattr(b, k)) for k in fields]
    return _new(*picked, *([None] * (6 - len(picked))))
