"""Worm efficiency: seed 000 Table 3.5-1 and seed 001's equations."""

import math

import pytest

from toothcontact.analytic import worm_efficiency as w
from toothcontact.runner import analyse_file, bundled_cases_dir

GAMMA = math.radians(4.1)
# Seed 000 Table 3.5-1: temperature, eta_tot, eta_spindle, eta_z, mu_zm, mu_0T, viscosity, Y_VISC
TABLE = [(-50, 0.325, 0.730, 0.441, 0.090, 0.069, 30000, 1.46),
         (-35, 0.365, 0.780, 0.468, 0.081, 0.062, 5000, 1.31),
         (-20, 0.442, 0.806, 0.516, 0.067, 0.051, 1020, 1.08),
         (-5, 0.473, 0.890, 0.532, 0.063, 0.048, 310, 1.01),
         (25, 0.477, 0.900, 0.534, 0.062, 0.047, 57, 1.00),
         (70, 0.484, 0.900, 0.538, 0.061, 0.047, 11, 1.00)]


@pytest.mark.parametrize("row", TABLE)
def test_din3996_efficiency_reproduces_table_3_5_1(row):
    """eta_z = tan(gm)/tan(gm + atan(mu_zm)) with the table's mu_zm gives its eta_z to the
    ±0.0025 the seeds README finds in every column."""
    _, _, _, eta_z, mu_zm, *_ = row
    assert w.efficiency_worm_driving(GAMMA, mu_zm) == pytest.approx(eta_z, abs=0.0025)


@pytest.mark.parametrize("row", TABLE)
def test_viscosity_factor_at_the_table_points(row):
    *_, mu_0T, viscosity, Y_VISC = row
    assert w.viscosity_factor(viscosity) == pytest.approx(Y_VISC, abs=1e-12)
    assert 0.047 * Y_VISC == pytest.approx(mu_0T, abs=0.0006)  # mu_0T = 0.047·Y_VISC to rounding


def test_viscosity_factor_between_below_and_above_the_table():
    geometric_mean = math.sqrt(1020 * 5000)
    assert w.viscosity_factor(geometric_mean) == pytest.approx(0.5 * (1.08 + 1.31), rel=1e-12)
    assert w.viscosity_factor(5.0) == 1.0
    with pytest.warns(UserWarning, match="held at 1.46"):
        assert w.viscosity_factor(50000.0) == 1.46


def test_kim_eq2_is_din_with_effective_friction_angle():
    for gamma_deg, alpha_deg, mu in [(4.1, 20, 0.06), (10, 14.5, 0.029), (25, 25, 0.1)]:
        g, a = math.radians(gamma_deg), math.radians(alpha_deg)
        assert w.efficiency_kim(g, a, mu) == pytest.approx(
            w.efficiency_worm_driving(g, mu / math.cos(a)), rel=1e-13)


def test_kim_eq3_normal_load_is_the_force_triangle():
    """F_n = F_t2 / (cos alpha_n·cos gamma): the wheel tangential force resolved into the
    normal of a flank with normal pressure angle alpha_n and lead angle gamma."""
    g, a, T, Rp = math.radians(10.0), math.radians(20.0), 19670.0, 35.5
    assert w.normal_tooth_load(T, Rp, g, a) == pytest.approx(T / Rp / (math.cos(a) * math.cos(g)),
                                                             rel=1e-13)


def test_wheel_driving_efficiency_and_self_locking():
    assert w.efficiency_wheel_driving(GAMMA, 0.090) < 0  # mu > tan(gamma): self-locking
    mu = 0.03
    expected = math.tan(GAMMA - math.atan(mu)) / math.tan(GAMMA)
    assert w.efficiency_wheel_driving(GAMMA, mu) == pytest.approx(expected, rel=1e-14)


def test_lead_angle_from_pitch_diameter_round_trip():
    z1, mn, gamma = 2, 1.75, math.radians(10.0)
    d1 = z1 * (mn / math.cos(gamma)) / math.tan(gamma)  # d1 = z1·mx / tan(gamma)
    assert w.lead_angle_from_pitch_diameter(z1, mn, d1) == pytest.approx(gamma, rel=1e-13)


def test_saba_case_flags_only_the_minus_20_column():
    """The -20 °C column of Table 3.5-1 breaks eta_tot = eta_z·eta_spindle (0.416 vs 0.442);
    the case must say so and find every other column consistent."""
    doc = analyse_file(bundled_cases_dir() / "worm_saba_flap_actuator.toml")
    failed = [c["name"] for c in doc["checks"] if not c["ok"]]
    assert failed == ["published eta_tot at -20 °C equals eta_z·eta_spindle"]
    rows = {r["temperature_C"]: r for r in doc["efficiency"]}
    assert rows[-50.0]["self_locking"] and not rows[70.0]["self_locking"]
    assert rows[70.0]["eta_z"] == pytest.approx(0.538, abs=0.005)


