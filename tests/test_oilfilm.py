"""Oil-film main bearings: the short-bearing coefficients against independent evidence, the
``[bearings]`` oil-film input, and f1 in bearings against the bearing stiffness."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from fetorsion.description import oilfilm

PI = math.pi
RPM = PI / 30  # rad/s per rpm

# A passenger-car main bearing: 58 mm journal, 20 mm wide, 30 µm radial clearance, SAE 10W-40
# near 100 °C (0.01 Pa·s), 6000 rpm, 5 kN.
CAR = dict(load=5000.0, speed=6000 * RPM, diameter=0.058, width=0.020, clearance=30e-6, viscosity=0.01)
# [Friswell] Example 5.5.1: D = 100 mm, L = 30 mm, c = 0.1 mm, μ = 0.1 Pa·s, 1500 rpm, W = 525 N.
FRISWELL = dict(load=525.0, speed=1500 * RPM, diameter=0.1, width=0.03, clearance=1e-4, viscosity=0.1)


# ---------------------------------------------------------------------------------------------
# (a) a hand evaluation: the quartic's root by numpy, the coefficients typed out with plain math


def hand_coefficients(load, speed, diameter, width, clearance, viscosity):
    """ε from the quartic in ε² (numpy's polynomial roots, not the bracketing of the package),
    then K and C from [Friswell]'s dimensionless coefficients, written out term by term."""
    s = diameter * speed * viscosity * width**3 / (8 * load * clearance**2)
    roots = np.roots([1.0, -4.0, 6.0 - s * s * (16 - PI**2), -(4.0 + PI**2 * s * s), 1.0])
    x = [r.real for r in roots if abs(r.imag) < 1e-12 and 0 < r.real < 1]
    assert len(x) == 1
    e = math.sqrt(x[0])
    h0 = 1 / (PI**2 * (1 - e**2) + 16 * e**2) ** 1.5
    kuu = 4 * h0 * (PI**2 * (2 - e**2) + 16 * e**2)
    kuv = h0 * PI * (PI**2 * (1 - e**2) ** 2 - 16 * e**4) / (e * math.sqrt(1 - e**2))
    kvu = -h0 * PI * (PI**2 * (1 - e**2) * (1 + 2 * e**2) + 32 * e**2 * (1 + e**2)) / (e * math.sqrt(1 - e**2))
    kvv = 4 * h0 * (PI**2 * (1 + 2 * e**2) + 32 * e**2 * (1 + e**2) / (1 - e**2))
    cuu = 2 * PI * h0 * math.sqrt(1 - e**2) * (PI**2 * (1 + 2 * e**2) - 16 * e**2) / e
    cuv = -8 * h0 * (PI**2 * (1 + 2 * e**2) - 16 * e**2)
    cvv = 2 * PI * h0 * (PI**2 * (1 - e**2) ** 2 + 48 * e**2) / (e * math.sqrt(1 - e**2))
    k, c = load / clearance, load / (clearance * speed)
    return e, k * np.array([[kuu, kuv], [kvu, kvv]]), c * np.array([[cuu, cuv], [cuv, cvv]])


@pytest.mark.parametrize("case", [CAR, FRISWELL], ids=["car", "friswell"])
def test_closed_form_equals_a_hand_evaluation(case):
    film = oilfilm.film_coefficients(**case)
    e, K, C = hand_coefficients(**case)
    assert film.eccentricity == pytest.approx(e, rel=1e-9)
    np.testing.assert_allclose(film.stiffness, K, rtol=1e-9)
    np.testing.assert_allclose(film.damping, C, rtol=1e-9)


def test_friswell_example_5_5_1():
    # the book's printed values, four significant figures: half a unit in the last place
    film = oilfilm.film_coefficients(**FRISWELL)
    np.testing.assert_allclose(film.stiffness / 1e6, [[12.81, 16.39], [-25.06, 8.815]], rtol=5e-4)
    np.testing.assert_allclose(film.damping / 1e3, [[232.9, -81.92], [-81.92, 294.9]], rtol=5e-4)


# ---------------------------------------------------------------------------------------------
# (b) the film force integrated from the short-bearing pressure, and its finite differences


def film_force(y, z, vy, vz, *, speed, diameter, width, clearance, viscosity, **_):
    """Force (N) of the oil on the journal, centre at (y, z) m moving at (vy, vz) m/s, the
    journal turning at ``speed`` from +y towards +z in a fixed bush.

    θ is fixed to the bush, from +y towards +z; the film is h = c − y cos θ − z sin θ. The
    short-bearing Reynolds equation ∂/∂x(h³ ∂p/∂x) = 6μΩ ∂h/∂θ + 12μ ∂h/∂t with p = 0 at the
    edges x = ±L/2 gives p = (3μ/h³)(L²/4 − x²) g(θ), g = −(Ω ∂h/∂θ + 2 ∂h/∂t); the oil carries
    no tension (p ≥ 0), so the force −∫∫ p (cos θ, sin θ) R dθ dx runs over g > 0 only. Across
    the width it integrates to L³/6; round the journal g = A sin θ + B cos θ is positive on one
    half turn, found exactly, and quad integrates the smooth integrand there.
    """
    R, mu, c = diameter / 2, viscosity, clearance
    A, B = -speed * y + 2 * vz, speed * z + 2 * vy  # g(θ) = A sin θ + B cos θ
    start = math.atan2(-B, A)  # g = r sin(θ − start): positive on (start, start + π)

    tol = 1e-13 * math.hypot(A, B) / c**3  # absolute: a component near zero has no relative accuracy

    def part(trig):
        return quad(lambda t: (A * math.sin(t) + B * math.cos(t)) * trig(t) / (c - y * math.cos(t) - z * math.sin(t)) ** 3,
                    start, start + PI, epsabs=tol, epsrel=1e-12, limit=200)[0]

    scale = -3 * mu * R * width**3 / 6
    return scale * np.array([part(math.cos), part(math.sin)])


def equilibrium(film, load_angle, clearance):
    """Journal centre (m) under a load at ``load_angle``: ε c from the bush centre, the line of
    centres the attitude angle on from the load, in the turning sense."""
    a = load_angle + film.attitude
    return film.eccentricity * clearance * np.array([math.cos(a), math.sin(a)])


@pytest.mark.parametrize("load", [20.0, 525.0, 5000.0, 30000.0])
@pytest.mark.parametrize("load_angle", [-PI / 2, 0.7])
def test_coefficients_are_the_derivatives_of_the_film_force(load, load_angle):
    """K = −∂f/∂x and C = −∂f/∂ẋ by central differences of the integrated film force, at the
    static position the closed form gives, in the crank's y, z for a load at ``load_angle``;
    the equilibrium itself checks ε and the attitude angle."""
    case = dict(CAR, load=load)
    film = oilfilm.film_coefficients(**case)
    c, w = case["clearance"], case["speed"]
    y0, z0 = equilibrium(film, load_angle, c)
    f0 = film_force(y0, z0, 0.0, 0.0, **case)
    applied = load * np.array([math.cos(load_angle), math.sin(load_angle)])
    np.testing.assert_allclose(f0, -applied, atol=1e-9 * load)

    h = 1e-5 * c  # truncation ~h², round-off ~1e-12/h relative: both below 1e-8 here
    K, C = np.zeros((2, 2)), np.zeros((2, 2))
    for j in range(2):
        d = np.eye(2)[j] * h
        K[:, j] = -(film_force(y0 + d[0], z0 + d[1], 0, 0, **case) - film_force(y0 - d[0], z0 - d[1], 0, 0, **case)) / (2 * h)
        v = d * w
        C[:, j] = -(film_force(y0, z0, *v, **case) - film_force(y0, z0, *-v, **case)) / (2 * h * w)
    Kc, Cc = oilfilm.in_crank_axes(film.stiffness, load_angle), oilfilm.in_crank_axes(film.damping, load_angle)
    k_err = np.abs(K - Kc).max() / np.abs(Kc).max()
    c_err = np.abs(C - Cc).max() / np.abs(Cc).max()
    assert k_err < 1e-6 and c_err < 1e-6, (k_err, c_err)


def test_light_and_heavy_load_limits():
    # Light load (S_s → ∞): ε → 1/(π S_s), the direct stiffness vanishes and the cross-coupled
    # one tends to π μ Ω R L³ / (4 c³), what an unloaded, centred journal feels when pushed aside.
    case = dict(CAR, load=1e-3)
    film = oilfilm.film_coefficients(**case)
    s = oilfilm.modified_sommerfeld(**case)
    assert film.eccentricity == pytest.approx(1 / (PI * s), rel=1e-6)
    assert film.attitude == pytest.approx(PI / 2 - 4 * film.eccentricity / PI, rel=1e-9)
    mu, w, R, L, c = case["viscosity"], case["speed"], case["diameter"] / 2, case["width"], case["clearance"]
    cross = PI * mu * w * R * L**3 / (4 * c**3)
    assert film.stiffness[0, 1] == pytest.approx(cross, rel=1e-6)
    assert film.stiffness[1, 0] == pytest.approx(-cross, rel=1e-6)
    assert abs(film.stiffness[0, 0]) + abs(film.stiffness[1, 1]) < 1e-5 * cross
    # Heavy load (S_s → 0): the journal nears the bush, 1 − ε² → 2 √S_s, and the line of
    # centres turns onto the load, φ → (π/4) √(2 √S_s)
    heavy = dict(CAR, load=1e9)
    s = oilfilm.modified_sommerfeld(**heavy)
    e = oilfilm.film_coefficients(**heavy).eccentricity
    assert 1 - e * e == pytest.approx(2 * math.sqrt(s), rel=1e-3)
    assert oilfilm.attitude_angle(e) == pytest.approx(PI / 4 * math.sqrt(2 * math.sqrt(s)), rel=1e-3)


def test_isotropic_equivalent_is_the_same_for_every_load_direction():
    film = oilfilm.film_coefficients(**CAR)
    k, c = oilfilm.isotropic_equivalent(film.stiffness, film.damping)
    assert k == pytest.approx(0.5 * (film.stiffness[0, 0] + film.stiffness[1, 1]), rel=1e-15)
    for angle in np.linspace(0, 2 * PI, 7):
        k2, c2 = oilfilm.isotropic_equivalent(oilfilm.in_crank_axes(film.stiffness, angle),
                                              oilfilm.in_crank_axes(film.damping, angle))
        assert (k2, c2) == pytest.approx((k, c), rel=1e-12)
    # the stiffer the load, the stiffer the film (at this speed): ε rises, and K with W / c
    loads = [500.0, 2000.0, 5000.0, 20000.0]
    ks = [oilfilm.isotropic_equivalent(*(lambda f: (f.stiffness, f.damping))(oilfilm.film_coefficients(**dict(CAR, load=w))))[0]
          for w in loads]
    assert np.all(np.diff(ks) > 0)


# ---------------------------------------------------------------------------------------------
# [bearings] as an oil film


def with_film(raw, **film):
    raw = dict(raw)
    raw["bearings"] = film
    return raw


def test_oil_film_input_gives_the_isotropic_equivalents(renault_raw):
    from fetorsion.description.crank import parse_crank

    loads = [3000.0, 5000.0, 5000.0, 5000.0, 3000.0]
    crank = parse_crank(with_film(renault_raw, clearance=0.030, oil_viscosity_pa_s=0.01, load_n=loads, width=20.0),
                        "x.toml")
    b = crank.main_bearings
    top = renault_raw["excitation"]["speed_range_rpm"][1]  # no speed_rpm: the top of the range
    assert b.oil_film.speed == pytest.approx(top * RPM)
    for j, journal in enumerate(crank.journals):
        e, K, C = hand_coefficients(loads[j], top * RPM, journal.diameter, 0.020, 30e-6, 0.01)
        assert b.oil_film.eccentricity[j] == pytest.approx(e, rel=1e-9)
        assert b.radial_stiffness[j] == pytest.approx(0.5 * (K[0, 0] + K[1, 1]), rel=1e-9)
        assert b.radial_damping[j] == pytest.approx(0.5 * (C[0, 0] + C[1, 1]), rel=1e-9)
    assert not b.rigid and b.oil_film.clearance == (30e-6,) * 5 and b.oil_film.load == tuple(loads)
    # a stated speed wins over the range; no [excitation] needs one
    slow = parse_crank(with_film(renault_raw, clearance=0.030, oil_viscosity_pa_s=0.01, load_n=5000.0,
                                 speed_rpm=2000.0), "x.toml").main_bearings
    assert slow.oil_film.speed == pytest.approx(2000 * RPM)
    assert slow.oil_film.eccentricity[0] > b.oil_film.eccentricity[1]  # slower: the journal sinks


# ---------------------------------------------------------------------------------------------
# f1 in bearings between the free-free and the rigid-bearing value


@pytest.fixture(scope="module")
def reduced_shaft():
    """A 1 m × 50 mm steel shaft condensed to its two end faces (as tests/test_condensed.py's
    shaft, on a coarser mesh: the test compares the model with itself)."""
    from fetorsion.fe import assembly
    from fetorsion.fe import substructure as ss
    from fetorsion.fe.couplings import Master, coupling_matrix
    from fetorsion.fe.modal import default_shift
    from fetorsion.fe.tetmesh import cylinder_mesh
    from fetorsion.description.model import Material

    steel = Material(210e9, 0.3, 7850.0, "steel")
    length, diameter = 1.0, 0.05
    mesh = cylinder_mesh(length, diameter, diameter / 2)
    m, dof_of_node = assembly.skfem_mesh(mesh)
    b = assembly.p2_basis(m)
    pat = assembly.block_pattern(b)
    K, M = assembly.stiffness(b, steel.youngs_modulus, steel.poisson_ratio, pat), assembly.mass(b, steel.density, pat)
    masters = [Master("front", np.zeros(3), mesh.node_sets["front_face"]),
               Master("rear", np.array([length, 0.0, 0.0]), mesh.node_sets["rear_face"])]
    itf = ss.interface(K, M, coupling_matrix(masters, dof_of_node, m.doflocs.T), default_shift(mesh, steel))
    along_y = np.zeros(M.shape[0])
    along_y[1::3] = 1.0  # the whole shaft moved 1 m along y (DOF 3n + d: node n, direction d)
    return ss.craig_bampton(itf), along_y @ (M @ along_y)


@pytest.mark.fe
def test_f1_in_bearings_rises_from_free_free_to_rigid(reduced_shaft):
    """Radial bearings at both ends of the shaft, isotropic stiffness k on each end master's y and z
    (as fetorsion.fe.condensed.bearing_matrices): k = 0 is the free-free shaft, k = ∞ holds those
    DOF. The shaft's torsion does not feel radial bearings, so the mode tracked is the first one
    the bearings carry, the first bending mode in bearings (sorted index 2, after the rigid twist
    and axial motion no radial bearing restrains): k = 0 gives its free-free value, a rigid-body
    lateral mode at 0 Hz, k = ∞ the pinned-pinned first bending mode. Adding a stiffness never
    lowers an eigenvalue (Rayleigh), so every sorted frequency rises monotonically with k; the
    first free-free elastic mode's index (6, after six rigid-body modes) is checked too, from
    free-free bending (~230 Hz) to its value with rigid bearings. A passenger-car film
    (:data:`CAR`) sits between the limits.
    """
    from fetorsion.fe import substructure as ss

    red, mass = reduced_shaft
    radial = [1, 2, 7, 8]  # y, z of the front and the rear master
    k_film = oilfilm.isotropic_equivalent(*(lambda f: (f.stiffness, f.damping))(oilfilm.film_coefficients(**CAR)))[0]
    ks = [0.0, *np.logspace(2, 12, 11), k_film, math.inf]
    ks.sort()
    f = []
    for k in ks:
        Dk = np.zeros((red.n_master_dofs, red.n_master_dofs))
        held = radial if math.isinf(k) else []
        if not math.isinf(k):
            Dk[radial, radial] = k
        w2, _, _ = ss.reduced_modes(red, Dk, held=held)
        f.append(np.sqrt(np.abs(w2[:10])) / (2 * PI))
    f = np.array(f)  # (stiffness, mode)
    # monotone in k, every mode, to the eigen-solver's round-off: relative 1e-7 on the elastic
    # modes, and a few mHz on the zero ones (ω² to ε_machine ‖K‖/m ≈ 1e-16 · 1e12 / 15 s⁻²)
    assert np.all(np.diff(f, axis=0) >= -(1e-7 * f[-1] + 1e-2)), np.diff(f, axis=0).min()
    # the first bending mode in bearings: 0 Hz free-free (a rigid mode), the pinned-pinned value
    # held; on soft springs it is the rigid shaft bouncing, √(2k/m)/2π (the shaft's own bending
    # stiffness, ~1e7 N/m, is 1e5 times the 1e2 N/m spring: the rigid value to ~1e-5)
    free, soft, stiff, held = f[0, 2], f[1, 2], f[-2, 2], f[-1, 2]
    assert free < 1e-3
    assert soft == pytest.approx(math.sqrt(2 * ks[1] / mass) / (2 * PI), rel=1e-4)
    # 1e12 N/m is 1e5 times the shaft's lateral stiffness: within ~1e-5 of the held value
    assert stiff == pytest.approx(held, rel=1e-4)
    assert 90 < held < 110  # a 1 m × 50 mm steel shaft pinned-pinned: ~101 Hz (Euler–Bernoulli)
    # the first free-free elastic mode: index 6 free-free (six rigid-body modes below it)
    assert f[1, 6] == pytest.approx(f[0, 6], rel=1e-4) and f[-2, 6] == pytest.approx(f[-1, 6], rel=1e-4)
    assert f[-1, 6] > f[0, 6] > 200
    # the film: between the limits, nearly rigid for this shaft (700 MN/m against ~10 MN/m)
    i = ks.index(k_film)
    assert f[0, 2] < f[i, 2] <= f[-1, 2] and f[i, 2] == pytest.approx(held, rel=1e-2)


# ---------------------------------------------------------------------------------------------
# oil films at each journal's mean load from the crank's own forces


@pytest.fixture(scope="module")
def condensed_with_film():
    """The Renault 21 (no fillets, 30 mm) with oil-film mains and no stated loads."""
    from conftest import plain

    from fetorsion.description.crank import parse_crank
    from fetorsion.fe.condensed import run_condensed

    raw = plain("renault21.toml").raw
    crank = parse_crank(with_film(raw, clearance=0.030, oil_viscosity_pa_s=0.01), "x.toml")
    return run_condensed(crank, 0.03)


@pytest.mark.fe
def test_mean_journal_loads_balance_the_mean_pin_forces(condensed_with_film):
    """Statics, at every crank angle: the bearings carry what the pins are loaded with. So the
    journals' mean loads (fixed frame) add up to the mean of the cylinders' pin forces turned
    into that frame, computed here directly from the slider-crank forces (1e-9 of their size)."""
    from fetorsion.excitation.torque import cycle_angle, cylinder_pin_forces, firing_angles
    from fetorsion.response.coupled import journal_mean_loads

    cc = condensed_with_film
    crank = cc.crank
    rpm = 4000.0
    loads = journal_mean_loads(cc, rpm)
    f = cylinder_pin_forces(crank, rpm)
    theta, period, phi = f["theta"], cycle_angle(crank.engine), firing_angles(crank.engine)
    total = np.zeros(2)
    for c, a in enumerate(crank.engine.crank_angles):
        ft = np.interp(theta - phi[c], theta, f["tangential"], period=period)
        fr = np.interp(theta - phi[c], theta, f["radial"], period=period)
        angle = a - theta  # the pin's direction in the fixed frame (top dead centre at θ = φ_c)
        total += np.mean(np.stack([fr * np.cos(angle) - ft * np.sin(angle), fr * np.sin(angle) + ft * np.cos(angle)]),
                         axis=1)
    scale = np.abs(f["radial"]).max()
    np.testing.assert_allclose(loads.sum(axis=0), total, rtol=0, atol=1e-9 * scale)
    assert np.all(np.hypot(*loads.T) > 0)


@pytest.mark.fe
def test_film_without_stated_loads_takes_the_mean_loads(condensed_with_film):
    """Without load_n the description parses with the film pending (rigid placeholders); the
    condensed crank then carries the short-bearing coefficients at the mean loads, the same as a
    description that states those loads."""
    from fetorsion.description.crank import parse_crank
    from fetorsion.response.coupled import journal_mean_loads, with_film_bearings

    cc = condensed_with_film
    assert cc.crank.main_bearings.oil_film.load is None
    film = with_film_bearings(cc)
    b = film.crank.main_bearings
    top = cc.crank.excitation.speed_range[1]
    expected = np.hypot(*journal_mean_loads(cc, top).T)
    np.testing.assert_allclose(b.oil_film.load, expected, rtol=1e-12)
    stated = parse_crank(with_film(cc.crank.raw, clearance=0.030, oil_viscosity_pa_s=0.01, load_n=list(expected)),
                         "x.toml").main_bearings
    np.testing.assert_allclose(b.radial_stiffness, stated.radial_stiffness, rtol=1e-9)
    np.testing.assert_allclose(b.radial_damping, stated.radial_damping, rtol=1e-9)
    assert all(0 < e < 1 for e in b.oil_film.eccentricity) and len(film.held) < len(cc.held)
    # and the crank in these bearings sits between free-free and rigid
    assert cc.modes("free").first_torsional() < film.modes("bearings").first_torsional() \
        <= cc.modes("bearings").first_torsional() * (1 + 1e-9)


def test_film_without_loads_or_excitation_is_refused_by_name(renault_raw):
    from fetorsion.description.crank import parse_crank
    from fetorsion.errors import FetorsionError

    raw = {k: v for k, v in with_film(renault_raw, clearance=0.030, oil_viscosity_pa_s=0.01, speed_rpm=3000.0).items()
           if k not in ("excitation", "limits", "dampers")}
    with pytest.raises(FetorsionError, match=r"bearings\.load_n.*\[excitation\]"):
        parse_crank(raw, "x.toml")
