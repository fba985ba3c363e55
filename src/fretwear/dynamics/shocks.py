"""Shock (impact-sliding contact) models in the manner of Code_Aster's DIS_CHOC.

A :class:`Shock` ties one shock point of the modal model to an obstacle. The obstacle families are
the keys of :data:`OBSTACLES`:

``"plane"``
    one plane at distance ``gap`` along the normal of angle ``angle`` (deg, from local y to z);
``"two_planes"``
    two parallel planes at ± ``gap`` along that normal (a slot);
``"circle"``
    a bore of radial clearance ``gap`` (the mobile's centre may move ``gap`` in every direction);
``"profile"``
    a discrete polar clearance profile: ``gap`` as a function of the angle (deg), e.g. the worn
    clearance produced by the obstacle update (Code_Aster's DEFI_OBSTACLE 'DISCRET').

Contact law (penalty): penetration δ > 0 gives the normal force
``Fn = max(0, k_n δ + c_n δ̇)`` (never a pulling force). Friction is Coulomb with a tangential
spring-dashpot (elastic stick) and a return map onto the Coulomb cone (slip): a sticking contact
slips when its tangential force passes μ_s Fn (static coefficient, Code_Aster COULOMB_STAT) and
then slides with μ_d Fn (dynamic coefficient, COULOMB_DYNA or COULOMB) until it sticks again.

:func:`code_aster_tangential_damping` gives the tangential damping Code_Aster uses when AMOR_TAN
is not given (``dtmprep_noli_choc``): the case file's ``[[dynamics.shocks]]`` takes it by
default; a :class:`Shock` built in Python takes it with ``tangential_damping=None``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from fretwear.errors import InputError, KeywordError

if TYPE_CHECKING:  # typing only: modal imports nothing from here
    from fretwear.dynamics.modal import ModalModel

#: Obstacle families and their integer codes in the compiled kernel.
OBSTACLES: dict[str, int] = {"plane": 0, "two_planes": 1, "circle": 2, "profile": 3}


@dataclass(frozen=True, eq=False)
class Shock:
    """One shock point and its obstacle (DIS_CHOC-like).

    Parameters
    ----------
    point : int or str
        Shock point of the :class:`~fretwear.dynamics.modal.ModalModel` (index or name).
    obstacle : str
        One of :data:`OBSTACLES`.
    normal_stiffness : float
        Penalty normal stiffness k_n [N/m] (Code_Aster RIGI_NOR), > 0.
    gap : float
        Clearance [m] (JEU): distance to the plane(s), radial clearance of the circle. May be
        negative (an interference, giving a preload k_n·|gap|). Ignored by ``"profile"``.
    angle : float
        Direction of the plane normal in the local y-z plane [deg] (from y towards z). Used by
        ``"plane"`` and ``"two_planes"``; also the direction of ``preload`` for circle/profile.
    normal_damping : float
        Normal contact damping c_n [N·s/m] (AMOR_NOR), >= 0.
    tangential_stiffness : float
        Tangential (stick) stiffness k_t [N/m] (RIGI_TAN), >= 0. 0 with ``friction > 0`` is an
        error (the elastic-stick model needs it).
    tangential_damping : float or None
        Tangential damping c_t [N·s/m] (AMOR_TAN), >= 0. None: Code_Aster's value when AMOR_TAN
        is absent, computed from the modal model by :func:`simulate
        <fretwear.dynamics.integrate.simulate>` (:func:`code_aster_tangential_damping`).
    friction : float
        Dynamic Coulomb coefficient μ_d [-] (COULOMB, or COULOMB_DYNA), >= 0: the sliding force
        is μ_d·Fn.
    static_friction : float, optional
        Static Coulomb coefficient μ_s [-] (COULOMB_STAT), >= 0: a sticking contact slips when
        its tangential force exceeds μ_s·Fn. Default: ``friction`` (one coefficient).
    preload : float
        A constant force [N] pushing the mobile's shock point towards the obstacle, along the
        normal (plane) or along ``angle`` (other families). 0 by default.
    origin : (float, float)
        Position of the obstacle's centre (or of the plane's reference point) relative to the
        mobile's rest position, local (y, z) [m].
    profile_angles, profile_gaps : array_like
        The discrete profile (``"profile"`` only): angles [deg] (any range; sorted and taken
        modulo 360) and clearances [m] > 0.
    name : str
        Label of the contact history produced.

    Notes
    -----
    Penetration δ and outward unit normal n (pointing from the mobile towards the obstacle) as a
    function of the shock point's relative displacement u = (u_y, u_z) − origin:
    plane δ = u·n − g; two planes δ = |u·n| − g with n of the sign of u·n; circle δ = |u| − g with
    n = u/|u|; profile: polygon through the points g_k (cos θ_k, sin θ_k), δ = (u − P_k)·n_k for the
    segment k holding the angle of u, n_k its outward normal.
    Normal force on the mobile −Fn·n with Fn = max(0, k_n δ + c_n δ̇). Tangential: with the
    elastic force Fs carried over from the previous step (projected on the new tangent plane),
    trial Ft* = Fs − k_t Δu_t − c_t v_t; stick if |Ft*| ≤ μ Fn (Fs ← Fs − k_t Δu_t), else slip
    with Ft = μ_d Fn Ft*/|Ft*| and Fs ← Ft (return map), where μ = μ_s when the contact stuck at
    the previous step (or has just closed) and μ = μ_d while it slides (Code_Aster's ``ftang``:
    the static threshold breaks adhesion, sliding goes on at μ_d until the tangential velocity
    turns). With μ_s = μ_d this is the plain return map. Local frame of the history: t1 = the
    in-plane tangent (−n_z, n_y), t2 = the axial direction x.

    References
    ----------
    .. [1] Code_Aster Reference Manual R5.06.03, *Modélisation des chocs et du frottement dans
           DYNA_VIBRA* (DIS_CHOC), EDF R&D.
    .. [2] Simo, J. C., & Hughes, T. J. R. (1998). *Computational Inelasticity*. Springer, §2.1
           (return map).

    Examples
    --------
    >>> s = Shock(point=0, obstacle="circle", gap=1e-4, normal_stiffness=1e6, friction=0.3,
    ...           tangential_stiffness=1e6)
    >>> s.obstacle, s.code
    ('circle', 2)
    """

    point: Any
    obstacle: str
    normal_stiffness: float
    gap: float = 0.0
    angle: float = 0.0
    normal_damping: float = 0.0
    tangential_stiffness: float = 0.0
    tangential_damping: float | None = 0.0
    friction: float = 0.0
    preload: float = 0.0
    origin: tuple[float, float] = (0.0, 0.0)
    profile_angles: Any = None
    profile_gaps: Any = None
    name: str = ""
    metadata: dict = field(default_factory=dict)
    static_friction: float | None = None

    def __post_init__(self) -> None:
        if self.obstacle not in OBSTACLES:
            raise KeywordError(f"shock {self.name or self.point!r}: unknown obstacle "
                               f"{self.obstacle!r}; choose one of {list(OBSTACLES)}")
        label = self.name or str(self.point)
        if self.static_friction is None:
            object.__setattr__(self, "static_friction", self.friction)
        for key in ("normal_stiffness", "normal_damping", "tangential_stiffness",
                    "tangential_damping", "friction", "static_friction", "gap", "angle",
                    "preload"):
            if key == "tangential_damping" and self.tangential_damping is None:
                continue  # Code_Aster's default, resolved against the modal model
            v = float(getattr(self, key))
            if not np.isfinite(v):
                raise InputError(f"shock {label!r}: {key!r} must be finite, got {v!r}")
            object.__setattr__(self, key, v)
        if self.normal_stiffness <= 0:
            raise InputError(f"shock {label!r}: 'normal_stiffness' must be > 0 [N/m], got "
                             f"{self.normal_stiffness}")
        for key in ("normal_damping", "tangential_stiffness", "tangential_damping", "friction",
                    "static_friction"):
            value = getattr(self, key)
            if value is not None and value < 0:
                raise InputError(f"shock {label!r}: {key!r} must be >= 0, got {value}")
        mu = max(self.friction, self.static_friction)
        if mu > 0 and self.tangential_stiffness <= 0:
            raise InputError(f"shock {label!r}: 'friction' = {mu} needs a "
                             "'tangential_stiffness' > 0 [N/m] (the elastic-stick spring); give "
                             "one, e.g. equal to the normal stiffness")
        if self.obstacle in ("two_planes", "circle") and self.gap < 0:
            raise InputError(f"shock {label!r}: a {self.obstacle!r} obstacle needs 'gap' >= 0 [m], "
                             f"got {self.gap}")
        origin = np.array(self.origin, dtype=float).reshape(-1)
        if origin.size != 2 or not np.all(np.isfinite(origin)):
            raise InputError(f"shock {label!r}: 'origin' must be two finite numbers (y, z) [m]")
        object.__setattr__(self, "origin", (float(origin[0]), float(origin[1])))
        if self.obstacle == "profile":
            if self.profile_angles is None or self.profile_gaps is None:
                raise KeywordError(f"shock {label!r}: a 'profile' obstacle needs 'profile_angles' "
                                   "[deg] and 'profile_gaps' [m]")
            ang = np.array(self.profile_angles, dtype=float).reshape(-1)
            gap = np.array(self.profile_gaps, dtype=float).reshape(-1)
            if ang.size != gap.size or ang.size < 3:
                raise InputError(f"shock {label!r}: 'profile_angles' and 'profile_gaps' need the "
                                 f"same length >= 3, got {ang.size} and {gap.size}")
            if not (np.all(np.isfinite(ang)) and np.all(np.isfinite(gap))):
                raise InputError(f"shock {label!r}: the profile has non-finite values")
            if np.any(gap <= 0):
                i = int(np.flatnonzero(gap <= 0)[0])
                raise InputError(f"shock {label!r}: 'profile_gaps' must be > 0 [m]; row {i} "
                                 f"(angle {ang[i]} deg) is {gap[i]}")
            theta = np.mod(ang, 360.0)
            order = np.argsort(theta, kind="stable")
            theta, gap = theta[order], gap[order]
            keep = np.concatenate([[True], np.diff(theta) > 1e-12])
            theta, gap = theta[keep], gap[keep]
            theta.flags.writeable = False
            gap.flags.writeable = False
            object.__setattr__(self, "profile_angles", theta)
            object.__setattr__(self, "profile_gaps", gap)
        object.__setattr__(self, "metadata", dict(self.metadata))

    @property
    def code(self) -> int:
        """Integer code of the obstacle family in the compiled kernel."""
        return OBSTACLES[self.obstacle]

    @property
    def label(self) -> str:
        """Name of the shock (its ``name``, else the point)."""
        return self.name or str(self.point)

    def gap_at(self, angle) -> np.ndarray:
        """Clearance [m] in the direction ``angle`` [deg] (distance the mobile can travel).

        For a plane, the distance along the direction to the plane (inf when moving away); for a
        profile, the polygon's radius in that direction.

        Examples
        --------
        >>> Shock(point=0, obstacle="circle", gap=2e-4, normal_stiffness=1.0).gap_at([0, 90])
        array([0.0002, 0.0002])
        """
        a = np.radians(np.asarray(angle, dtype=float))
        d = np.stack([np.cos(a), np.sin(a)], axis=-1)
        if self.obstacle == "circle":
            return np.full(a.shape, self.gap)
        if self.obstacle in ("plane", "two_planes"):
            n = np.array([np.cos(np.radians(self.angle)), np.sin(np.radians(self.angle))])
            c = d @ n
            if self.obstacle == "two_planes":
                c = np.abs(c)
            with np.errstate(divide="ignore"):
                return np.where(c > 0, self.gap / np.where(c > 0, c, 1.0), np.inf)
        th = np.radians(self.profile_angles)
        pts = self.profile_gaps[:, None] * np.stack([np.cos(th), np.sin(th)], axis=-1)
        out = np.empty(a.shape)
        flat_a, flat_out = np.mod(np.degrees(a).reshape(-1), 360.0), out.reshape(-1)
        t = self.profile_angles
        k = (np.searchsorted(t, flat_a, side="right") - 1) % t.size
        p0, p1 = pts[k], pts[(k + 1) % t.size]
        dd = d.reshape(-1, 2)
        # ray s·d meets segment p0 + w (p1 - p0): solve s d - w e = p0
        e = p1 - p0
        det = dd[:, 0] * (-e[:, 1]) + dd[:, 1] * e[:, 0]
        flat_out[:] = (p0[:, 0] * (-e[:, 1]) + p0[:, 1] * e[:, 0]) / det
        return out


def circle_profile(gap: float, n_points: int = 721) -> tuple[np.ndarray, np.ndarray]:
    """A circular clearance as a discrete profile (Code_Aster's DISCRET: 721 points by 0.5°).

    Parameters
    ----------
    gap : float
        Radial clearance [m].
    n_points : int
        Points from 0 to 360° inclusive.

    Returns
    -------
    angles [deg], gaps [m]

    Examples
    --------
    >>> a, g = circle_profile(5e-4)
    >>> a.size, float(a[1]), float(g[0])
    (721, 0.5, 0.0005)
    """
    angles = np.linspace(0.0, 360.0, n_points)
    return angles, np.full(n_points, float(gap))


def _tangent_shapes(model: ModalModel, shock: Shock) -> np.ndarray:
    """|φ_t,r| [-]: each mode's displacement at the shock point in the contact's tangent plane.

    Plane obstacles: the in-plane tangent (−sin a, cos a) and the axial x (Code_Aster's PLAN_Y /
    PLAN_Z take the two axes of the plane). A circle or a profile has no fixed tangent: the whole
    displacement (y, z, x) (Code_Aster's CERCLE takes the axial x only, which gives 0 for the
    in-plane shapes fretwear's beams have).
    """
    phi = model.shock_shapes[model.shock_index(shock.point)]  # (3, n): y, z, x
    if shock.obstacle in ("plane", "two_planes"):
        a = math.radians(shock.angle)
        in_plane = -math.sin(a) * phi[0] + math.cos(a) * phi[1]
        return np.sqrt(in_plane**2 + phi[2] ** 2)
    return np.sqrt(np.sum(phi**2, axis=0))


def code_aster_tangential_damping(model: ModalModel, shock: Shock) -> float:
    """The tangential damping Code_Aster gives a shock without AMOR_TAN [N·s/m].

    Code_Aster's DYNA_VIBRA (``dtmprep_noli_choc``, § 3.9) computes, when RIGI_TAN > 0 and
    AMOR_TAN is absent, the damping that makes the tangential spring of the shock critically
    damped on the mode that moves the shock point most along the contact's tangent plane, minus
    that mode's own damping: with m, ω, ξ the mode's effective mass at the shock point, circular
    frequency and damping ratio and k = ω² m,

    .. math:: c_t = 2\\sqrt{m\\,(k + k_t)} - 2\\,\\xi\\sqrt{k\\,m}, \\qquad c_t \\ge 0.

    Parameters
    ----------
    model : ModalModel
        The modes (frequencies [Hz], damping ratios [-], masses [kg], shapes at the shock).
    shock : Shock
        The contact: its ``tangential_stiffness`` k_t [N/m], obstacle and point.

    Returns
    -------
    float
        c_t [N·s/m]; 0 when k_t = 0 (Code_Aster leaves AMOR_TAN at 0 then) or when no elastic
        mode moves the point along the tangent plane.

    Notes
    -----
    The mode is the elastic one (ω > 0) with the largest tangential displacement per unit
    modal mass |φ_t,r|/√m_r, and m = m_r/|φ_t,r|² is its mass seen at the shock point. Code_Aster
    takes the mode with the largest m_r·|φ_t,r| and uses its generalised mass m_r as is: the same
    for mass-normalised modes (m_r = 1) and for a shape of unit amplitude at the shock (as in
    Code_Aster's test SDND100A), but fretwear's form does not depend on how the modes are
    normalised. The tangent plane: see :func:`_tangent_shapes`.

    References
    ----------
    .. [1] Code_Aster source ``bibfor/dyna_gene/dtmprep_noli_choc.F90`` (§ 3.9 "Special treatment
           for the tangential damping"), EDF R&D.
    .. [2] Code_Aster validation test SDND100A (one degree of freedom sliding with Coulomb
           friction, ``astest/sdnd100a.comm``), EDF R&D.

    Examples
    --------
    SDND100A: m = 1 kg, k = 1e4 N/m (ξ = 0), RIGI_TAN = 4e5 N/m: c_t = 2√(1 · 4.1e5).

    >>> from fretwear.dynamics.modal import ModalModel
    >>> m = ModalModel(frequencies=[100.0 / (2 * math.pi)], damping_ratios=0.0, masses=1.0,
    ...                shock_shapes=[[[1.0], [0.0]]])
    >>> s = Shock(point=0, obstacle="plane", angle=90.0, normal_stiffness=20.0, gap=-0.5,
    ...           tangential_stiffness=4e5, friction=0.1)
    >>> round(code_aster_tangential_damping(m, s), 4)
    1280.6248
    """
    kt = float(shock.tangential_stiffness)
    if kt <= 0:
        return 0.0
    omega = model.omega
    phi_t = _tangent_shapes(model, shock)
    weight = np.where(omega > 0, phi_t / np.sqrt(model.masses), 0.0)
    r = int(np.argmax(weight))
    if weight[r] <= 0:
        return 0.0
    mass = float(model.masses[r] / phi_t[r] ** 2)
    k = float(omega[r] ** 2 * mass)
    xi = float(model.damping_ratios[r])
    return max(0.0, 2.0 * math.sqrt(mass * (k + kt)) - 2.0 * xi * math.sqrt(k * mass))


def with_code_aster_damping(model: ModalModel, shocks) -> list[Shock]:
    """The shocks, those with ``tangential_damping=None`` given Code_Aster's value.

    The value is recorded in the shock's ``metadata["tangential_damping"]`` with its source
    (``"dtmprep_noli_choc"``).
    """
    out = []
    for s in shocks:
        if s.tangential_damping is None:
            c = code_aster_tangential_damping(model, s)
            meta = dict(s.metadata, tangential_damping={"value_N_s_per_m": c,
                                                        "source": "dtmprep_noli_choc"})
            s = replace(s, tangential_damping=c, metadata=meta)
        out.append(s)
    return out
