"""The three wear laws of POST_USURE as pure vectorised functions (theory §4).

Every function broadcasts its array arguments with numpy rules (for instance sector powers against
a column of durations), checks them (finite, non-negative) and returns a new array; nothing the
caller passed is modified. SI units: power [W], duration [s], volume [m³].
"""

from __future__ import annotations

import math
import warnings
from contextvars import ContextVar

import numpy as np

from fretwear._lazy import compiled_when_used
from fretwear.errors import InputError, LawWarning

#: Default EDF_MZ coefficients (theory §4; Code_Aster's COEF_USURE, COEF_B, COEF_N, COEF_S).
EDF_MZ_DEFAULTS = {
    "rate_coefficient": 1e-13,     # A [m³/(s·W^b)]
    "power_exponent": 1.2,         # b [1]
    "decay_constant": 2.44e-8,     # n [1/s]
    "asymptotic_rate": 1.14e-16,   # S [m³/s]
}

#: The LawWarnings of the law functions while a :class:`~fretwear.laws.WearLaw` method runs
#: (a list of messages, :func:`fretwear.laws.registry._warning_once` issues each once at its
#: caller's line); None otherwise: the functions warn themselves. A context variable, not
#: ``warnings.catch_warnings`` (which swaps the process's filters: a cost on every call and a
#: race between threads).
_collected: ContextVar[list[str] | None] = ContextVar("fretwear_law_warnings", default=None)


def _law_warning(message: str, stacklevel: int) -> None:
    """A LawWarning at ``stacklevel`` of the function calling this one, or kept in
    :data:`_collected` when a WearLaw method collects them."""
    kept = _collected.get()
    if kept is None:
        warnings.warn(message, LawWarning, stacklevel=stacklevel + 1)
    else:
        kept.append(message)


# Below this value of x = n·t the functions psi1, psi2 use their Taylor series.
_SERIES_LIMIT = 0.5
_SERIES_TERMS = 24


def _checked(name: str, value, *, positive: bool = False) -> np.ndarray:
    """``value`` as a float array, finite and >= 0 (> 0 if ``positive``), else InputError."""
    if type(value) is float and math.isfinite(value) and (value > 0 if positive else value >= 0):
        return np.asarray(value)  # a plain float in range: the array checks cost ~4 us each
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InputError(
            f"{name!r} must be a number or an array of numbers, got {value!r}") from None
    bad = ~np.isfinite(arr) | ((arr <= 0) if positive else (arr < 0))
    if bad.any():
        where = "" if arr.ndim == 0 else f" at index {tuple(int(i) for i in np.argwhere(bad)[0])}"
        bound = "> 0" if positive else ">= 0"
        raise InputError(
            f"{name!r} must be finite and {bound}, got {float(arr[bad].flat[0])!r}{where}; "
            "check its sign and units (SI: W, s, m³, Pa⁻¹)")
    return arr


def _psi1(x: np.ndarray) -> np.ndarray:
    """(1 − e^(−x))/x for x >= 0, = 1 at x = 0 (no cancellation)."""
    x = np.asarray(x, dtype=float)
    out = np.ones_like(x)
    big = x > 0
    out[big] = -np.expm1(-x[big]) / x[big]
    return out


def _psi2(x: np.ndarray) -> np.ndarray:
    """(x − 1 + e^(−x))/x = 1 − psi1(x) for x >= 0, by its Taylor series where x is small.

    psi2(x) = Σ_{k>=1} (−1)^(k+1) x^k/(k+1)!, so psi2 ≈ x/2 for small x without the cancellation
    of ``1 − psi1``.
    """
    x = np.asarray(x, dtype=float)
    out = np.empty_like(x)
    small = x < _SERIES_LIMIT
    xs = x[small]
    kernel = _psi2_series_kernel()
    if kernel is None:
        term = xs / 2.0
        total = term.copy()
        for k in range(2, _SERIES_TERMS + 1):
            term = -term * xs / (k + 1)
            total += term
    else:
        total = np.empty_like(xs)
        kernel[0](np.ascontiguousarray(xs), _SERIES_TERMS, total)
    out[small] = total
    xb = x[~small]
    out[~small] = 1.0 + np.expm1(-xb) / xb
    return out