def test_kim_case_ars_misalignment_matches_the_reported_points():
    """Seed 001 §2.4.1: -1.10 mm at 0 N·m and 0 at 19.67 N·m with a 30 N/mm spring (the
    case's lever arms are chosen for this, so this checks eqs (20)-(21) as implemented)."""
    doc = analyse_file(bundled_cases_dir() / "worm_kim_steering_ars.toml")
    rows = {r["output_torque_Nm"]: r for r in doc["misalignment"]}
    assert rows[0.0]["misalignment_mm"] == pytest.approx(-1.10, abs=0.005)
    assert rows[19.67]["misalignment_mm"] == pytest.approx(0.0, abs=0.005)
    torques = sorted(rows)
    slopes = {(rows[b]["misalignment_mm"] - rows[a]["misalignment_mm"]) / (b - a)
              for a, b in zip(torques, torques[1:])}
    assert max(slopes) - min(slopes) < 1e-9  # eq (21) is linear in the torque


def test_friction_law_passes_the_measured_point_with_the_sliding_exponent():
    """Seed 001 §2.4.1: mu = c·p^n, n = -0.9 (sliding), through 0.029 at 130 MPa."""
    mu = lambda p: w.friction_power_law(p, 0.029, 130.0, -0.9)  # noqa: E731
    assert mu(130.0) == pytest.approx(0.029, rel=1e-12)
    assert mu(260.0) / mu(130.0) == pytest.approx(2.0 ** -0.9, rel=1e-12)


def test_kim_pressure_is_the_force_over_eq_18_area():
    """Seed 001 eq (19) is the force over eq (18)'s area A = π{(3/4)C_E}^(2/3)
    (R_eq1 R_eq2)^(1/3) (F/3)^(2/3): P·A = F for any force."""
    radii = w.kim_curvature_radii(10.0, 8.5, 11.0, math.radians(10.0), 35.0, math.radians(20.0))
    R1, _, R3, R4 = radii
    C_E = 0.91 / 206e3 + 0.84 / 3000.0
    for F in (10.0, 600.0, 1400.0):
        area = math.pi * (0.75 * C_E) ** (2 / 3) * (R1 * R3 / (R3 - R1) * R4) ** (1 / 3) * (F / 3) ** (2 / 3)
        assert w.kim_contact_pressure(F, radii, C_E) * area == pytest.approx(F, rel=1e-12)


def test_kim_case_efficiency_with_and_without_the_spring():
    """The bundled Kim case: the spring's preload costs efficiency most at low torque, and
    nothing where the shaft is aligned (19.67 N·m, zero spring force: the paper's 'the
    difference becomes zero when the misalignment is zero')."""
    rows = analyse_file(bundled_cases_dir() / "worm_kim_steering_ars.toml")["misalignment"]
    loaded = [r for r in rows if r["output_torque_Nm"] > 0]
    gap = [r["eta_kim_aligned"] - r["eta_kim"] for r in loaded]
    aligned = next(r for r in loaded if r["output_torque_Nm"] == pytest.approx(19.67))
    assert aligned["eta_kim"] == pytest.approx(aligned["eta_kim_aligned"], abs=1e-6)
    below = [g for r, g in zip(loaded, gap) if r["output_torque_Nm"] < 19.67]
    assert all(g > 0 for g in below) and below == sorted(below, reverse=True)


KIM = bundled_cases_dir() / "worm_kim_steering_ars.toml"

#: seed 001's printed numbers and the checks that hold the case to them
KIM_CHECKS = {"the spring rate k of eq (21) is the paper's": ("eq (21)", "30 N/mm"),
              "misalignment at no output torque matches the paper's": ("eqs (20)-(21)", "-1.1 mm"),
              "output torque where the shaft is aligned matches the paper's":
              ("eq (20)", "19.67 N·m"),
              "friction at 130 MPa matches the paper's": ("§2.3", "0.029"),
              "efficiency at 36 N·m matches the paper's": ("eq (2)", "0.931")}


def test_kim_case_checks_eqs_20_21_and_the_printed_numbers():
    """The README promises the Kim case checks eqs 20-21 against the paper: each printed
    number (spring rate, -1.10 mm at 0 N·m, aligned at 19.67 N·m, 0.029 at 130 MPa, the
    measured 93.10 % at 36 N·m) is a source check naming its equation, the computed and
    the published number and a tolerance; all agree."""
    checks = {c["name"]: c for c in analyse_file(KIM)["checks"]}
    assert set(checks) == set(KIM_CHECKS)
    for name, (equation, published) in KIM_CHECKS.items():
        check = checks[name]
        assert check["ok"] and check["kind"] == "source", check
        assert equation in check["detail"] and f"published {published}" in check["detail"]
        assert "tolerance ±" in check["detail"]
    details = " ".join(c["detail"] for c in checks.values())
    assert "computed -1.1000 mm" in details and "computed 19.670 N·m" in details


