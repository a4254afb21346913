"""Loaded transmission error of an uncrowned spur pair, with and without tip relief,
against an independent computation along the line of action.

The reference treats the pair as the textbook one-dimensional mesh (Harris 1958; Munro's
"Harris map"): at each roll angle the tooth pairs sit on the path of contact at roll lengths
s1 = s_pitch + r_b1·(phi - phi_0) + k·p_b; each pair's unloaded separation is the least
gap of its relieved flanks about that point (both members' tip relief, linear in roll
length from the start diameter, along the transverse normal; a relieved flank leans away by
the relief's slope θ, so the flanks come closest off the line of action, about R·θ²/2 nearer
than on it: 2 µm for a 20 µm relief here); each pair's approach under w N/mm is w·(q1 + q2)
(the two slices' compliance at their load radii, contact.compliance.ToothCompliance, for a
load uniform along the face, which the coupling along the face leaves at exactly c·q) plus
each body's contact compression between its surface and its tooth's centre line, the
plane-strain integral of Hertz's stresses on the axis of a line contact (Johnson 1985
§4.2; Weber's flattening); one rigid rotation D closes all pairs, sum of b·w_k = F_n, and
TE = D/r_b2. Nothing in it shares the analysis's surfaces, separation search, half-space
solver or load sharing (the slice compliance is checked against ISO 6336-1 in
test_loaded_teeth). The teeth of different pairs are coupled through the gear bodies as
the analysis couples them (analytic.gear_body, the one part it shares; held to 3D FE in
tests/test_gear_body.py). Its one simplification: it keeps contact on the path (between the
tips' roll lengths); an unrelieved tip corner that bends into contact beyond the path (the
analysis finds it) is left out.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq, minimize_scalar

from toothcontact.analyses import analyse
from toothcontact.analytic.gear_body import chord_green
from toothcontact.case import parse_case
from toothcontact.contact.compliance import ToothCompliance
from toothcontact.gearset import gear_pair

E, NU = 206000.0, 0.3
TEETH, MODULE, ALPHA, FACE, LOAD = (20, 60), 3.0, math.radians(20.0), 20.0, 6000.0
#: tip relief starts 1.8 mm below each tip diameter (a "long" relief for this pair)
STARTS = (64.2, 184.2)
#: the case's linear reliefs start blended over this share of their length (the default)
BLEND = 0.2


def case(relief_um: float) -> dict:
    raw = {"kind": "spur", "teeth": list(TEETH), "module": f"{MODULE} mm",
           "pressure_angle": "20 deg", "face_width": f"{FACE} mm",
           "load": {"tangential_load": f"{LOAD} N"},
           "analysis": {"positions": 8, "pressure_grid": 64, "interference": False,
                        "positions_check": False, "field_grid": 41}}
    for member, start in zip(("pinion", "gear"), STARTS):
        raw[member] = {"tip_edge": {"radius": "0 mm"}}     # the reference's involute is sharp
        if relief_um:
            raw[member]["tip_relief"] = {"amount": f"{relief_um} um",
                                         "start_diameter": f"{start} mm", "shape": "linear"}
    return raw


def contact_compression(w: float, half_width: float, depth: float) -> float:
    """Compression (mm) of one body between its surface and the point at `depth` (mm) below
    the middle of a Hertz line contact of load w (N/mm) and half-width b (plane strain):
    -∫ε_z dz on the axis, σ_z = -p0·b/√(b²+z²), σ_x = -(p0/b)·((b²+2z²)/√(b²+z²) - 2z)."""
    b, p0 = half_width, 2.0 * w / (math.pi * half_width)

    def strain(z):
        root = math.sqrt(b * b + z * z)
        sz = -p0 * b / root
        sx = -(p0 / b) * ((b * b + 2 * z * z) / root - 2 * z)
        return ((1 - NU * NU) * sz - NU * (1 + NU) * sx) / E

    return -quad(strain, 0.0, depth, limit=200)[0]


class LineOfAction:
    """The pair on its line of action: roll lengths, reliefs, compliances."""

    def __init__(self, relief_um: float):
        pair = gear_pair(parse_case(case(relief_um)))
        self.relief = relief_um * 1e-3
        self.teeth = [ToothCompliance(g, E, NU) for g in (pair.pinion, pair.gear)]
        self.rb = [0.5 * z * MODULE * math.cos(ALPHA) for z in TEETH]
        self.ra = [0.5 * z * MODULE + MODULE for z in TEETH]
        self.line = sum(self.rb) * math.tan(ALPHA)                 # s1 + s2 (standard centres)
        self.tip = [math.sqrt(ra * ra - rb * rb) for ra, rb in zip(self.ra, self.rb)]
        self.start = [math.sqrt((0.5 * d) ** 2 - rb * rb) for d, rb in zip(STARTS, self.rb)]
        self.pitch = 2.0 * math.pi * self.rb[0] / TEETH[0]        # base pitch
        self.C_E = 2.0 * (1 - NU * NU) / E                           # Σ(1-ν²)/E, 1/MPa

    def half_thickness(self, member: int, r: float) -> float:
        """Nominal involute tooth half-thickness (mm) at radius r (no backlash thinning)."""
        rp, rb = 0.5 * TEETH[member] * MODULE, self.rb[member]
        inv = lambda a: math.tan(a) - a                                  # noqa: E731
        return r * (0.25 * math.pi * MODULE / rp + inv(ALPHA) - inv(math.acos(rb / r)))

    def pair_approach(self, s1: float, w: float) -> float:
        """Approach (mm) of the pair at pinion roll length s1 under w N/mm."""
        s = (s1, self.line - s1)
        r = [math.hypot(si, rb) for si, rb in zip(s, self.rb)]
        bending = w * sum(float(t.at(ri)[0]) for t, ri in zip(self.teeth, r))
        R = 1.0 / (1.0 / s[0] + 1.0 / s[1])
        b = math.sqrt(4.0 * w * R * self.C_E / math.pi)
        return bending + sum(contact_compression(w, b, self.half_thickness(m, r[m]))
                             for m in (0, 1))

    def relief_at(self, s1: float, s2: float) -> float:
        """Both members' tip relief (mm) at roll lengths s1 (pinion) and s2 (gear): linear,
        its start blended over BLEND of its length as the case's reliefs are by default
        (a parabola from x = -BLEND/2 to +BLEND/2 of the relief's length x joining none and
        the line with their slopes)."""
        h = 0.5 * BLEND

        def ramp(x):
            return x if x >= h else (x + h) ** 2 / (4.0 * h) if x > -h else 0.0

        return sum(self.relief * ramp((si - st) / (tip - st))
                   for si, st, tip in zip((s1, s2), self.start, self.tip))

    def separation(self, s1: float) -> float:
        """The pair's least separation (mm) about the line of action's point s1: a relieved
        flank leans away by the relief's slope, so the flanks come closest off the line; a
        step ξ along the common tangent moves the points to roll lengths s1 + ξ·r_b1/s1 and
        s2 - ξ·r_b2/s2 (the involute's arc dσ = s·ds/r_b) and opens the unrelieved gap by
        ξ²/(2R) (R the relative radius, 1/R = 1/s1 + 1/s2)."""
        s2 = self.line - s1
        R = 1.0 / (1.0 / s1 + 1.0 / s2)
        gap = lambda xi: (self.relief_at(s1 + xi * self.rb[0] / s1, s2 - xi * self.rb[1] / s2)  # noqa: E731
                          + xi * xi / (2.0 * R))
        best = minimize_scalar(gap, bounds=(-1.0, 1.0), method="bounded",
                               options={"xatol": 1e-9})
        return min(float(best.fun), gap(0.0))

    def body_coupling(self, pairs: list[float]) -> np.ndarray:
        """(n, n) mm/N: how far pair k closes under 1 N on pair l through the gear bodies
        (analytic.gear_body.chord_green between their teeth, each tooth rigid on its root
        chord, the rim in plane stress over the face: the coupling the analysis adds and
        tests/test_gear_body.py holds to 3D FE); 0 on the diagonal."""
        n = len(pairs)
        C = np.zeros((n, n))
        for m, teeth in enumerate(self.teeth):
            r = [math.hypot(s if m == 0 else self.line - s, self.rb[m]) for s in pairs]
            g = teeth.root_loads(r)
            for k in range(n):
                for l in range(n):
                    if k != l:
                        # a pinion's roll grows with s1, the gear's falls
                        ahead = math.copysign(1.0, (pairs[k] - pairs[l]) * (1 if m == 0 else -1))
                        place = int(round(teeth.roll_sense * ahead
                                          * abs(pairs[k] - pairs[l]) / self.pitch))
                        C[k, l] += g[k] @ chord_green(
                            teeth.bore_radius, teeth.root_radius, teeth.root_half_angle,
                            TEETH[m], place, E, NU) @ g[l] / FACE
        return C

    def transmission_error(self, s1_pair0: float, normal_load: float) -> tuple[float, int]:
        """Loaded TE (µrad) at pair 0's roll length, and how many pairs carry load: each
        pair closes by its own approach and by the bodies' coupling to the others' loads
        (iterated to 1e-9 of the load)."""
        pairs = [s1_pair0 + k * self.pitch for k in range(-3, 4)]
        pairs = [s for s in pairs if self.line - self.tip[1] <= s <= self.tip[0]]
        gaps = np.array([self.separation(s) for s in pairs])
        C = self.body_coupling(pairs)
        loads = np.zeros(len(pairs))

        def pair_load(s: float, closing: float) -> float:
            """The load (N) on the pair at s1 = s closed by `closing` (mm)."""
            if closing <= 1e-12:
                return 0.0
            return FACE * brentq(lambda w: self.pair_approach(s, w) - closing, 1e-9, 1e5)

        def load(D: float, opened: np.ndarray) -> np.ndarray:
            return np.array([pair_load(s, D - g) for s, g in zip(pairs, opened)])

        for _ in range(200):
            opened = gaps + C @ loads
            low = float(np.min(opened))
            D = brentq(lambda D, at=opened: load(D, at).sum() - normal_load, low + 1e-9,
                       low + 0.2)
            new = load(D, opened)
            if np.max(np.abs(new - loads)) < 1e-9 * normal_load:
                break
            loads = 0.5 * (loads + new)
        return 1e6 * D / self.rb[1], int(np.sum(new > 0))


@pytest.fixture(scope="module", params=[0.0, 20.0, 40.0],
                ids=["no_relief", "relief_20um", "relief_40um"])
def compared(request):
    relief = request.param
    result = analyse(parse_case(case(relief)))
    reference = LineOfAction(relief)
    rows = result.sections["positions"]
    normal_load = result.sections["summary"]["normal_load_N"]
    # the cycle's phase: pair 0's roll length at the first position, from its contact radius
    first = next(r for r in rows if r["pair"] == 0)
    s0 = math.sqrt(first["contact_radius_pinion_mm"] ** 2 - reference.rb[0] ** 2)
    out = []
    for roll in sorted({r["roll_deg"] for r in rows}):
        here = [r for r in rows if r["roll_deg"] == roll]
        s1 = s0 + reference.rb[0] * math.radians(roll - first["roll_deg"])
        te, loaded = reference.transmission_error(s1, normal_load)
        out.append((here[0]["loaded_transmission_error_urad"], te,
                    sum(r["bem_load_N"] > 0 for r in here) == loaded))
    return relief, out, result


def test_loaded_te_follows_the_line_of_action_model(compared):
    """Where the analysis and the reference load the same number of pairs, the loaded TE
    agrees within 2 % (measured -0.88 % to +0.29 %, -1.13 % to +0.37 % before the bodies'
    coupling, the reference's reliefs blended at their starts as the case's are; +3.1 %
    where it kept them sharp: the coupled face, the profile's
    cross compliance under the Hertz band and the 3-D half-space against the slices' point
    compliance and plane strain; largest where a 40 µm relief loads a relieved pair off
    the line of action). That is every position with relief; without it
    one position differs: an unrelieved tip corner bends into contact beyond the path of
    contact (the analysis loads it, the reference cannot), and the TE there is below the
    reference's single-pair value (measured 250 against 267 µrad; 229 before the bodies'
    coupling, which now softens the pair that carries beside the corner)."""
    relief, out, _ = compared
    for model, ref, same in out:
        if same:
            assert model == pytest.approx(ref, rel=0.02)
    corner = [(model, ref) for model, ref, same in out if not same]
    if relief:
        assert not corner
    else:
        assert len(corner) == 1 and corner[0][0] < 0.96 * corner[0][1]


def test_tip_relief_changes_the_loaded_te_as_the_reference_does(compared):
    """Peak to peak over the positions compared within 2 % of the reference's (measured
    85.9/86.4 µrad without relief, 88.0/88.6 with 20 µm, 93.5/94.1 with 40 µm; before the
    bodies' coupling softened the two-pair zone, 132.8/133.1, 134.8/135.3, 141.7/142.2), and
    as a length (µm) the lag on the gear's base circle; with
    relief the analysis loads a relieved pair at some position that its rigid contact
    leaves out."""
    relief, out, result = compared
    rows, summary = result.sections["positions"], result.sections["summary"]
    # as a length: the gear's lag on its base circle, the approach along the line of action
    rb2 = gear_pair(parse_case(case(relief))).gear.base_radius
    assert summary["transmission_error_arm_mm"] == pytest.approx(rb2, rel=1e-12)
    for row in rows:
        assert row["loaded_transmission_error_um"] == pytest.approx(
            1e-3 * rb2 * row["loaded_transmission_error_urad"], rel=1e-12)
    assert summary["loaded_transmission_error_peak_to_peak_um"] == pytest.approx(
        1e-3 * rb2 * summary["loaded_transmission_error_peak_to_peak_urad"], rel=1e-12)
    model = [m for m, _, same in out if same]
    ref = [r for _, r, same in out if same]
    assert np.ptp(model) == pytest.approx(np.ptp(ref), rel=0.02)
    if relief:
        beyond = [r for r in result.sections["positions"]
                  if not r["rigid_contact"] and r["bem_load_N"] > 0]
        assert beyond