def _psi2_series(xs, terms, total):
    """The Taylor series of :func:`_psi2` for each x, term by term as the numpy loop makes it
    (the same operations in the same order), compiled by :func:`_psi2_series_kernel`."""
    for i in range(xs.size):
        x = xs[i]
        term = x / 2.0
        value = term
        for k in range(2, terms + 1):
            term = -term * x / (k + 1)
            value += term
        total[i] = value


#: (:func:`_psi2_series`,) compiled at the first call, None without numba.
_psi2_series_kernel = compiled_when_used(_psi2_series)


def archard(power, duration, coefficient) -> np.ndarray:
    """Worn volume of Archard's law, ``V = K·P·t``.

    Parameters
    ----------
    power : array_like
        Wear power P [W] (= N·m/s), >= 0.
    duration : array_like
        Duration of wear t [s], >= 0 (service time, not the simulated time).
    coefficient : array_like
        Wear coefficient K [Pa⁻¹] (= m³/J), >= 0 (Code_Aster ``COEF_USURE``).

    Returns
    -------
    numpy.ndarray
        Worn volume V [m³], the broadcast shape of the arguments.

    Raises
    ------
    InputError
        An argument is negative or not finite (naming it).

    Notes
    -----
    .. math:: V = K \\, P \\, t

    Archard's adhesive-wear relation ``V = k·Fn·L/H`` [1]_ with ``K = k/H`` and the wear work
    ``W = ∫ Fn·Vt dt = P·t`` (theory §4; Code_Aster R7.20.01 §2.1).

    References
    ----------
    .. [1] Archard, J. F. (1953). Contact and rubbing of flat surfaces. *Journal of Applied Physics*
           24(8), 981-988.

    Examples
    --------
    >>> float(archard(power=0.01, duration=3.15e7, coefficient=1e-13))
    3.15e-08
    """
    p = _checked("power", power)
    t = _checked("duration", duration)
    k = _checked("coefficient", coefficient)
    return k * p * t


def kwu_epri(power, duration, reference_coefficient, intensity,
             reference_intensity=1.0) -> np.ndarray:
    """Worn volume of the KWU-EPRI law, ``V = (k_r·w/w_r)·P·t``.

    Parameters
    ----------
    power : array_like
        Wear power P [W], >= 0.
    duration : array_like
        Duration of wear t [s], >= 0.
    reference_coefficient : array_like
        Reference wear coefficient k_r [Pa⁻¹], measured in a conventional oscillating-sliding test
        (Code_Aster ``COEF_USURE``).
    intensity : array_like
        Total wear-intensity factor w of the contact, from :func:`kwu_epri_statistics` (same units
        as ``reference_intensity``).
    reference_intensity : array_like, optional
        Intensity factor w_r of the reference test, > 0. Default 1 (then k_r is Code_Aster's
        COEF_USURE).

    Returns
    -------
    numpy.ndarray
        Worn volume V [m³].

    Notes
    -----
    .. math:: K_{KWU} = k_r \\, w / w_r, \\qquad V = K_{KWU} \\, P \\, t

    with :math:`w = (\\sum P_w)^2 / (\\sum P_h + \\sum P_w)` from the 5×5 force/speed classes of
    the contact [1]_ (theory §4; Code_Aster R7.20.01 §2.2).

    References
    ----------
    .. [1] Hoffmann, P. J., Steininger, D. A., & Schettler, T. (1992). PWR steam generator tube
           fretting and fatigue wear phenomena and correlations. Symposium on Flow-Induced Vibration
           and Noise, Vol. 1, ASME HTD-Vol. 230 / NE-Vol. 9.

    Examples
    --------
    >>> float(kwu_epri(power=0.02, duration=1000.0, reference_coefficient=1e-14, intensity=0.5))
    1e-10
    """
    p = _checked("power", power)
    t = _checked("duration", duration)
    kr = _checked("reference_coefficient", reference_coefficient)
    w = _checked("intensity", intensity)
    wr = _checked("reference_intensity", reference_intensity, positive=True)
    return kr * w / wr * p * t