@pytest.mark.parametrize("field, value, failing", [
    ("published_misalignment_at_no_torque", "-1.20 mm",
     "misalignment at no output torque matches the paper's"),
    ("published_aligned_torque", "19.7 N*m",
     "output torque where the shaft is aligned matches the paper's"),
    ("published_stiffness", "31 N/mm", "the spring rate k of eq (21) is the paper's"),
])
def test_a_kim_check_fails_when_its_published_number_is_altered(tmp_path, field, value, failing):
    """Each check compares: a published number moved past its tolerance (0.005 mm, 0.005 N·m,
    0.5 N/mm) fails that check alone."""
    import tomllib

    import tomli_w

    raw = tomllib.loads(KIM.read_text())
    raw["anti_rattle_spring"][field] = value
    case = tmp_path / "kim_altered.toml"
    case.write_text(tomli_w.dumps(raw))
    failed = [c["name"] for c in analyse_file(case)["checks"] if not c["ok"]]
    assert failed == [failing]


def test_kim_friction_and_efficiency_checks_fail_when_altered(tmp_path):
    import tomllib

    import tomli_w

    raw = tomllib.loads(KIM.read_text())
    raw["contact"]["published_friction"] = {"mu": 0.031, "pressure": "130 MPa"}
    raw["contact"]["published_efficiency"] = [{"output_torque": "36 N*m", "eta": 0.95}]
    case = tmp_path / "kim_altered.toml"
    case.write_text(tomli_w.dumps(raw))
    failed = {c["name"] for c in analyse_file(case)["checks"] if not c["ok"]}
    assert failed == {"friction at 130 MPa matches the paper's",
                      "efficiency at 36 N·m matches the paper's"}


def test_kim_aligned_torque_is_eq_20_at_no_spring_force():
    """The torque where the shaft is aligned zeroes eq (20) (and so eq 21)."""
    g, a, Rp = math.radians(10.08), math.radians(20.0), 35.55
    T0 = w.anti_rattle_aligned_torque(4091.0, 20.0, Rp, a, g)
    assert w.anti_rattle_spring_force(T0, 4091.0, 103.97, 20.0, Rp, a, g) == pytest.approx(
        0.0, abs=1e-12)
    section = analyse_file(KIM)["anti_rattle_spring"]
    assert section["aligned_torque_Nm"] == pytest.approx(19.67, abs=0.005)
    assert section["misalignment_at_no_torque_mm"] == pytest.approx(-1.10, abs=0.005)


def test_kim_key_results_range_over_the_output_torques():
    """The Kim case's conditions are its output torques: the key results name them, with
    units, for the efficiency, the spring force, the misalignment, the aligned torque, the
    pressure and the friction; no empty placeholder ('( to °C)', '0.8553 to 0.8553')."""
    from toothcontact.views.report_view import key_results

    results = {k.label: k for k in key_results(analyse_file(KIM))}
    text = " | ".join(f"{k.label} {k.value} {k.where}" for k in results.values())
    assert "( to" not in text and "°C" not in text and "conditions" not in text
    assert not any(" to " in k.value and k.value.split(" to ")[0] == k.value.split(" to ")[1]
                   for k in results.values())
    assert results["anti-rattle spring force (eq 20)"].value == "-33 to 42.5 N"
    assert results["worm-shaft misalignment (eq 21)"].value == "-1.1 to 1.417 mm"
    assert results["output torque where the shaft is aligned"].value == "19.67 N·m"
    assert results["contact pressure with the spring (eq 19)"].value.endswith(" MPa")
    friction = results["friction coefficient μ with the spring"]
    assert "μ = 0.029·(p / 130 MPa)^-0.9" in friction.where
    spring = results["efficiency with the spring (eq 2, μ from eq 19's pressure)"]
    assert spring.value == "0.6921 to 0.9307"
    assert "over 9 output torques, 0.5 to 45 N·m" in spring.where
    for label in ("anti-rattle spring force (eq 20)", "worm-shaft misalignment (eq 21)",
                  "contact pressure with the spring (eq 19)"):
        assert "over 10 output torques, 0 to 45 N·m" in results[label].where


def test_saba_key_results_still_range_over_temperatures():
    from toothcontact.views.report_view import key_results

    doc = analyse_file(bundled_cases_dir() / "worm_saba_flap_actuator.toml")
    results = {k.label: k for k in key_results(doc)}
    assert results["efficiency eta_z (worm driving, DIN 3996)"].value == "0.4427 to 0.5375"
    assert results["efficiency eta_z (worm driving, DIN 3996)"].where == \
        "over 6 lubricant temperatures, -50 to 70 °C"
    assert results["self-locking (wheel driving)"].where.startswith("at -50, -35 °C of 6")


def test_kim_report_rounds_its_figures():
    """No figure of the Kim report in exponent notation: the misalignment at 19.67 N·m
    (6.8e-06 mm, the mount moment's last digit) shows as 0 beside -1.1 to 1.417 mm, and the
    spring force there as 0 N; the same in report.md and report.html."""
    import re

    from toothcontact.views import report

    doc = analyse_file(KIM)
    for text in (report.markdown(doc), report.html(doc)):
        body = text.split("Inputs (as given)")[0]
        assert not re.findall(r"\d(?:\.\d+)?e[-+]?\d", body)
    row = next(line for line in report.markdown(doc).splitlines()
               if line.startswith("| 19.67 |"))
    assert row.split(" | ")[2:4] == ["0", "0"]