def _edf_mz_arrays(power, a, b, n, s):
    p = _checked("power", power)
    a = _checked("rate_coefficient", a)
    b = _checked("power_exponent", b)
    n = _checked("decay_constant", n)
    s = _checked("asymptotic_rate", s)
    initial_rate = a * p ** b
    return initial_rate, n, s


def _warn_rising(initial_rate: np.ndarray, s: np.ndarray, stacklevel: int = 3) -> None:
    rising = np.broadcast_to(s > initial_rate, np.broadcast(s, initial_rate).shape)
    if rising.any():
        i = np.argwhere(rising)[0] if rising.ndim else ()
        s0 = float(np.broadcast_to(initial_rate, rising.shape)[tuple(i)])
        ss = float(np.broadcast_to(s, rising.shape)[tuple(i)])
        _law_warning(
            f"EDF_MZ: the asymptotic rate S = {ss:.6g} m³/s exceeds the initial rate A·P^b = "
            f"{s0:.6g} m³/s for {int(rising.sum())} of {rising.size} value(s): the wear rate rises "
            "with time instead of slowing down (the formula still holds); check A, b, S and the "
            "power", stacklevel=stacklevel)


def edf_mz(power, duration, rate_coefficient=1e-13, power_exponent=1.2, decay_constant=2.44e-8,
           asymptotic_rate=1.14e-16) -> np.ndarray:
    """Worn volume of the EDF-MZ law, ``V = ((A·P^b − S)/n)·(1 − e^(−n·t)) + S·t``.

    Parameters
    ----------
    power : array_like
        Wear power P [W], >= 0.
    duration : array_like
        Duration of wear t [s], >= 0.
    rate_coefficient : array_like, optional
        A [m³/(s·W^b)] (Code_Aster ``COEF_USURE``): the initial wear rate is ``S0 = A·P^b``
        [m³/s]. For b = 1 its unit is Pa⁻¹, like an Archard coefficient. Default 1e-13.
    power_exponent : array_like, optional
        b [1] (``COEF_B``). Default 1.2.
    decay_constant : array_like, optional
        n [s⁻¹] (``COEF_N``), >= 0: the rate relaxes from S0 to S with time constant 1/n
        (n = 0 gives ``V = A·P^b·t``). Default 2.44e-8 s⁻¹ (1/n ≈ 1.3 years).
    asymptotic_rate : array_like, optional
        S [m³/s] (``COEF_S``), the long-term wear rate. Default 1.14e-16 m³/s.

    Returns
    -------
    numpy.ndarray
        Worn volume V [m³].

    Warns
    -----
    LawWarning
        When S > A·P^b: the rate rises with time (the formula still holds).

    Notes
    -----
    .. math:: V(t) = \\frac{A P^b - S}{n} \\left(1 - e^{-n t}\\right) + S\\,t
              = t \\left[A P^b \\, \\psi_1(n t) + S \\, \\psi_2(n t)\\right]

    with :math:`\\psi_1(x) = (1 - e^{-x})/x` and :math:`\\psi_2(x) = 1 - \\psi_1(x)`, evaluated
    with ``expm1`` and a Taylor series for small ``x`` so that no digit is lost when n·t is small.
    The rate :math:`\\dot V = A P^b e^{-n t} + S (1 - e^{-n t})` goes from A·P^b at t = 0 to S
    [1]_ (theory §4).

    References
    ----------
    .. [1] Zbinden, M., & Durbec, V. (1996). A kinetic model for impact/sliding wear of pressurized
           water reactor internal components: application to rod cluster control assemblies. ASME
           Pressure Vessels and Piping Conference, Montreal.

    Examples
    --------
    >>> v = edf_mz(power=[0.01, 0.01], duration=[1.0, 3.15e7])
    >>> [f"{x:.4e}" for x in v]
    ['3.9811e-16', '9.8360e-09']
    """
    initial_rate, n, s = _edf_mz_arrays(power, rate_coefficient, power_exponent, decay_constant,
                                        asymptotic_rate)
    t = _checked("duration", duration)
    _warn_rising(initial_rate, s)
    x = n * t
    return t * (initial_rate * _psi1(x) + s * _psi2(x))


def edf_mz_rate(power, duration, rate_coefficient=1e-13, power_exponent=1.2,
                decay_constant=2.44e-8, asymptotic_rate=1.14e-16) -> np.ndarray:
    """Wear rate dV/dt of the EDF-MZ law [m³/s] (parameters as :func:`edf_mz`).

    Notes
    -----
    .. math:: \\dot V(t) = A P^b e^{-n t} + S\\,(1 - e^{-n t})

    Examples
    --------
    >>> float(edf_mz_rate(power=1.0, duration=0.0))
    1e-13
    """
    initial_rate, n, s = _edf_mz_arrays(power, rate_coefficient, power_exponent, decay_constant,
                                        asymptotic_rate)
    t = _checked("duration", duration)
    decay = np.exp(-n * t)
    return initial_rate * decay - s * np.expm1(-n * t)


def edf_mz_equivalent_time(volume, power, rate_coefficient=1e-13, power_exponent=1.2,
                           decay_constant=2.44e-8, asymptotic_rate=1.14e-16, *,
                           rtol: float = 1e-13) -> np.ndarray:
    """Duration at which the EDF-MZ law reaches a given volume (restart, theory §7).

    Parameters
    ----------
    volume : array_like
        Worn volume reached so far V [m³], >= 0.
    power : array_like
        Wear power P [W] of the continuation, >= 0.
    rate_coefficient, power_exponent, decay_constant, asymptotic_rate : array_like, optional
        A [m³/(s·W^b)], b [1], n [s⁻¹], S [m³/s], as in :func:`edf_mz`.
    rtol : float, optional
        Relative tolerance on the time. Default 1e-13.

    Returns
    -------
    numpy.ndarray
        Equivalent time t_eq [s] with ``edf_mz(power, t_eq, ...) == volume``. ``inf`` where the law
        never reaches the volume (S = 0: V saturates at A·P^b/n; or A·P^b = S = 0), with a
        :class:`~fretwear.errors.LawWarning`.

    Notes
    -----
    V(t) is strictly increasing when A·P^b + S > 0 (its rate is a weighted mean of A·P^b and S), so
    the root is unique. It is bracketed by ``V/max(A·P^b, S) <= t_eq`` and
    ``t_eq <= V/min(A·P^b, S)`` (or ``V/S + 1/n`` when A·P^b = 0; closed forms when S = 0 or
    n = 0), then found by Newton steps safeguarded by bisection (geometric while the bracket spans
    decades) on all elements at once, until the step or the bracket is below ``rtol``. A restart
    continues with ``V(t_eq + Δt)``.

    Examples
    --------
    >>> v = edf_mz(power=0.01, duration=3.15e7)       # one year at 10 mW
    >>> float(edf_mz_equivalent_time(volume=v, power=0.01))
    31500000.0
    """
    v = _checked("volume", volume)
    initial_rate, n, s = _edf_mz_arrays(power, rate_coefficient, power_exponent, decay_constant,
                                        asymptotic_rate)
    _warn_rising(initial_rate, s)
    v, r0, n, s = np.broadcast_arrays(v, initial_rate, n, s)
    v, r0, n, s = (np.array(a, dtype=float) for a in (v, r0, n, s))
    out = np.zeros(v.shape)
    # largest volume the law ever reaches: finite only when S = 0 (saturation at A·P^b/n)
    ceiling = np.full(v.shape, np.inf)
    saturating = (s == 0) & (n > 0)
    ceiling[saturating] = r0[saturating] / n[saturating]
    ceiling[(n == 0) & (r0 == 0)] = 0.0      # n = 0: V = A·P^b·t, whatever S
    unreachable = (v > 0) & (v >= ceiling)
    if unreachable.any():
        out[unreachable] = np.inf
        _law_warning(
            f"EDF_MZ: {int(unreachable.sum())} volume(s) can never be reached by the law (S = 0 "
            "and V >= A·P^b/n, or A·P^b = S = 0): equivalent time set to inf, so the volume "
            "stays where it is", stacklevel=2)
    todo = (v > 0) & ~unreachable
    if not todo.any():
        return out
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        out[todo] = _solve_edf_mz(v[todo], r0[todo], n[todo], s[todo], rtol)
    return out


def _solve_edf_mz(vv, r, nn, ss, rtol) -> np.ndarray:
    """Times t with V(t) = vv (all reachable, vv > 0): bracket, then safeguarded Newton."""
    hi_rate = np.maximum(r, ss)
    lo_rate = np.minimum(r, ss)
    lo = vv / hi_rate
    hi = np.where(lo_rate > 0, vv / np.where(lo_rate > 0, lo_rate, 1.0), np.inf)
    # A·P^b = 0 < S: V >= S(t − 1/n)  ->  t <= V/S + 1/n
    zero_r = (r == 0) & (ss > 0) & (nn > 0)
    hi = np.where(zero_r, vv / np.where(ss > 0, ss, 1.0) + 1.0 / np.where(nn > 0, nn, 1.0), hi)
    # V >= (r/n)(1 − e^{−nt}) (the S = 0 law): t <= −ln(1 − V·n/r)/n where V·n/r < 1
    q = np.where(r > 0, vv * nn / np.where(r > 0, r, 1.0), np.inf)
    t_sat = np.where(nn > 0, -np.log1p(-np.minimum(q, 0.5)) / np.where(nn > 0, nn, 1.0),
                     vv / np.where(r > 0, r, 1.0))
    hi = np.where((q < 0.5) & (r > 0), np.minimum(hi, t_sat), hi)
    hi = np.minimum(hi, np.finfo(float).max)
    # S = 0 < A·P^b (reachable): V = (r/n)(1 − e^{−nt})  ->  closed form
    zero_s = (ss == 0) & (r > 0) & (nn > 0)
    if zero_s.any():
        closed = -np.log1p(-vv[zero_s] * nn[zero_s] / r[zero_s]) / nn[zero_s]
        lo[zero_s] = hi[zero_s] = closed
    # n = 0: V = A·P^b·t  ->  closed form
    linear = nn == 0
    lo[linear] = hi[linear] = vv[linear] / r[linear]
    t = np.where(hi > 4.0 * lo, np.sqrt(lo) * np.sqrt(hi), 0.5 * (lo + hi))
    for _ in range(200):
        x = nn * t
        f = t * (r * _psi1(x) + ss * _psi2(x)) - vv
        hi = np.where(f >= 0, t, hi)
        lo = np.where(f <= 0, t, lo)
        rate = r * np.exp(-x) - ss * np.expm1(-x)
        newton = t - f / rate
        inside = np.isfinite(newton) & (newton >= lo) & (newton <= hi)
        # bisect geometrically while the bracket spans decades, arithmetically after
        middle = np.where(hi > 4.0 * lo, np.sqrt(lo) * np.sqrt(hi), 0.5 * (lo + hi))
        t_new = np.where(inside, newton, middle)
        step = np.abs(t_new - t)
        t = t_new
        if np.all((step <= rtol * t) | (hi - lo <= rtol * hi)):
            break
    return t


def linear_equivalent_time(volume, volume_rate) -> np.ndarray:
    """Equivalent time of a law linear in time, ``t = V / (dV/dt)`` [s].

    Parameters
    ----------
    volume : array_like
        Volume reached [m³], >= 0.
    volume_rate : array_like
        Constant wear rate K·P [m³/s], >= 0.

    Returns
    -------
    numpy.ndarray
        ``V / rate`` [s]; 0 where V = 0; ``inf`` (with a LawWarning) where V > 0 and the rate is 0.

    Examples
    --------
    >>> float(linear_equivalent_time(3.0e-9, 1.0e-15))
    3000000.0
    """
    v = _checked("volume", volume)
    q = _checked("volume_rate", volume_rate)
    v, q = np.broadcast_arrays(v, q)
    never = (v > 0) & (q == 0)
    if never.any():
        _law_warning(
            f"{int(never.sum())} volume(s) > 0 with a zero wear rate (K·P = 0): equivalent time "
            "set to inf, the volume stays where it is", stacklevel=2)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(v == 0, 0.0, np.where(never, np.inf, v / np.where(q > 0, q, 1.0)))
